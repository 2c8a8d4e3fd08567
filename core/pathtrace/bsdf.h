#pragma once
// The surface model both renderers share (core/render/shaders.cpp): a Lambertian lobe weighted by
// base * (1 - metallic) and a GGX specular lobe (Karis 2013: GGX distribution, Smith-Schlick visibility
// with k = (roughness + 1)^2 / 8, Schlick Fresnel), evaluated, sampled and given a pdf for path tracing.
// Vectors are world-space units; `n` is the shading normal, `v` points away from the surface towards
// the viewer, `l` towards the light. Pure logic.

#include <numbers>

#include <Eigen/Core>

namespace sp::pathtrace {

inline constexpr float kPi = std::numbers::pi_v<float>;

struct SurfacePoint {
    Eigen::Vector3f n;
    Eigen::Vector3f base; // linear base colour
    float roughness = 0.5f;
    float metallic = 0.0f;
};

// The reflectance f(v, l) (1/sr), zero below the surface: diffuse(s) plus the specular lobe.
Eigen::Vector3f evaluate(const SurfacePoint& s, const Eigen::Vector3f& v, const Eigen::Vector3f& l);

// The diffuse lobe alone, base * (1 - metallic) / pi (the same for every pair of directions above).
Eigen::Vector3f diffuse(const SurfacePoint& s);

// The solid-angle density with which sample() picks l.
float pdf(const SurfacePoint& s, const Eigen::Vector3f& v, const Eigen::Vector3f& l);

// A direction l drawn from a mixture of cosine-weighted hemisphere and GGX half-vector sampling, chosen
// from the uniform numbers u0, u1, u2 in [0, 1); returns false when it points below the surface. Each
// strategy gets at least a tenth of the draws, so that the density covers the whole hemisphere even for a
// metal (the diffuse illumination a white surface would receive is estimated from the same paths).
bool sample(const SurfacePoint& s, const Eigen::Vector3f& v, float u0, float u1, float u2,
            Eigen::Vector3f& l);

// The roughness of the lobe sample() draws from with u0: the specular lobe's, or 1 for the diffuse lobe
// (path regularisation: what later surfaces of the path are roughened to).
float sampledRoughness(const SurfacePoint& s, float u0);

// A direction drawn with density cos(theta) / pi about n, from u0, u1 in [0, 1).
Eigen::Vector3f cosineDirection(const Eigen::Vector3f& n, float u0, float u1);

// An orthonormal basis (t, b, n) around unit n (Duff et al. 2017).
void basis(const Eigen::Vector3f& n, Eigen::Vector3f& t, Eigen::Vector3f& b);

} // namespace sp::pathtrace
