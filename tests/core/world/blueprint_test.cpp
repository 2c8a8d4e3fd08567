#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/world/static_mesh_actor.h"

namespace {
// Writes a blueprint asset into the test's temporary directory; the file stem is the class name.
std::string writeAsset(const std::string& stem, const std::string& text) {
    const auto dir = std::filesystem::temp_directory_path() / "spear_blueprint_test";
    std::filesystem::create_directories(dir);
    const auto path = dir / (stem + ".json");
    std::ofstream(path) << text;
    return path.string();
}
} // namespace

TEST(BlueprintTest, SpawnedObjectsReportTheBlueprintClassAndGetItsDefaults) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    const std::string path = writeAsset("BP_CppTestCrate", R"({
        "format": "spear.blueprint", "version": 1, "parent": "AStaticMeshActor",
        "properties": {"Tags": ["crate"]},
        "components": [
          {"name": "StaticMeshComponent", "properties": {"MassInKg": 7.0}},
          {"name": "Lid", "class": "UStaticMeshComponent", "attach_parent": "StaticMeshComponent",
           "properties": {"StaticMesh": "/Engine/BasicShapes/Plane"}}]})");
    const UClass* type = world.load_class(&AActor::StaticClass(), path);
    ASSERT_NE(type, nullptr);
    EXPECT_EQ(type->name, "BP_CppTestCrate");
    EXPECT_EQ(type->parent, &AStaticMeshActor::StaticClass());
    EXPECT_EQ(world.load_class(&AActor::StaticClass(), path), type); // cached by path

    AActor* actor = world.spawn_actor(type, {}, {}, "Crate", {"spawned"});
    EXPECT_EQ(&actor->GetClass(), &AStaticMeshActor::StaticClass()); // the generated class made it
    EXPECT_EQ(&actor->GetObjectClass(), type);
    EXPECT_EQ(actor->GetClassName(), "BP_CppTestCrate");
    EXPECT_TRUE(actor->IsA(*type) && actor->IsA(AStaticMeshActor::StaticClass()));
    EXPECT_EQ(actor->Tags, (std::vector<std::string>{"crate", "spawned"}));
    auto* crate = static_cast<AStaticMeshActor*>(actor);
    EXPECT_EQ(crate->StaticMeshComponent->MassInKg, 7.0);
    auto* lid = static_cast<UStaticMeshComponent*>(world.get_component_by_name(actor, "Lid"));
    ASSERT_NE(lid, nullptr);
    EXPECT_EQ(lid->GetAttachParent(), crate->StaticMeshComponent);
    EXPECT_EQ(lid->StaticMesh, "/Engine/BasicShapes/Plane");

    AActor* plain = world.spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "Plain");
    EXPECT_FALSE(plain->IsA(*type));
    EXPECT_EQ(world.find_actors_by_class(type), std::vector<AActor*>{actor});
    EXPECT_EQ(world.find_actors_by_class(&AStaticMeshActor::StaticClass()),
              (std::vector<AActor*>{actor, plain}));
}

TEST(BlueprintTest, ABadAssetIsRejectedOnLoadWithItsPathAndField) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    const std::string path = writeAsset("BP_CppTestBad", R"({"format": "spear.blueprint", "version": 1,
        "parent": "AActor", "components": [{"name": "C", "class": "UNope"}]})");
    try {
        world.load_class(&AActor::StaticClass(), path);
        FAIL() << "expected InvalidArgument";
    } catch (const sp::InvalidArgument& error) {
        EXPECT_EQ(std::string(error.what()), "UWorld.load_class(): blueprint '" + path +
                                                 "': component 'C': class 'UNope' is not registered");
    }
    EXPECT_THROW(world.load_class(&AActor::StaticClass(), path + ".missing.json"), sp::NotFound);
}
