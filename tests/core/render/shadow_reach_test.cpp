// Where a view's shadow maps can darken a surface (ShadowReceivers), on maps described by hand: no GL.

#include <gtest/gtest.h>

#include "core/render/primitives.h"
#include "core/render/shadow_maps.h"
#include "core/render/shadow_reach.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

// A floor of 40 x 40 m, a 1 m box standing on it at the origin and a box floating 4 m up, off to the side.
struct Yard {
    Scene scene;
    InstanceId floor, box, floating;
    Yard() {
        const MeshId plane = scene.addMesh(primitives::plane(40, 40));
        const MeshId cube = scene.addMesh(primitives::box());
        const MaterialId grey = scene.addMaterial(makeMaterial({0.5f, 0.5f, 0.5f}, 0.8f, 0.0f));
        floor = scene.addInstance({plane, {grey}, {1}});
        Instance standing{cube, {grey}, {2}};
        standing.transform.translation() = Eigen::Vector3d(0.0, 0.0, 0.5);
        box = scene.addInstance(standing);
        Instance up{cube, {grey}, {3}};
        up.transform.translation() = Eigen::Vector3d(3.0, -2.0, 4.5);
        floating = scene.addInstance(up);
    }
};

// A map for light 0 with 2 cm texels (only texel, perspective and, for spot maps, the projection count).
ShadowInfo sunMap() {
    ShadowInfo map;
    map.lightOrdinal = 0;
    map.layer = 0;
    map.texel = 0.02f;
    map.worldToClip.row(2) << 0.0f, 0.0f, -0.05f, 0.0f; // a 40 m depth range
    return map;
}

int area(const std::vector<PixelRect>& rects) {
    int total = 0;
    for (const PixelRect& r : rects)
        total += (r.x1 - r.x0) * (r.y1 - r.y0);
    return total;
}

