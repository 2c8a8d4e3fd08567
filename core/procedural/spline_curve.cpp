#include "core/procedural/spline_curve.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sp::procedural {

namespace {

// 8-point Gauss-Legendre on [-1, 1]; each segment is integrated over 8 sub-intervals of it.
constexpr std::array<double, 8> kNodes{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                       -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                       0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights{0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                         0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                         0.2223810344533745, 0.1012285362903763};
constexpr int kSubIntervals = 8;

} // namespace

void SplineCurve::clear() {
    points_.clear();
    tangents_.clear();
    invalidate();
}

void SplineCurve::addPoint(const Eigen::Vector3d& point) {
    points_.push_back(point);
    tangents_.emplace_back();
    invalidate();
}

void SplineCurve::setPoints(std::vector<Eigen::Vector3d> points) {
    points_ = std::move(points);
    tangents_.assign(points_.size(), std::nullopt);
    invalidate();
}

void SplineCurve::setClosedLoop(bool closed) {
    closed_ = closed;
    invalidate();
}

void SplineCurve::setTangent(int index, std::optional<Eigen::Vector3d> tangent) {
    tangents_[std::size_t(index)] = tangent;
    invalidate();
}

int SplineCurve::segmentCount() const {
    const int n = pointCount();
    return n < 2 ? 0 : closed_ ? n : n - 1;
}

Eigen::Vector3d SplineCurve::tangent(int index) const {
    const int n = pointCount();
    if (const auto& own = tangents_[std::size_t(index)])
        return *own;
    if (n < 2)
        return Eigen::Vector3d::Zero();
    if (closed_)
        return 0.5 * (point((index + 1) % n) - point((index + n - 1) % n));
    if (index == 0)
        return point(1) - point(0);
    if (index == n - 1)
        return point(n - 1) - point(n - 2);
    return 0.5 * (point(index + 1) - point(index - 1));
}

Eigen::Vector3d SplineCurve::location(double key) const {
    const int segments = segmentCount();
    if (segments == 0)
        return pointCount() == 1 ? point(0) : Eigen::Vector3d::Zero();
    key = std::isfinite(key) ? std::clamp(key, 0.0, double(segments)) : 0.0; // never index with NaN
    const int i = std::min(int(key), segments - 1);
    const double t = key - i, t2 = t * t, t3 = t2 * t;
    const int j = (i + 1) % pointCount();
    return (2 * t3 - 3 * t2 + 1) * point(i) + (t3 - 2 * t2 + t) * tangent(i) + (-2 * t3 + 3 * t2) * point(j) +
           (t3 - t2) * tangent(j);
}

Eigen::Vector3d SplineCurve::derivative(double key) const {
    const int segments = segmentCount();
    if (segments == 0)
        return Eigen::Vector3d::Zero();
    key = std::isfinite(key) ? std::clamp(key, 0.0, double(segments)) : 0.0; // never index with NaN
    const int i = std::min(int(key), segments - 1);
    const double t = key - i, t2 = t * t;
    const int j = (i + 1) % pointCount();
    return (6 * t2 - 6 * t) * point(i) + (3 * t2 - 4 * t + 1) * tangent(i) + (-6 * t2 + 6 * t) * point(j) +
           (3 * t2 - 2 * t) * tangent(j);
}

double SplineCurve::segmentLength(int segment, double t) const {
    double length = 0.0;
    const double step = t / kSubIntervals;
    for (int s = 0; s < kSubIntervals; ++s) {
        const double a = s * step, half = step / 2;
        for (std::size_t k = 0; k < kNodes.size(); ++k)
            length += kWeights[k] * half * derivative(segment + a + half * (kNodes[k] + 1.0)).norm();
    }
    return length;
}

void SplineCurve::ensureLengths() const {
    if (!lengths_.empty() || segmentCount() == 0)
        return;
    lengths_.assign(std::size_t(segmentCount()) + 1, 0.0);
    for (int i = 0; i < segmentCount(); ++i)
        lengths_[std::size_t(i) + 1] = lengths_[std::size_t(i)] + segmentLength(i, 1.0);
}

double SplineCurve::length() const {
    ensureLengths();
    return lengths_.empty() ? 0.0 : lengths_.back();
}

double SplineCurve::distanceAtPoint(int index) const {
    ensureLengths();
    return lengths_.empty() ? 0.0 : lengths_[std::size_t(std::min(index, segmentCount()))];
}

double SplineCurve::keyAtDistance(double distance) const {
    ensureLengths();
    if (lengths_.empty())
        return 0.0;
    distance = std::isfinite(distance) ? std::clamp(distance, 0.0, lengths_.back()) : 0.0;
    const auto upper = std::upper_bound(lengths_.begin(), lengths_.end(), distance);
    const int segment = std::clamp(int(upper - lengths_.begin()) - 1, 0, segmentCount() - 1);
    const double within = distance - lengths_[std::size_t(segment)];
    const double segmentTotal = lengths_[std::size_t(segment) + 1] - lengths_[std::size_t(segment)];
    if (segmentTotal <= 0.0)
        return segment;
    // Newton on s(t) = within from the proportional guess; bisection keeps it inside [0, 1].
    double t = within / segmentTotal, low = 0.0, high = 1.0;
    for (int iteration = 0; iteration < 32; ++iteration) {
        const double error = segmentLength(segment, t) - within;
        if (std::abs(error) < 1e-12 * std::max(1.0, segmentTotal))
            break;
        (error > 0 ? high : low) = t;
        const double speed = derivative(segment + t).norm();
        const double next = speed > 0.0 ? t - error / speed : (low + high) / 2;
        t = next > low && next < high ? next : (low + high) / 2;
    }
    return segment + t;
}

} // namespace sp::procedural
