#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/scene/scene_io.h"
#include "core/sensors/light_actors.h"
#include "core/world/static_mesh_actor.h"

TEST(SceneIoTest, SaveLoadSaveIsIdentical) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    auto* cube = static_cast<AStaticMeshActor*>(
        world.spawn_actor(&AStaticMeshActor::StaticClass(), {1, 2, 3}, {10, 20, 30}, "Cube", {"t"}));
    cube->StaticMeshComponent->SetStaticMesh("/Engine/BasicShapes/Cube");
    cube->StaticMeshComponent->SetMaterial(0, "/Game/M_Wood");
    auto* lamp = static_cast<APointLight*>(world.spawn_actor(&APointLight::StaticClass(), {}, {}, "Lamp"));
    lamp->LightComponent->LightColor = {0.5f, 0.25f, 1.0f, 1.0f};
    const std::string first = sp::scene::sceneToString(sp::scene::saveScene(world));
    sp::scene::loadScene(world, sp::scene::saveScene(world), "test");
    EXPECT_EQ(world.get_actor_count(), 2);
    const std::string second = sp::scene::sceneToString(sp::scene::saveScene(world));
    EXPECT_EQ(first, second);
    auto* loaded = static_cast<APointLight*>(world.find_actor_by_name("Lamp"));
    ASSERT_NE(loaded, nullptr);
    EXPECT_EQ(loaded->LightComponent->LightColor, (FLinearColor{0.5f, 0.25f, 1.0f, 1.0f}));
}

TEST(SceneIoTest, ABadDocumentLeavesTheWorldUnchanged) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    world.spawn_actor(&AActor::StaticClass(), {}, {}, "Keep");
    sp::scene::SceneJson scene = sp::scene::saveScene(world);
    scene["actors"][0]["properties"]["Tags"] = 5;
    try {
        sp::scene::loadScene(world, scene, "doc");
        FAIL() << "expected InvalidArgument";
    } catch (const sp::InvalidArgument& error) {
        EXPECT_STREQ(error.what(),
                     "doc: actors[0] 'Keep': property 'Tags': expected a list (list[str]), got number 5");
    }
    EXPECT_EQ(world.get_actor_count(), 1);
    EXPECT_THROW(sp::scene::readSceneFile("/nonexistent/scene.json", "f()"), sp::NotFound);
}
