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

namespace {
// A blueprint of a static-mesh actor with `functions` (a JSON list).
std::string assetWithFunctions(const std::string& functions) {
    return R"({"format": "spear.blueprint", "version": 1, "parent": "AStaticMeshActor",
        "components": [{"name": "StaticMeshComponent", "properties": {"Mobility": "Static"}}],
        "functions": )" +
           functions + "}";
}
} // namespace

TEST(BlueprintTest, FunctionsRunTheirStepsWhenCalledByName) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    const std::string path = writeAsset("BP_CppTestFunctions", assetWithFunctions(R"([
        {"name": "Where", "params": [{"name": "Dz", "type": "float", "default": 2}], "returns": "FVector",
         "body": [{"call": "GetActorLocation", "result": "Here"},
                  {"call": "StaticMeshComponent.SetMassOverrideInKg", "args": {"MassInKg": "$Dz"}},
                  {"return": "$Here"}]},
        {"name": "MoveTo", "params": [{"name": "Target", "type": "FVector"}],
         "body": [{"call": "SetActorLocation", "args": {"NewLocation": "$Target"}}]},
        {"name": "Label", "params": [{"name": "Text", "type": "str"}], "returns": "str",
         "body": [{"return": "$Text"}]},
        {"name": "Mesh", "returns": "UPrimitiveComponent", "body": [{"return": "Self.StaticMeshComponent"}]}])"));
    const UClass* type = world.load_class(&AActor::StaticClass(), path);
    ASSERT_EQ(type->functions.size(), 4u);
    const sp::reflect::FunctionInfo* where = type->findFunction("Where");
    ASSERT_NE(where, nullptr);
    EXPECT_EQ(where->returnType.kind, sp::reflect::TypeCode::Kind::Struct);
    EXPECT_TRUE(where->params.at(0).hasDefault);
    EXPECT_NE(type->findFunction("GetActorLocation"), nullptr) << "the parent's functions stay reachable";

    engine.beginFrame();
    AActor* actor = world.spawn_actor(type, {1, 2, 3}, {}, "Crate");
    using Value = sp::reflect::Value;
    const Value here = where->invoke(actor, {});
    EXPECT_EQ(here.as<Value::Dict>().at("Z").as<double>(), 3.0);
    auto* crate = static_cast<AStaticMeshActor*>(actor);
    EXPECT_EQ(crate->StaticMeshComponent->MassInKg, 2.0) << "the default, an int, taken as a float";
    where->invoke(actor, {{"Dz", Value(int64_t(5))}});
    EXPECT_EQ(crate->StaticMeshComponent->MassInKg, 5.0);
    EXPECT_EQ(type->findFunction("Mesh")->invoke(actor, {}).as<sp::reflect::ObjectHandle>(),
              static_cast<AStaticMeshActor*>(actor)->StaticMeshComponent->GetHandle());
    EXPECT_EQ(
        type->findFunction("Label")->invoke(actor, {{"Text", Value("$$not a variable")}}).as<std::string>(),
        "$$not a variable")
        << "an argument's value is data, never read as a variable";

    auto message = [&](const char* function, const sp::reflect::CallArgs& args) -> std::string {
        try {
            type->findFunction(function)->invoke(actor, args);
        } catch (const sp::Error& error) {
            return error.what();
        }
        return "no error";
    };
    EXPECT_EQ(message("Where", {{"Dz", Value("high")}}),
              "BP_CppTestFunctions.Where(): argument 'Dz' must be float, got 'high'");
    EXPECT_EQ(message("Where", {{"Dx", Value(1.0)}}),
              "BP_CppTestFunctions.Where(): unexpected argument 'Dx'");
    EXPECT_EQ(message("MoveTo", {}), "BP_CppTestFunctions.MoveTo(): missing argument 'Target'");
    // A step that fails names the function and the step; the mesh is static, so it cannot be moved.
    const std::string moved = message("MoveTo", {{"Target", Value(Value::Dict{{"X", Value(0.0)}})}});
    EXPECT_EQ(moved.rfind("BP_CppTestFunctions.MoveTo(): step 1 (SetActorLocation): ", 0), 0u) << moved;
    engine.executeFrame();
    engine.beginEndFrame();
    engine.endFrame();
}

