#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/render/camera.h"

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
