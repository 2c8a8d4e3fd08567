#include "core/pathtrace/bsdf.h"
#include "core/render/luminance.h"

#include <algorithm>
#include <cmath>

namespace sp::pathtrace {
namespace {

Eigen::Vector3f specularColor(const SurfacePoint& s) {
    return Eigen::Vector3f::Constant(0.04f) * (1.0f - s.metallic) + s.base * s.metallic;
}

float alpha(const SurfacePoint& s) {
    return std::max(s.roughness * s.roughness, 0.002f);
}

float dGgx(float noh, float a) {
    const float a2 = a * a;
    const float d = noh * noh * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

// The probability of drawing from the specular lobe: its share of the albedo estimate, within [0.1, 0.9].
float specularProbability(const SurfacePoint& s) {
    const float diffuse = render::luminance(s.base) * (1.0f - s.metallic);
    const float specular = render::luminance(specularColor(s));
    return std::clamp(specular / std::max(specular + diffuse, 1e-6f), 0.1f, 0.9f);
}

} // namespace

void basis(const Eigen::Vector3f& n, Eigen::Vector3f& t, Eigen::Vector3f& b) {
    const float sign = std::copysign(1.0f, n.z());
    const float a = -1.0f / (sign + n.z());
    const float c = n.x() * n.y() * a;
    t = Eigen::Vector3f(1.0f + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
    b = Eigen::Vector3f(c, sign + n.y() * n.y() * a, -n.y());
}

Eigen::Vector3f cosineDirection(const Eigen::Vector3f& n, float u0, float u1) {
    const float r = std::sqrt(u0), phi = 2.0f * kPi * u1;
    Eigen::Vector3f t, b;
    basis(n, t, b);
    return (t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1.0f - u0)))
        .normalized();
}

Eigen::Vector3f evaluate(const SurfacePoint& s, const Eigen::Vector3f& v, const Eigen::Vector3f& l) {
    const float nol = s.n.dot(l), nov = std::max(s.n.dot(v), 1e-4f);
    if (nol <= 0.0f)
        return Eigen::Vector3f::Zero();
    const Eigen::Vector3f h = (v + l).normalized();
    const float noh = std::max(s.n.dot(h), 0.0f), voh = std::max(v.dot(h), 0.0f);
    const float k = (s.roughness + 1.0f) * (s.roughness + 1.0f) / 8.0f;
    const float g = (nol / (nol * (1.0f - k) + k)) * (nov / (nov * (1.0f - k) + k));
    const float m = 1.0f - voh, m5 = m * m * m * m * m;
    const Eigen::Vector3f f0 = specularColor(s);
    const Eigen::Vector3f fresnel = f0 + (Eigen::Vector3f::Ones() - f0) * m5;
    const Eigen::Vector3f specular = fresnel * (dGgx(noh, alpha(s)) * g / (4.0f * nol * nov));
    return diffuse(s) + specular;
}

Eigen::Vector3f diffuse(const SurfacePoint& s) {
    return s.base * ((1.0f - s.metallic) / kPi);
}

float pdf(const SurfacePoint& s, const Eigen::Vector3f& v, const Eigen::Vector3f& l) {
    const float nol = s.n.dot(l);
    if (nol <= 0.0f)
        return 0.0f;
    const Eigen::Vector3f h = (v + l).normalized();
    const float noh = std::max(s.n.dot(h), 0.0f), voh = std::max(v.dot(h), 1e-6f);
    const float ps = specularProbability(s);
    return ps * dGgx(noh, alpha(s)) * noh / (4.0f * voh) + (1.0f - ps) * nol / kPi;
}

float sampledRoughness(const SurfacePoint& s, float u0) {
    return u0 < specularProbability(s) ? s.roughness : 1.0f;
}

bool sample(const SurfacePoint& s, const Eigen::Vector3f& v, float u0, float u1, float u2,
            Eigen::Vector3f& l) {
    if (u0 < specularProbability(s)) {
        // A half vector with density D(h) (n . h), reflected about.
        const float a2 = alpha(s) * alpha(s);
        const float cosTheta = std::sqrt((1.0f - u1) / (1.0f + (a2 - 1.0f) * u1));
        const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta)), phi = 2.0f * kPi * u2;
        Eigen::Vector3f t, b;
        basis(s.n, t, b);
        const Eigen::Vector3f h =
            t * (sinTheta * std::cos(phi)) + b * (sinTheta * std::sin(phi)) + s.n * cosTheta;
        l = 2.0f * v.dot(h) * h - v;
    } else {
        l = cosineDirection(s.n, u1, u2);
    }
    return s.n.dot(l) > 0.0f;
}

} // namespace sp::pathtrace