TEST(BlueprintTest, BadFunctionsAreRejectedOnLoadNamingTheFunctionAndStep) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    const std::pair<const char*, const char*> cases[] = {
        {R"([{"name": "F", "body": [{"call": "Lid.SetVisibility", "args": {"bNewVisibility": true}}]}])",
         "functions[0]: function 'F': body[0]: 'Lid.SetVisibility': AStaticMeshActor has no component 'Lid'"},
        {R"([{"name": "F", "body": [{"call": "Fly"}]}])",
         "functions[0]: function 'F': body[0]: 'Fly': class 'AStaticMeshActor' has no function 'Fly'"},
        {R"([{"name": "F", "body": [{"call": "SetActorLocation", "args": {"Location": {"X": 1}}}]}])",
         "functions[0]: function 'F': body[0]: 'SetActorLocation' needs argument 'NewLocation'"},
        {R"([{"name": "F", "body": [{"call": "SetActorLocation", "args": {"NewLocation": "$Where"}}]}])",
         "functions[0]: function 'F': body[0]: argument 'NewLocation': '$Where' is not a parameter or an "
         "earlier "
         "step's result"},
        {R"([{"name": "F", "params": [{"name": "N", "type": "str"}],
              "body": [{"call": "SetActorLocation", "args": {"NewLocation": {"X": "$N"}}}]}])",
         "functions[0]: function 'F': body[0]: argument 'NewLocation'.X: '$N' is str, not float"},
        {R"([{"name": "F", "params": [{"name": "N", "type": "double"}], "body": [{"call": "GetActorLocation"}]}])",
         "functions[0]: function 'F': parameter 'N': unknown type 'double' (bool, int, float, str, or a "
         "reflected "
         "struct, enum or class)"},
        {R"([{"name": "F", "returns": "AActor", "body": [{"return": "Self.StaticMeshComponent"}]}])",
         "functions[0]: function 'F': body[0]: 'return': 'Self.StaticMeshComponent' is UStaticMeshComponent, "
         "not "
         "AActor"},
        {R"([{"name": "F", "returns": "UStaticMeshComponent", "body": [{"return": "Self.Lid"}]}])",
         "functions[0]: function 'F': body[0]: 'return': actor 'Self' has no component 'Lid'"},
        {R"([{"name": "F", "returns": "int", "body": [{"call": "GetActorLocation"}]}])",
         "functions[0]: function 'F': declares 'returns' but its last step is not a return"},
        {R"([{"name": "F", "body": [{"return": 1}]}])",
         "functions[0]: function 'F': body[0]: a return step needs 'returns' to declare the result's type"},
        {R"([{"name": "GetActorLocation", "body": [{"call": "GetActorLocation"}]}])",
         "functions[0]: function 'GetActorLocation': the parent class has a member of that name"},
        {R"([{"name": "Tags", "body": [{"call": "GetActorLocation"}]}])",
         "functions[0]: function 'Tags': the parent class has a member of that name"},
        {R"([{"name": "_hidden", "body": [{"call": "GetActorLocation"}]}])",
         "functions[0]: function '_hidden': a function's name is letters, digits and '_', not starting with "
         "'_'"},
        {R"([{"name": "F", "doc": 3, "body": [{"call": "GetActorLocation"}]}])",
         "functions[0]: function 'F': 'doc' must be a string, got 3"},
        {R"([{"name": "F", "body": [{"call": "GetActorLocation"}]}, {"name": "F", "body": [{"call": "GetActorLocation"}]}])",
         "function 'F' is declared twice"},
    };
    int index = 0;
    for (const auto& [functions, expected] : cases) {
        const std::string path =
            writeAsset("BP_CppTestBadFunction" + std::to_string(index++), assetWithFunctions(functions));
        try {
            world.load_class(&AActor::StaticClass(), path);
            ADD_FAILURE() << "accepted: " << functions;
        } catch (const sp::InvalidArgument& error) {
            EXPECT_EQ(std::string(error.what()),
                      "UWorld.load_class(): blueprint '" + path + "': " + expected);
        }
    }
}
