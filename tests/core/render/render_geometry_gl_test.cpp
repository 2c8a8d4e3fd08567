// Geometry modalities against analytic values: depth, position and normal of planes; ids per slot.

#include <set>

#include "core/render/image_buffer.h"
#include "gl_fixture.h"

namespace sp::render::test {
namespace {

using RenderGeometryGlTest = GlTest;

MaterialId grey(Scene& scene) {
    return scene.addMaterial(Material{});
}

TEST_F(RenderGeometryGlTest, DepthOfAFacingPlaneIsItsDistance) {
    Scene scene;
    const double distance = 7.25;
    Instance wall{scene.addMesh(primitives::plane(100, 100)), {grey(scene)}, {5}};
    // The plane faces +Z; turn it to face the camera (-X) and move it along the optical axis.
    wall.transform =
        Eigen::Translation3d(distance, 0.3, -0.2) * Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY());
    scene.addInstance(wall);
    Camera camera = lookingAlong({0, 0, 0}, {1, 0, 0}, 64, 48, 70.0);
    RenderTarget target(renderer(), {Modality::Depth, Modality::Position, Modality::Normal}, 0);
    Frame frame;
    ASSERT_EQ(target.render(scene, camera, frame), 1u);
    const ImageBuffer& depth = frame.get(Modality::Depth);
    const ImageBuffer& position = frame.get(Modality::Position);
    const ImageBuffer& normal = frame.get(Modality::Normal);
    const double f = camera.focalLengthPixels();
    double worst = 0.0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            worst = std::max(worst, std::abs(depth.at(x, y) - distance) / distance);
            // Pixel centre ray: +Y is left (u grows right), +Z is up (v grows down).
            const Eigen::Vector3d expected(distance, -(x + 0.5 - 32.0) * distance / f,
                                           -(y + 0.5 - 24.0) * distance / f);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(position.at(x, y, c), expected[c], 1e-4 * distance) << x << "," << y << " c" << c;
            ASSERT_NEAR(normal.at(x, y, 0), -1.0f, 1e-5f);
            ASSERT_NEAR(normal.at(x, y, 1), 0.0f, 1e-5f);
            ASSERT_NEAR(normal.at(x, y, 2), 0.0f, 1e-5f);
        }
    EXPECT_LT(worst, 1e-4);
}

TEST_F(RenderGeometryGlTest, DepthOfTheGroundSeenFromAPitchedCamera) {
    Scene scene;
    scene.addInstance({scene.addMesh(primitives::plane(400, 400)), {grey(scene)}, {1}});
    const double height = 1.6;
    Camera camera = lookingAlong({0, 0, height}, {1, 0.2, -0.6}, 40, 30, 60.0);
    RenderTarget target(renderer(), {Modality::Depth, Modality::ObjectIds}, 0);
    Frame frame;
    target.render(scene, camera, frame);
    const double f = camera.focalLengthPixels();
    int checked = 0;
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
            const Eigen::Vector3d body(1.0, -(x + 0.5 - 20.0) / f, -(y + 0.5 - 15.0) / f);
            const Eigen::Vector3d dir = camera.pose.linear() * body;
            ASSERT_LT(dir.z(), 0.0);                   // every pixel sees the ground
            const double expected = -height / dir.z(); // body.x() == 1, so t is the optical-axis depth
            ASSERT_NEAR(frame.get(Modality::Depth).at(x, y), expected, 1e-4 * expected) << x << "," << y;
            ++checked;
        }
    EXPECT_EQ(checked, 40 * 30);
}

