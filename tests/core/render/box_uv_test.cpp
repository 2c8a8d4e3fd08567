#include "core/render/box_uv.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace sp::render {
namespace {

// u runs to the right and v downwards as a viewer facing the face from outside sees it, with +Z up (on the
// Z faces, +X up): right = forward x up, forward = -normal.
void expectImageOrientation(const Eigen::Vector3f& normal, const Eigen::Vector3f& up) {
    const auto [along, down] = boxAxes(normal);
    const Eigen::Vector3f right = (-normal).cross(up);
    EXPECT_TRUE(along.isApprox(right))
        << "normal " << normal.transpose() << ": u along " << along.transpose();
    EXPECT_TRUE(down.isApprox(-up)) << "normal " << normal.transpose() << ": v along " << down.transpose();
}

TEST(BoxUvTest, EveryFaceIsSeenUnmirroredWithItsUpUp) {
    const Eigen::Vector3f x = Eigen::Vector3f::UnitX(), y = Eigen::Vector3f::UnitY(),
                          z = Eigen::Vector3f::UnitZ();
    for (const float side : {1.0f, -1.0f}) {
        expectImageOrientation(side * x, z);
        expectImageOrientation(side * y, z);
        expectImageOrientation(side * z, x);
    }
}

TEST(BoxUvTest, TheAxisTheNormalIsMostAlongChoosesThePlaneAndTiesGoToZThenX) {
    EXPECT_EQ(boxAxes({0.6f, 0.5f, 0.62f}).second, Eigen::Vector3f(-1.0f, 0.0f, 0.0f)); // Z: v along -X
    EXPECT_EQ(boxAxes({0.5f, 0.5f, 0.5f}).second, Eigen::Vector3f(-1.0f, 0.0f, 0.0f));  // a tie: Z
    EXPECT_EQ(boxAxes({0.7f, 0.7f, 0.1f}).first, Eigen::Vector3f(0.0f, 1.0f, 0.0f));    // a tie: X
    EXPECT_EQ(boxAxes({0.3f, -0.9f, 0.1f}).first, Eigen::Vector3f(1.0f, 0.0f, 0.0f));   // Y
}

TEST(BoxUvTest, CoordinatesAreMetresOverTheTextureSize) {
    // On the +X face, 0.5 m along +Y and 0.25 m down, with a 0.25 m texture: (2, 1) repeats.
    EXPECT_TRUE(boxUv({1.0f, 0.5f, -0.25f}, {1.0f, 0.0f, 0.0f}, 4.0f).isApprox(Eigen::Vector2f(2.0f, 1.0f)));
    // Only the two coordinates across the face count.
    EXPECT_EQ(boxUv({7.0f, 0.5f, -0.25f}, {1.0f, 0.0f, 0.0f}, 4.0f),
              boxUv({1.0f, 0.5f, -0.25f}, {1.0f, 0.0f, 0.0f}, 4.0f));
}

} // namespace
} // namespace sp::render
