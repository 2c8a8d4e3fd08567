// The shared surface model as a path tracer uses it: reciprocity, a pdf that integrates to one and matches
// what sample() draws, and no energy created by the specular lobe of a white metal.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/pathtrace/bsdf.h"

namespace sp::pathtrace {
namespace {

SurfacePoint surface(float roughness, float metallic, Eigen::Vector3f base = {1.0f, 1.0f, 1.0f}) {
    return {Eigen::Vector3f::UnitZ(), base, roughness, metallic};
}

Eigen::Vector3f direction(float theta, float phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

TEST(Bsdf, IsReciprocal) {
    for (float roughness : {0.1f, 0.5f, 1.0f}) {
        const SurfacePoint s = surface(roughness, 0.3f, {0.7f, 0.4f, 0.2f});
        const Eigen::Vector3f a = direction(0.4f, 0.3f), b = direction(1.1f, 2.5f);
        EXPECT_TRUE(evaluate(s, a, b).isApprox(evaluate(s, b, a), 1e-5f)) << roughness;
    }
}

// Monte Carlo with sample(): E[f cos / pdf] is the directional albedo, and E[1 / pdf] over drawn
// directions is the hemisphere's solid angle when the pdf is the density sample() draws with.
struct Estimates {
    double albedo = 0.0;
    double solidAngle = 0.0; // the pdf's integral over the upper hemisphere
    double accepted = 0.0;   // the fraction of draws above the surface
};

Estimates estimate(const SurfacePoint& s, const Eigen::Vector3f& v, int count) {
    std::mt19937 generator(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    Estimates e;
    for (int i = 0; i < count; ++i) {
        Eigen::Vector3f l;
        if (!sample(s, v, uniform(generator), uniform(generator), uniform(generator), l))
            continue;
        e.accepted += 1.0 / count;
        const float p = pdf(s, v, l);
        EXPECT_GT(p, 0.0f);
        e.albedo += double(evaluate(s, v, l).x() * s.n.dot(l) / p) / count;
    }
    // The pdf integrates to one over the hemisphere (uniform directions, 1 / (2 pi) each).
    for (int i = 0; i < count; ++i) {
        const float z = uniform(generator), phi = 6.2831853f * uniform(generator);
        const Eigen::Vector3f l(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi),
                                z);
        e.solidAngle += double(pdf(s, v, l)) * 6.2831853 / count;
    }
    return e;
}

TEST(Bsdf, PdfIsTheDensityOfWhatSampleDraws) {
    // Its integral over the upper hemisphere is the share of draws that land there (a reflected half
    // vector may point below the surface: that draw is lost, and its density with it).
    // (Uniform directions cannot estimate the integral of a nearly mirror-like lobe: rough lobes only.)
    for (float roughness : {0.3f, 0.6f, 1.0f})
        for (float metallic : {0.0f, 0.5f, 1.0f}) {
            const Estimates e = estimate(surface(roughness, metallic), direction(0.5f, 0.0f), 400000);
            EXPECT_NEAR(e.solidAngle, e.accepted, 0.02) << roughness << " " << metallic;
            EXPECT_GT(e.accepted, 0.45) << roughness << " " << metallic;
        }
}

TEST(Bsdf, AWhiteMetalReflectsNoMoreThanItReceives) {
    // White furnace of the specular lobe: a smooth white metal reflects nearly all; rougher ones less and
    // less (single scattering, with the shared model's visibility term), never more.
    const Eigen::Vector3f v = direction(0.3f, 0.0f);
    double previous = estimate(surface(0.05f, 1.0f), v, 200000).albedo;
    EXPECT_NEAR(previous, 1.0, 0.03);
    for (float roughness : {0.25f, 0.5f, 0.75f, 1.0f}) {
        const double albedo = estimate(surface(roughness, 1.0f), v, 200000).albedo;
        EXPECT_LE(albedo, previous + 0.01) << roughness;
        EXPECT_GT(albedo, 0.2) << roughness;
        previous = albedo;
    }
}

TEST(Bsdf, TheDiffuseLobeIsLambertian) {
    // Base colour enters the diffuse lobe linearly: the albedo difference of two dielectric bases is the
    // difference of the bases (the specular lobe, F0 = 0.04, is the same for both).
    const Eigen::Vector3f v = direction(0.7f, 1.0f);
    const double white = estimate(surface(0.5f, 0.0f), v, 400000).albedo;
    const double grey = estimate(surface(0.5f, 0.0f, {0.5f, 0.5f, 0.5f}), v, 400000).albedo;
    EXPECT_NEAR(white - grey, 0.5, 0.01);
}

} // namespace
} // namespace sp::pathtrace