TEST_F(RenderGeometryGlTest, IdsPerInstanceSlotWithBackgroundZero) {
    Scene scene;
    // A two-slot mesh: left and right halves of a quad, each its own submesh.
    const float positions[] = {0, -1, -1, 0, 0, -1, 0, 0, 1, 0, -1, 1, 0, 1, -1, 0, 1, 1};
    const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
    const std::uint32_t offsets[] = {0, 6};
    MeshId twoSlots = scene.addMesh(MeshData::fromArrays(positions, {}, {}, indices, offsets));
    Material red;
    red.baseColor = {0.8f, 0.1f, 0.1f, 1.0f};
    red.id = 900;
    MaterialId redId = scene.addMaterial(red), greyId = grey(scene);
    MeshId box = scene.addMesh(primitives::box({0.5f, 0.5f, 0.5f}));
    Instance quad{twoSlots, {redId, greyId}, {0x00ABCDEFu, 0x00ABCDF0u}};
    quad.transform.translation() = Eigen::Vector3d(6, 0, 0);
    scene.addInstance(quad);
    std::vector<Eigen::Vector3d> boxCentres = {{4, 1.5, 0.8}, {4, -1.5, -0.8}, {5, 0, 1.4}};
    for (std::size_t i = 0; i < boxCentres.size(); ++i) {
        Instance instance{box, {greyId}, {std::uint32_t(100 + i)}};
        instance.transform.translation() = boxCentres[i];
        scene.addInstance(instance);
    }
    RenderTarget target(renderer(), {Modality::ObjectIds, Modality::MaterialIds}, 0);
    for (const Eigen::Vector3d& cameraPosition :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(-0.5, 0.3, 0.2)}) {
        Camera camera = lookingAlong(cameraPosition, Eigen::Vector3d(5, 0, 0) - cameraPosition, 96, 72, 75.0);
        Frame frame;
        target.render(scene, camera, frame);
        const ImageBuffer& ids = frame.get(Modality::ObjectIds);
        const ImageBuffer& materials = frame.get(Modality::MaterialIds);
        std::set<std::uint32_t> seen(ids.as<std::uint32_t>().begin(), ids.as<std::uint32_t>().end());
        EXPECT_EQ(seen, (std::set<std::uint32_t>{0, 100, 101, 102, 0x00ABCDEF, 0x00ABCDF0}));
        EXPECT_EQ(ids.uintAt(0, 0), 0u);
        EXPECT_EQ(materials.uintAt(0, 0), 0u);
        for (std::size_t i = 0; i < boxCentres.size(); ++i) {
            const Eigen::Vector3d p = camera.project(boxCentres[i]);
            EXPECT_EQ(ids.uintAt(int(p.x()), int(p.y())), 100 + i);
            EXPECT_EQ(materials.uintAt(int(p.x()), int(p.y())), greyId.index + 1);
        }
        // Left half of the quad (+Y in world is left in the image) is slot 1, the right half slot 0.
        const Eigen::Vector3d left = camera.project({6, 0.5, -0.5}), right = camera.project({6, -0.5, -0.5});
        EXPECT_EQ(ids.uintAt(int(left.x()), int(left.y())), 0x00ABCDF0u);
        EXPECT_EQ(ids.uintAt(int(right.x()), int(right.y())), 0x00ABCDEFu);
        EXPECT_EQ(materials.uintAt(int(right.x()), int(right.y())), 900u);
    }
}

TEST_F(RenderGeometryGlTest, OnlyRequestedPassesRun) {
    Scene scene;
    scene.addInstance({scene.addMesh(primitives::box()), {grey(scene)}, {1}});
    scene.addLight(Light{});
    Camera camera = lookingAlong({-3, 0, 0}, {1, 0, 0}, 16, 16);
    Frame frame;
    renderer().resetStats();
    RenderTarget ids(renderer(), {Modality::ObjectIds, Modality::Depth}, 0);
    ids.render(scene, camera, frame);
    RenderStats stats = renderer().stats();
    EXPECT_EQ(stats.surfacePasses, 1u);
    EXPECT_EQ(stats.attributePasses, 0u);
    EXPECT_EQ(stats.lightingPasses, 0u);
    EXPECT_EQ(stats.tonemapPasses, 0u);
    EXPECT_EQ(stats.shadowPasses, 0u);
    EXPECT_EQ(stats.readbacks, 2u);
    EXPECT_FALSE(frame.has(Modality::FinalColor));
    EXPECT_THROW(frame.get(Modality::FinalColor), NotFound);

    renderer().resetStats();
    RenderTarget hdr(renderer(), {Modality::HdrColor}, 0);
    hdr.render(scene, camera, frame);
    stats = renderer().stats();
    EXPECT_EQ(stats.lightingPasses, 1u);
    EXPECT_EQ(stats.tonemapPasses, 0u);
    EXPECT_EQ(stats.shadowPasses, 1u);

    renderer().resetStats();
    camera.params.shadows = false;
    RenderTarget color(renderer(), {Modality::FinalColor}, 0);
    color.render(scene, camera, frame);
    stats = renderer().stats();
    EXPECT_EQ(stats.tonemapPasses, 1u);
    EXPECT_EQ(stats.shadowPasses, 0u);
    EXPECT_EQ(stats.readbacks, 1u);
    EXPECT_EQ(stats.meshUploads, 0u); // the box was uploaded by the first target already
}

} // namespace
} // namespace sp::render::test
