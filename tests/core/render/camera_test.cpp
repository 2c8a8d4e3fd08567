#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/base/error.h"
#include "core/render/camera.h"
#include "core/render/tone.h"

namespace sp::render {
namespace {

TEST(CameraTest, ValidateNamesTheBadField) {
    CameraParams params;
    params.hfovDeg = 180.0;
    try {
        params.validate("CameraParams::check");
        FAIL() << "expected InvalidArgument";
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "CameraParams::check(): hfovDeg must be in (0, 180), got 180");
    }
    params = CameraParams();
    params.farClip = 0.01;
    EXPECT_THROW(params.validate("f"), InvalidArgument);
    params = CameraParams();
    params.width = 0;
    EXPECT_THROW(params.validate("f"), InvalidArgument);
}

TEST(CameraTest, AmbientOcclusionSettingsAreChecked) {
    const auto message = [](float intensity, float radius) -> std::string {
        CameraParams params;
        params.ambientOcclusionIntensity = intensity;
        params.ambientOcclusionRadius = radius;
        try {
            params.validate("f");
        } catch (const InvalidArgument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(message(0.0f, 0.5f), "");
    EXPECT_EQ(message(1.0f, 100.0f), "");
    EXPECT_EQ(message(1.5f, 0.5f), "f(): ambientOcclusionIntensity must be in [0, 1], got 1.5");
    EXPECT_EQ(message(-0.1f, 0.5f), "f(): ambientOcclusionIntensity must be in [0, 1], got -0.1");
    EXPECT_EQ(message(std::nanf(""), 0.5f), "f(): ambientOcclusionIntensity must be in [0, 1], got nan");
    EXPECT_EQ(message(0.5f, 0.0f), "f(): ambientOcclusionRadius must be in (0, 100] metres, got 0");
    EXPECT_EQ(message(0.5f, 101.0f), "f(): ambientOcclusionRadius must be in (0, 100] metres, got 101");
    EXPECT_EQ(message(0.5f, std::nanf("")),
              "f(): ambientOcclusionRadius must be in (0, 100] metres, got nan");
}

TEST(CameraTest, ViewMatrixMapsBodyForwardToGlMinusZ) {
    Camera camera; // identity pose: looks along world +X, +Y left, +Z up
    const Eigen::Vector4d eye = camera.viewMatrix() * Eigen::Vector4d(2.0, 1.0, 0.5, 1.0);
    EXPECT_NEAR(eye.x(), -1.0, 1e-12); // left in the body frame is -X (left) in GL eye space
    EXPECT_NEAR(eye.y(), 0.5, 1e-12);
    EXPECT_NEAR(eye.z(), -2.0, 1e-12);
}

TEST(CameraTest, ProjectsPointsToPixels) {
    Camera camera;
    camera.params.width = 100;
    camera.params.height = 50;
    camera.params.hfovDeg = 90.0;
    camera.pose.translation() = Eigen::Vector3d(1, 2, 3);
    // Straight ahead lands on the image centre; a point to the left lands left of centre.
    Eigen::Vector3d centre = camera.project({11, 2, 3});
    EXPECT_NEAR(centre.x(), 50.0, 1e-9);
    EXPECT_NEAR(centre.y(), 25.0, 1e-9);
    EXPECT_NEAR(centre.z(), 10.0, 1e-9);
    Eigen::Vector3d leftUp = camera.project({11, 12, 3 + 5});
    EXPECT_NEAR(leftUp.x(), 0.0, 1e-9); // 45 degrees left = the left image edge
    EXPECT_NEAR(leftUp.y(), 0.0, 1e-9); // fy = fx = 50 px
    // The GL projection agrees with project() on NDC.
    const Eigen::Vector4d clip =
        camera.projectionMatrix(false) * camera.viewMatrix() * Eigen::Vector4d(11, 12, 8, 1);
    EXPECT_NEAR(clip.x() / clip.w(), -1.0, 1e-9);
    EXPECT_NEAR(clip.y() / clip.w(), 1.0, 1e-9);
}

} // namespace
} // namespace sp::render

namespace sp::render {
namespace {

TEST(WhiteBalance, DaylightIsNeutralAndOtherLightIsBalancedKeepingLuminance) {
    const Eigen::Vector3f luma(0.2126f, 0.7152f, 0.0722f);
    EXPECT_TRUE(whiteBalanceGains(6500.0).isApprox(Eigen::Vector3f::Ones(), 1e-6f));
    const Eigen::Vector3f tungsten = whiteBalanceGains(3200.0), shade = whiteBalanceGains(10000.0);
    EXPECT_GT(tungsten.z(), tungsten.y());
    EXPECT_GT(tungsten.y(), tungsten.x());
    EXPECT_GT(shade.x(), shade.z());
    EXPECT_NEAR(tungsten.dot(luma), 1.0f, 1e-5f);
    EXPECT_NEAR(shade.dot(luma), 1.0f, 1e-5f);
    // Continuous across the fit's pieces (2222 K and 4000 K).
    for (double kelvin : {2222.0, 4000.0})
        EXPECT_TRUE(whiteBalanceGains(kelvin - 0.5).isApprox(whiteBalanceGains(kelvin + 0.5), 2e-3f))
            << kelvin;
    // A grey lit by a black body at the temperature comes out grey: the gains undo the light's colour.
    CameraParams params;
    params.toneMap = ToneMap::Linear;
    params.whiteBalance = tungsten;
    const Eigen::Vector3f light = tungsten.cwiseInverse() * 0.2f;
    EXPECT_NEAR(toneMapChannel(light.x(), 0, params), toneMapChannel(light.z(), 2, params), 1e-6f);
}

} // namespace
} // namespace sp::render