bool overlaps(const PixelRect& a, const PixelRect& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

TEST(ShadowReachTest, AFloorIsSplitAroundTheShadowOfWhatStandsOnIt) {
    Yard yard;
    Light sun;
    sun.direction = Eigen::Vector3d(0.3, 0.2, -1.0);
    yard.scene.addLight(sun);
    const Camera camera = cameraLookingAt({9.0, -7.0, 5.0}, {0.0, 0.0, 0.0}, 1280, 720, 70.0);
    const ShadowReceivers receivers(yard.scene, camera, 1280, 720, {sunMap()});

    const ShadowReach floor = receivers.reach(yard.scene, yard.scene.instance(yard.floor));
    ASSERT_EQ(floor.kind, ShadowReach::Kind::Part);
    // Most of the floor is drawn without lookups; its rectangles and the shadowed ones do not overlap, and
    // every rectangle is whole 64-pixel tiles but where the floor's own rectangle cuts it.
    EXPECT_GT(area(floor.unshadowed), 4 * area(floor.shadowed));
    for (const PixelRect& s : floor.shadowed)
        for (const PixelRect& u : floor.unshadowed)
            EXPECT_FALSE(overlaps(s, u));
    // The box's shadow falls on the floor beside the box, along the sun: the box's foot and the point its top
    // corner's shadow lands on are in a shadowed rectangle.
    const auto inShadowed = [&](const Eigen::Vector3d& world) {
        const PixelRect at = receivers.pixels(Eigen::AlignedBox3d(world, world));
        for (const PixelRect& s : floor.shadowed)
            if (overlaps(s, at))
                return true;
        return false;
    };
    EXPECT_TRUE(inShadowed({0.0, 0.0, 0.0}));
    EXPECT_TRUE(inShadowed(Eigen::Vector3d(0.5, 0.5, 1.0) + 1.0 * Eigen::Vector3d(0.3, 0.2, -1.0)));
    EXPECT_FALSE(inShadowed({-8.0, 6.0, 0.0})); // far from any shadow

    // Nothing stands between the sun and the floating box, which cannot shadow itself (convex, flat).
    EXPECT_EQ(yard.scene.instance(yard.floating).mesh, yard.scene.instance(yard.box).mesh);
    EXPECT_EQ(receivers.reach(yard.scene, yard.scene.instance(yard.floating)).kind, ShadowReach::Kind::None);
    // The floating box shadows the floor too: beneath it, not where the sun is.
    EXPECT_TRUE(inShadowed(Eigen::Vector3d(3.0, -2.0, 4.0) + 4.0 * Eigen::Vector3d(0.3, 0.2, -1.0)));
}

TEST(ShadowReachTest, ASpotLightAboveTheFloorDarkensNothingAboveTheFloorThroughIt) {
    // The floor's bounding sphere (28 m) holds the spot light 3 m above it: only the side of the floor away
    // from the light bounds what the floor can darken, and the floating box is on the light's side.
    Yard yard;
    Light spot;
    spot.type = LightType::Spot;
    spot.position = Eigen::Vector3d(2.0, -1.0, 3.0);
    spot.direction = Eigen::Vector3d(0.0, 0.0, -1.0);
    spot.outerConeDeg = 60.0f;
    yard.scene.addLight(spot);
    ShadowInfo map = sunMap();
    map.perspective = true;
    map.texel = 0.002f; // per metre of distance
    // A projection whose frustum holds the whole yard, so that no caster is outside the map.
    map.worldToClip = Eigen::Matrix4f::Identity();
    map.worldToClip(3, 3) = 100.0f;
    const Camera camera = cameraLookingAt({9.0, -7.0, 5.0}, {0.0, 0.0, 0.0}, 1280, 720, 70.0);
    const ShadowReceivers receivers(yard.scene, camera, 1280, 720, {map});
    EXPECT_EQ(receivers.reach(yard.scene, yard.scene.instance(yard.floating)).kind, ShadowReach::Kind::None);
    // The standing box is under the light: the floating box's shadow or the floor's edge may reach it.
    EXPECT_NE(receivers.reach(yard.scene, yard.scene.instance(yard.box)).kind, ShadowReach::Kind::Part);

    // A shade around the light (a box holding it) may darken anything: even the floating box is reached.
    Instance shade{yard.scene.instance(yard.box).mesh, yard.scene.instance(yard.box).materials, {9}};
    shade.transform.translation() = spot.position;
    shade.transform.scale(0.5);
    yard.scene.addInstance(shade);
    const ShadowReceivers shaded(yard.scene, camera, 1280, 720, {map});
    EXPECT_EQ(shaded.reach(yard.scene, yard.scene.instance(yard.floating)).kind, ShadowReach::Kind::Whole);
}

TEST(ShadowReachTest, ASmallViewOfManyCastersMakesNoTests) {
    // The tests cost a few dozen nanoseconds each (casters x lights x instances): a view affords one per 8
    // pixels (at least 4096), and past that draws everything whole with its lookups.
    Yard yard;
    Light sun;
    sun.direction = Eigen::Vector3d(0.3, 0.2, -1.0);
    yard.scene.addLight(sun);
    const MeshId cube = yard.scene.instance(yard.box).mesh;
    for (int i = 0; i < 100; ++i) { // a row of boxes far behind the yard's
        Instance far{cube, yard.scene.instance(yard.box).materials, {std::uint32_t(10 + i)}};
        far.transform.translation() = Eigen::Vector3d(-15.0, -15.0 + 0.3 * i, 0.5);
        yard.scene.addInstance(far);
    }
    const Camera wide = cameraLookingAt({9.0, -7.0, 5.0}, {0.0, 0.0, 0.0}, 1280, 720, 70.0);
    const Camera small = cameraLookingAt({9.0, -7.0, 5.0}, {0.0, 0.0, 0.0}, 64, 36, 70.0);
    const Instance& floating = yard.scene.instance(yard.floating);
    EXPECT_EQ(ShadowReceivers(yard.scene, wide, 1280, 720, {sunMap()}).reach(yard.scene, floating).kind,
              ShadowReach::Kind::None); // 102 x 1 x 103 tests: affordable at 1280 x 720
    EXPECT_EQ(ShadowReceivers(yard.scene, small, 64, 36, {sunMap()}).reach(yard.scene, floating).kind,
              ShadowReach::Kind::Whole); // not at 64 x 36
}

TEST(ShadowReachTest, PixelsOfABoxAreClippedAtTheNearPlane) {
    const Camera camera = cameraLookingAt({0.0, 0.0, 1.0}, {10.0, 0.0, 1.0}, 640, 480, 90.0);
    Scene scene;
    const ShadowReceivers receivers(scene, camera, 640, 480, {});
    // Wholly behind the camera: no pixels.
    EXPECT_TRUE(
        receivers.pixels(Eigen::AlignedBox3d(Eigen::Vector3d(-5, -1, 0), Eigen::Vector3d(-2, 1, 2))).empty());
    // From behind the camera to in front of it, off to its left: the left part of the image, not all of it.
    const PixelRect left =
        receivers.pixels(Eigen::AlignedBox3d(Eigen::Vector3d(-3, 1, 0.5), Eigen::Vector3d(5, 3, 1.5)));
    EXPECT_FALSE(left.empty());
    EXPECT_EQ(left.x0, 0);
    EXPECT_LT(left.x1, 320);
    // In front: inside the image.
    const PixelRect ahead =
        receivers.pixels(Eigen::AlignedBox3d(Eigen::Vector3d(9, -0.5, 0.5), Eigen::Vector3d(10, 0.5, 1.5)));
    EXPECT_GT(ahead.x0, 280);
    EXPECT_LT(ahead.x1, 360);
    // Nothing shadowed in the view: nothing reaches anything.
    EXPECT_TRUE(receivers.pixels(Eigen::AlignedBox3d()).empty());
}

} // namespace
} // namespace sp::render::test
