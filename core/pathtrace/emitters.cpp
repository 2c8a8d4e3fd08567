#include "core/pathtrace/emitters.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/render/luminance.h"

namespace sp::pathtrace {

void Emitters::clear() {
    triangles_.clear();
    cumulative_.clear();
}

void Emitters::add(std::uint32_t shape, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                   const Eigen::Vector3f& c, const Eigen::Vector3f& radiance) {
    const Eigen::Vector3f ab = b - a, ac = c - a;
    const Eigen::Vector3f cross = ab.cross(ac);
    const float area = 0.5f * cross.norm();
    const float power = area * render::luminance(radiance);
    if (!(power > 0.0f) || !std::isfinite(power))
        return;
    triangles_.push_back({a, ab, ac, cross.normalized(), radiance, shape});
    cumulative_.push_back((cumulative_.empty() ? 0.0 : cumulative_.back()) + double(power));
}

EmitterSample Emitters::sample(float u0, float u1, float u2) const {
    const double target = double(u0) * cumulative_.back();
    const std::size_t i = std::min<std::size_t>(
        std::size_t(std::upper_bound(cumulative_.begin(), cumulative_.end(), target) - cumulative_.begin()),
        triangles_.size() - 1);
    const Triangle& t = triangles_[i];
    // Uniform over the triangle: the square root folds the unit square onto it evenly.
    const float r = std::sqrt(u1);
    EmitterSample out;
    out.point = t.a + t.ab * (r * (1.0f - u2)) + t.ac * (r * u2);
    out.normal = t.normal;
    out.radiance = t.radiance;
    out.pdfArea = pdfArea(t.radiance);
    out.shape = t.shape;
    return out;
}

float Emitters::pdfArea(const Eigen::Vector3f& radiance) const {
    return empty() ? 0.0f : float(double(render::luminance(radiance)) / cumulative_.back());
}

} // namespace sp::pathtrace
