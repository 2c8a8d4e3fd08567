#pragma once
// Polylines measured along their length: what the lane graph, its lanes and the drawn road all walk. Pure
// logic.

#include <algorithm>
#include <vector>

#include <Eigen/Core>

namespace sp::zonegraph {

// The arc length at each point, from 0.
inline std::vector<double> arcLengths(const std::vector<Eigen::Vector3d>& points) {
    std::vector<double> s{0.0};
    for (size_t i = 1; i < points.size(); ++i)
        s.push_back(s.back() + (points[i] - points[i - 1]).norm());
    return s;
}

// The point at arc length d (clamped to the polyline; at least two points), `s` its arcLengths.
inline Eigen::Vector3d pointAtArcLength(const std::vector<Eigen::Vector3d>& points,
                                        const std::vector<double>& s, double d) {
    d = std::clamp(d, 0.0, s.back());
    const size_t i = std::clamp<size_t>(std::upper_bound(s.begin(), s.end(), d) - s.begin(), 1, s.size() - 1);
    const double span = s[i] - s[i - 1];
    return points[i - 1] + (span > 0.0 ? (d - s[i - 1]) / span : 0.0) * (points[i] - points[i - 1]);
}

// The parameter in [0, 1] of the point of segment ab nearest p (on the ground or in space).
template <typename Vector> double nearestOnSegment(const Vector& a, const Vector& b, const Vector& p) {
    const Vector ab = b - a;
    const double len2 = ab.squaredNorm();
    return len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
}

} // namespace sp::zonegraph
