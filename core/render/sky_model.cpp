#include "core/render/sky_model.h"

#include <algorithm>
#include <cmath>

#include "core/base/error.h"
#include "core/base/parallel.h"
#include "core/render/luminance.h"

namespace sp::render {
namespace {

// Below the horizon the sky fades to black over this many degrees of sun depression.
constexpr float kTwilightDegrees = 6.0f;

} // namespace

void SkyParameters::validate(const char* function) const {
    SP_CHECK(sunDirection.allFinite() && sunDirection.norm() > 1e-6f, InvalidArgument, function,
             ": the sun's direction must be finite and non-zero, got (", sunDirection.x(), ", ",
             sunDirection.y(), ", ", sunDirection.z(), ")");
    SP_CHECK(sunIrradiance.allFinite() && sunIrradiance.minCoeff() >= 0.0f, InvalidArgument, function,
             ": the sun's colour times intensity must be finite and non-negative, got (", sunIrradiance.x(),
             ", ", sunIrradiance.y(), ", ", sunIrradiance.z(), ")");
    SP_CHECK(turbidity >= PreethamSky::kMinTurbidity && turbidity <= PreethamSky::kMaxTurbidity,
             InvalidArgument, function, ": Turbidity must be in [", PreethamSky::kMinTurbidity, ", ",
             PreethamSky::kMaxTurbidity, "], got ", turbidity);
    SP_CHECK(groundAlbedo.allFinite() && groundAlbedo.minCoeff() >= 0.0f && groundAlbedo.maxCoeff() <= 1.0f,
             InvalidArgument, function, ": GroundAlbedo must be in [0, 1] per channel, got (",
             groundAlbedo.x(), ", ", groundAlbedo.y(), ", ", groundAlbedo.z(), ")");
}

Eigen::Vector3f xyYToLinearSrgb(const Eigen::Vector3f& xyY) {
    const float x = xyY.x(), y = std::max(xyY.y(), 1e-6f), luminance = xyY.z();
    const float X = x * luminance / y, Z = (1.0f - x - y) * luminance / y;
    return Eigen::Vector3f(3.2406f * X - 1.5372f * luminance - 0.4986f * Z,
                           -0.9689f * X + 1.8758f * luminance + 0.0415f * Z,
                           0.0557f * X - 0.2040f * luminance + 1.0570f * Z)
        .cwiseMax(0.0f);
}

PreethamSky::PreethamSky(const SkyParameters& parameters) {
    parameters.validate("PreethamSky");
    const Eigen::Vector3f toSun = -parameters.sunDirection.normalized();
    const float elevation = std::asin(std::clamp(toSun.z(), -1.0f, 1.0f)) * 180.0f / kPi;
    // A sun below the horizon: the sky of a sun on it, faded.
    const float fade = std::clamp(1.0f + elevation / kTwilightDegrees, 0.0f, 1.0f);
    Eigen::Vector3f horizontal(toSun.x(), toSun.y(), 0.0f);
    if (horizontal.norm() < 1e-6f)
        horizontal = Eigen::Vector3f::UnitX();
    toSun_ = toSun.z() >= 0.0f ? toSun : Eigen::Vector3f(horizontal.normalized());
    thetaSun_ = std::acos(std::clamp(toSun_.z(), 0.0f, 1.0f));

    const float T = parameters.turbidity, t = thetaSun_, t2 = t * t, t3 = t2 * t;
    // Zenith luminance (the paper's kcd/m^2, here cd/m^2) and chromaticity (Preetham et al. 1999, appendix
    // A).
    const float chi = (4.0f / 9.0f - T / 120.0f) * (kPi - 2.0f * t);
    zenith_[0] = 1000.0f * ((4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f);
    zenith_[1] = T * T * (0.00166f * t3 - 0.00375f * t2 + 0.00209f * t) +
                 T * (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * t + 0.00394f) +
                 (0.11693f * t3 - 0.21196f * t2 + 0.06052f * t + 0.25886f);
    zenith_[2] = T * T * (0.00275f * t3 - 0.00610f * t2 + 0.00317f * t) +
                 T * (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * t + 0.00516f) +
                 (0.15346f * t3 - 0.26756f * t2 + 0.06670f * t + 0.26688f);
    // The Perez distribution's coefficients A..E for Y, x and y.
    const float fits[3][5][2] = {
        {{0.1787f, -1.4630f},
         {-0.3554f, 0.4275f},
         {-0.0227f, 5.3251f},
         {0.1206f, -2.5771f},
         {-0.0670f, 0.3703f}},
        {{-0.0193f, -0.2592f},
         {-0.0665f, 0.0008f},
         {-0.0004f, 0.2125f},
         {-0.0641f, -0.8989f},
         {-0.0033f, 0.0452f}},
        {{-0.0167f, -0.2608f},
         {-0.0950f, 0.0092f},
         {-0.0079f, 0.2102f},
         {-0.0441f, -1.6537f},
         {-0.0109f, 0.0529f}},
    };
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 5; ++k)
            coefficients_[c][k] = fits[c][k][0] * T + fits[c][k][1];
    for (int c = 0; c < 3; ++c) {
        normalisation_[c] = 1.0f;
        normalisation_[c] = 1.0f / perez(c, 1.0f, thetaSun_); // F(0, theta_sun): the zenith's own value
    }

    // The sun light's luminance sets the scale (its colour tints only the direct light and the ground).
    const float sunLuminance = luminance(parameters.sunIrradiance);
    scale_ = sunLuminance / kSolarIlluminance * fade;

    // The ground: Lambertian, lit by the sun and by the sky's irradiance on a horizontal surface.
    constexpr int kRings = 64, kSegments = 128;
    Eigen::Vector3f skyIrradiance = Eigen::Vector3f::Zero();
    for (int i = 0; i < kRings; ++i) {
        const float theta0 = 0.5f * kPi * float(i) / kRings, theta1 = 0.5f * kPi * float(i + 1) / kRings;
        const float theta = 0.5f * (theta0 + theta1);
        // The ring's projected solid angle (cos theta d omega) per segment.
        const float weight = kPi *
                             (std::sin(theta1) * std::sin(theta1) - std::sin(theta0) * std::sin(theta0)) /
                             float(kSegments);
        for (int j = 0; j < kSegments; ++j) {
            const float phi = 2.0f * kPi * (float(j) + 0.5f) / kSegments;
            const Eigen::Vector3f view(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                       std::cos(theta));
            skyIrradiance += xyYToLinearSrgb(xyY(view)) * (scale_ * weight);
        }
    }
    const Eigen::Vector3f sun = parameters.sunIrradiance * std::max(toSun.z(), 0.0f);
    ground_ = parameters.groundAlbedo.cwiseProduct(sun + skyIrradiance) / kPi;
}

float PreethamSky::perez(int channel, float cosTheta, float gamma) const {
    const float* k = coefficients_[channel];
    const float cosGamma = std::cos(gamma);
    return (1.0f + k[0] * std::exp(k[1] / std::max(cosTheta, 1e-3f))) *
           (1.0f + k[2] * std::exp(k[3] * gamma) + k[4] * cosGamma * cosGamma) * normalisation_[channel];
}

Eigen::Vector3f PreethamSky::xyY(const Eigen::Vector3f& view) const {
    const float cosTheta = std::max(view.z(), 0.0f);
    const float gamma = std::acos(std::clamp(view.dot(toSun_), -1.0f, 1.0f));
    return {zenith_[1] * perez(1, cosTheta, gamma), zenith_[2] * perez(2, cosTheta, gamma),
            zenith_[0] * perez(0, cosTheta, gamma)};
}

Eigen::Vector3f PreethamSky::radiance(const Eigen::Vector3f& view) const {
    if (view.z() < 0.0f)
        return ground_;
    return xyYToLinearSrgb(xyY(view)) * scale_;
}

RadianceImage PreethamSky::image(int width, int height) const {
    RadianceImage out{width, height, std::vector<Eigen::Vector3f>(std::size_t(width) * std::size_t(height))};
    parallelFor(height, hardwareThreads(), [&](int y) {
        for (int x = 0; x < width; ++x)
            out.texels[std::size_t(y) * std::size_t(width) + std::size_t(x)] = radiance(
                EnvironmentMap::fromUv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)));
    });
    return out;
}

} // namespace sp::render
