// The analytic sky (Preetham, Shirley and Smits 1999) against the paper's formulas evaluated independently,
// and its shape: the Perez distribution equal to the zenith's values at the zenith, brighter towards the sun
// and the horizon, a ground lit by the sun and the sky, the fade below the horizon and the settings' ranges.

#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.h"
#include "core/render/sky_model.h"

namespace sp::render {
namespace {

constexpr float kPi = 3.14159265358979f;

// The direction sunlight travels for a sun `zenithDegrees` from the zenith, in the X-Z plane.
Eigen::Vector3f sunAt(float zenithDegrees) {
    const float t = zenithDegrees * kPi / 180.0f;
    return -Eigen::Vector3f(std::sin(t), 0.0f, std::cos(t));
}

TEST(SkyModelTest, ZenithLuminanceAndChromaticityAreThePapersFits) {
    // Appendix A of the paper, evaluated in double precision outside the engine (cd/m^2, CIE x, y).
    struct Case {
        float turbidity, sunZenith, luminance, x, y;
    };
    for (const Case& c :
         {Case{2.0f, 30.0f, 5886.74f, 0.25142f, 0.25592f}, Case{3.0f, 60.0f, 5139.16f, 0.24493f, 0.25257f},
          Case{6.0f, 45.0f, 14893.33f, 0.26145f, 0.27545f}}) {
        SkyParameters parameters;
        parameters.turbidity = c.turbidity;
        parameters.sunDirection = sunAt(c.sunZenith);
        const PreethamSky sky(parameters);
        EXPECT_NEAR(sky.zenithLuminance(), c.luminance, 1e-3f * c.luminance) << c.turbidity;
        EXPECT_NEAR(sky.zenithChromaticity().x(), c.x, 2e-4f);
        EXPECT_NEAR(sky.zenithChromaticity().y(), c.y, 2e-4f);
        // The Perez distribution is normalised to the zenith.
        const Eigen::Vector3f zenith = sky.xyY(Eigen::Vector3f::UnitZ());
        EXPECT_NEAR(zenith.z(), c.luminance, 1e-3f * c.luminance);
        EXPECT_NEAR(zenith.x(), c.x, 2e-4f);
    }
}

TEST(SkyModelTest, TheSkyIsBrightestAroundTheSunAndBrightensTowardsTheHorizon) {
    SkyParameters parameters;
    parameters.sunDirection = sunAt(50.0f);
    const PreethamSky sky(parameters);
    const Eigen::Vector3f towardsSun = Eigen::Vector3f(std::sin(0.6f), 0.0f, std::cos(0.6f)).normalized();
    const Eigen::Vector3f awayFromSun(-towardsSun.x(), 0.0f, towardsSun.z());
    EXPECT_GT(sky.xyY(towardsSun).z(), 2.0f * sky.xyY(awayFromSun).z());
    // Away from the sun, the horizon is brighter than the zenith (a clear sky's horizon brightening).
    const Eigen::Vector3f side(0.0f, std::cos(0.1f), std::sin(0.1f));
    EXPECT_GT(sky.xyY(side).z(), sky.zenithLuminance());
    // Blue: in linear sRGB, blue exceeds red overhead.
    const Eigen::Vector3f overhead = sky.radiance(Eigen::Vector3f::UnitZ());
    EXPECT_GT(overhead.z(), overhead.x());
}

TEST(SkyModelTest, RadianceIsLuminanceScaledByTheSunOverTheSolarIlluminance) {
    SkyParameters parameters;
    parameters.sunDirection = sunAt(40.0f);
    parameters.sunIrradiance = Eigen::Vector3f::Constant(PreethamSky::kSolarIlluminance);
    const PreethamSky sky(parameters);
    // A sun of intensity 128,000 (lux): the sky's luminance in cd/m^2.
    const Eigen::Vector3f zenith = sky.radiance(Eigen::Vector3f::UnitZ());
    const float luminance = 0.2126f * zenith.x() + 0.7152f * zenith.y() + 0.0722f * zenith.z();
    EXPECT_NEAR(luminance, sky.zenithLuminance(), 0.02f * sky.zenithLuminance());
}

TEST(SkyModelTest, TheGroundIsLambertianUnderTheSunAndTheSky) {
    SkyParameters parameters;
    parameters.sunDirection = sunAt(0.0f);
    parameters.sunIrradiance = Eigen::Vector3f::Constant(kPi);
    parameters.groundAlbedo = Eigen::Vector3f::Constant(0.5f);
    const Eigen::Vector3f ground = PreethamSky(parameters).radiance(-Eigen::Vector3f::UnitZ());
    // At least the sun's share (0.5 x pi / pi), and the sky adds some tens of percent on a clear day.
    EXPECT_GT(ground.x(), 0.5f);
    EXPECT_LT(ground.x(), 0.5f * 1.5f);
    parameters.groundAlbedo = Eigen::Vector3f::Constant(0.25f);
    EXPECT_TRUE(PreethamSky(parameters).radiance(-Eigen::Vector3f::UnitZ()).isApprox(ground * 0.5f, 1e-5f));
}

TEST(SkyModelTest, BelowTheHorizonTheSkyFadesToBlack) {
    SkyParameters parameters;
    parameters.sunDirection = sunAt(90.0f);
    const float atHorizon = PreethamSky(parameters).radiance(Eigen::Vector3f::UnitZ()).sum();
    parameters.sunDirection = sunAt(93.0f);
    const float twilight = PreethamSky(parameters).radiance(Eigen::Vector3f::UnitZ()).sum();
    parameters.sunDirection = sunAt(97.0f);
    const float night = PreethamSky(parameters).radiance(Eigen::Vector3f::UnitZ()).sum();
    EXPECT_GT(atHorizon, 0.0f);
    EXPECT_NEAR(twilight, 0.5f * atHorizon, 1e-3f * atHorizon);
    EXPECT_EQ(night, 0.0f);
}

TEST(SkyModelTest, SettingsOutOfRangeAreRefusedByName) {
    SkyParameters parameters;
    parameters.turbidity = 12.0f;
    try {
        PreethamSky sky(parameters);
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "PreethamSky: Turbidity must be in [1.7, 10], got 12");
    }
    parameters.turbidity = 3.0f;
    parameters.groundAlbedo = Eigen::Vector3f(0.5f, 1.5f, 0.5f);
    EXPECT_THROW(PreethamSky{parameters}, InvalidArgument);
}

} // namespace
} // namespace sp::render
