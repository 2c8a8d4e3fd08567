// RenderScene without GL: what the world becomes in the render scene (instances, per-slot object ids,
// materials by name, lights and sky). The GL path is tested end to end in tests/python/test_camera.py.

#include <gtest/gtest.h>

#include "core/engine/engine.h"
#include "core/sensors/camera_sensor_actor.h"
#include "core/sensors/light_actors.h"
#include "core/sensors/render_scene.h"
#include "core/sensors/render_subsystem.h"
#include "core/sensors/sky_light_component.h"
#include "core/sensors/spot_light_component.h"
#include "core/world/static_mesh_actor.h"

namespace {

struct RenderSceneTest : ::testing::Test {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    // The world's own render scene: it learns of actors and components by registration as they begin play.
    sp::sensors::RenderScene& scene = world.GetSubsystem<sp::sensors::RenderSubsystem>().renderScene();

    AStaticMeshActor* spawnMesh(const std::string& mesh, const std::string& material) {
        auto* actor = static_cast<AStaticMeshActor*>(world.spawn_actor(&AStaticMeshActor::StaticClass()));
        actor->StaticMeshComponent->SetStaticMesh(mesh);
        actor->StaticMeshComponent->SetMaterial(0, material);
        return actor;
    }
};

TEST_F(RenderSceneTest, OneInstancePerMeshComponentWithStableNonZeroIds) {
    AStaticMeshActor* cube = spawnMesh("/Engine/BasicShapes/Cube", "Red");
    AStaticMeshActor* ball = spawnMesh("/Engine/BasicShapes/Sphere", "Red");
    world.spawn_actor(&AStaticMeshActor::StaticClass()); // no mesh: nothing to draw
    scene.sync();
    EXPECT_EQ(scene.scene().instanceCount(), 2u);
    const std::uint32_t cubeId = scene.objectId(cube->StaticMeshComponent->GetHandle(), 0);
    const std::uint32_t ballId = scene.objectId(ball->StaticMeshComponent->GetHandle(), 0);
    EXPECT_NE(cubeId, 0u);
    EXPECT_NE(ballId, 0u);
    EXPECT_NE(cubeId, ballId);
    EXPECT_EQ(scene.objectId(cube->StaticMeshComponent->GetHandle(), 1), 0u); // a cube has one slot

    cube->SetActorLocation({1.0, 2.0, 3.0});
    scene.sync();
    EXPECT_EQ(scene.objectId(cube->StaticMeshComponent->GetHandle(), 0), cubeId);
    auto info = scene.objectIdInfo(cubeId);
    ASSERT_TRUE(info);
    EXPECT_EQ(info->component, cube->StaticMeshComponent->GetHandle());
    EXPECT_EQ(info->slot, 0);
    EXPECT_EQ(info->materialName, "Red");
    EXPECT_FALSE(scene.objectIdInfo(0));

    world.destroy_actor(ball);
    scene.sync();
    EXPECT_EQ(scene.scene().instanceCount(), 1u);
    EXPECT_FALSE(scene.objectIdInfo(ballId)); // gone with its component, never reused
    AStaticMeshActor* again = spawnMesh("/Engine/BasicShapes/Sphere", "Red");
    scene.sync();
    EXPECT_GT(scene.objectId(again->StaticMeshComponent->GetHandle(), 0), ballId);
}

TEST_F(RenderSceneTest, TransformScaleAndVisibilityReachTheInstance) {
    AStaticMeshActor* cube = spawnMesh("/Engine/BasicShapes/Cube", "");
    cube->SetActorLocation({1.0, 2.0, 3.0});
    cube->SetActorScale3D({2.0, 3.0, 4.0});
    cube->StaticMeshComponent->bVisible = false;
    scene.sync();
    bool seen = false;
    scene.scene().forEachInstance([&](sp::render::InstanceId, const sp::render::Instance& instance) {
        seen = true;
        EXPECT_FALSE(instance.visible);
        EXPECT_TRUE(instance.transform.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
        EXPECT_TRUE(
            (instance.transform.linear() * Eigen::Vector3d::Ones()).isApprox(Eigen::Vector3d(2, 3, 4)));
    });
    EXPECT_TRUE(seen);
}

TEST_F(RenderSceneTest, MaterialsResolveLibraryThenBuiltinThenDefault) {
    auto* library = static_cast<AMaterialLibrary*>(world.spawn_actor(&AMaterialLibrary::StaticClass()));
    FMaterialDesc mine;
    mine.BaseColor = {0.1f, 0.2f, 0.3f, 1.0f};
    library->SetMaterial("Mine", mine);
    spawnMesh("/Engine/BasicShapes/Cube", "Mine");
    spawnMesh("/Engine/BasicShapes/Cube", "/Engine/Materials/Gold");
    spawnMesh("/Engine/BasicShapes/Cube", "NoSuchMaterial");
    scene.sync();
    EXPECT_EQ(scene.scene().materialCount(), 3u);
    const std::uint32_t mineId = scene.materialId("Mine");
    EXPECT_NE(mineId, 0u);
    EXPECT_NE(scene.materialId("/Engine/Materials/Gold"), 0u);
    EXPECT_NE(scene.materialId("NoSuchMaterial"), 0u); // default parameters, its own id
    EXPECT_EQ(scene.materialId("Unused"), 0u);

    mine.Roughness = 0.9f; // an edited material keeps its id
    library->SetMaterial("Mine", mine);
    scene.sync();
    EXPECT_EQ(scene.materialId("Mine"), mineId);
    EXPECT_EQ(scene.scene().materialCount(), 3u);
}

TEST_F(RenderSceneTest, LightsAndSkyAreCopiedEveryFrame) {
    auto* sun = static_cast<ADirectionalLight*>(
        world.spawn_actor(&ADirectionalLight::StaticClass(), {}, FRotator{-90.0, 0.0, 0.0}));
    auto* spot = static_cast<ASpotLight*>(world.spawn_actor(&ASpotLight::StaticClass(), {0.0, 0.0, 3.0}));
    spot->LightComponent->OuterConeAngle = 50.0f;
    auto* sky = static_cast<ASkyLight*>(world.spawn_actor(&ASkyLight::StaticClass()));
    sky->SkyLightComponent->Intensity = 0.5f;
    scene.sync();
    ASSERT_EQ(scene.scene().lightCount(), 2u);
    int directional = 0, spots = 0;
    scene.scene().forEachLight([&](sp::render::LightId, const sp::render::Light& light) {
        if (light.type == sp::render::LightType::Directional) {
            ++directional;
            EXPECT_TRUE(
                light.direction.isApprox(Eigen::Vector3d(0, 0, -1), 1e-9)); // pitch -90: straight down
        } else if (light.type == sp::render::LightType::Spot) {
            ++spots;
            EXPECT_FLOAT_EQ(light.outerConeDeg, 50.0f);
            EXPECT_TRUE(light.position.isApprox(Eigen::Vector3d(0, 0, 3)));
        }
    });
    EXPECT_EQ(directional, 1);
    EXPECT_EQ(spots, 1);
    EXPECT_FLOAT_EQ(scene.scene().environment().ambient.x(), 0.5f);

    world.destroy_actor(sun);
    scene.sync();
    EXPECT_EQ(scene.scene().lightCount(), 1u);
}

} // namespace

// A scene's actors begin play before they join the world; the camera among them makes the render subsystem,
// which must still be told of the actors that began before it.
TEST(RenderSubsystemRegistration, ALoadedSceneIsMirroredFromItsFirstCamera) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    std::vector<std::unique_ptr<AActor>> actors;
    actors.push_back(world.NewActorDeferred(AStaticMeshActor::StaticClass(), "Cube"));
    static_cast<AStaticMeshActor&>(*actors.back())
        .StaticMeshComponent->SetStaticMesh("/Engine/BasicShapes/Cube");
    actors.push_back(world.NewActorDeferred(ACameraSensorActor::StaticClass(), "Camera"));
    world.ReplaceActors(std::move(actors));
    auto* render = world.FindSubsystem<sp::sensors::RenderSubsystem>();
    ASSERT_NE(render, nullptr); // made by the camera as it began play
    render->renderScene().sync();
    EXPECT_EQ(render->renderScene().scene().instanceCount(), 1u);
}
