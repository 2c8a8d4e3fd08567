#include <gtest/gtest.h>

#include <algorithm>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/reflect/property_path.h"
#include "core/reflect/registry.h"
#include "core/world/static_mesh_actor.h"

using namespace sp::reflect;

namespace {
struct RegistryTest : ::testing::Test {
    void SetUp() override { sp::engine::registerEngineTypes(); }
    Registry& registry = Registry::get();
};
} // namespace

TEST_F(RegistryTest, ClassesKnowTheirHierarchy) {
    const TypeInfo& mesh = registry.getClass("AStaticMeshActor", "test");
    EXPECT_EQ(mesh.parent, &AActor::StaticClass());
    EXPECT_TRUE(mesh.isChildOf(UObject::StaticClass()));
    EXPECT_FALSE(AActor::StaticClass().isChildOf(mesh));
    EXPECT_TRUE(UObject::StaticClass().isAbstract);
    EXPECT_EQ(UObject::StaticClass().create, nullptr);
    auto derived = registry.derivedClasses(AActor::StaticClass());
    // Sorted by name, the base itself included.
    EXPECT_TRUE(std::is_sorted(derived.begin(), derived.end(),
                               [](const TypeInfo* a, const TypeInfo* b) { return a->name < b->name; }));
    EXPECT_NE(std::find(derived.begin(), derived.end(), &AActor::StaticClass()), derived.end());
    EXPECT_NE(std::find(derived.begin(), derived.end(), &mesh), derived.end());
    for (const TypeInfo* type : derived)
        EXPECT_TRUE(type->isChildOf(AActor::StaticClass())) << type->name;
    EXPECT_EQ(std::find(derived.begin(), derived.end(), &UObject::StaticClass()), derived.end());
    EXPECT_THROW(registry.getClass("FVector", "test"), sp::NotFound); // a struct is not a class
    try {
        registry.getClass("AFoo", "UWorld.spawn_actor()");
        FAIL();
    } catch (const sp::NotFound& e) {
        EXPECT_STREQ(e.what(), "UWorld.spawn_actor(): class 'AFoo' is not registered");
    }
}

TEST_F(RegistryTest, InvokersConvertCheckAndReturnOutParameters) {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
    const FunctionInfo* spawn = UWorld::StaticClass().findFunction("spawn_actor");
    ASSERT_NE(spawn, nullptr);
    EXPECT_EQ(spawn->returnType.spelling(), "AActor");
    Value actor = spawn->invoke(&world, {{"uclass", Value(ClassName{"AStaticMeshActor"})},
                                         {"location", Value(Value::Dict{{"Z", Value(2.0)}})}});
    ASSERT_TRUE(actor.is<ObjectHandle>());
    auto* spawned = static_cast<AStaticMeshActor*>(ObjectTable::find(actor.as<ObjectHandle>()));
    ASSERT_NE(spawned, nullptr);
    EXPECT_EQ(spawned->GetActorLocation(), (FVector{0, 0, 2}));

    const FunctionInfo* bounds = AActor::StaticClass().findFunction("GetActorBounds");
    Value out =
        bounds->invoke(static_cast<ObjectBase*>(spawned), {{"bOnlyCollidingComponents", Value(false)}});
    ASSERT_TRUE(out.is<Value::Dict>());
    EXPECT_EQ(out.as<Value::Dict>().count("Origin"), 1u);
    EXPECT_EQ(out.as<Value::Dict>().count("BoxExtent"), 1u);

    EXPECT_THROW(spawn->invoke(&world, {}), sp::InvalidArgument); // missing uclass
    try {
        spawn->invoke(&world, {{"uclass", Value("AActor")}, {"locaton", Value()}});
        FAIL();
    } catch (const sp::InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "UWorld.spawn_actor(): unexpected argument 'locaton' (parameters: uclass, "
                               "location, rotation, name, tags)");
    }
}

TEST_F(RegistryTest, PropertiesUseSettersAndRejectWrongTypes) {
    sp::engine::Engine engine;
    AActor* actor = engine.GetGameWorld().spawn_actor(&AStaticMeshActor::StaticClass());
    auto* root = actor->RootComponent;
    const PropertyInfo* mobility = root->GetClass().findProperty("Mobility");
    mobility->set(static_cast<ObjectBase*>(root), Value(EnumValue{"EComponentMobility", 0}));
    EXPECT_EQ(root->Mobility, EComponentMobility::Static);
    const PropertyInfo* location = root->GetClass().findProperty("RelativeLocation");
    // The Setter runs, so a static component refuses to move through the property too.
    EXPECT_THROW(location->set(static_cast<ObjectBase*>(root), Value(Value::Dict{{"X", Value(1.0)}})),
                 sp::InvalidState);
    const PropertyInfo* rootProperty = AActor::StaticClass().findProperty("RootComponent");
    EXPECT_EQ(rootProperty->set, nullptr);
    EXPECT_TRUE(rootProperty->readOnly);
}

TEST_F(RegistryTest, PropertyPathsWalkReferencesListsAndStructsAndNameWhatIsMissing) {
    sp::engine::Engine engine;
    AActor* actor = engine.GetGameWorld().spawn_actor(&AStaticMeshActor::StaticClass());
    actor->Tags = {"crate", "prop"};
    EXPECT_EQ(getPath(*actor, "Tags[1]", "t").value.as<std::string>(), "prop");
    const PathValue z = getPath(*actor, "RootComponent.RelativeLocation.Z", "t");
    EXPECT_EQ(z.type.kind, TypeCode::Kind::Float);
    setPath(*actor, "RootComponent.RelativeLocation.Z", Value(2.5), "t");
    EXPECT_EQ(actor->RootComponent->RelativeLocation.Z, 2.5);
    setPath(*actor, "Tags[0]", Value("box"), "t");
    EXPECT_EQ(actor->Tags[0], "box");
    auto message = [&](std::string_view path) {
        try {
            getPath(*actor, path, "get_property()");
        } catch (const sp::Error& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message("Tags[2]"), "get_property(): 'Tags' has 2 items, no [2]");
    EXPECT_EQ(message("RootComponent.Nope"),
              "get_property(): class 'UStaticMeshComponent' has no property 'Nope' (at 'RootComponent')");
    EXPECT_EQ(message("Tags[1].X"), "get_property(): 'Tags[1]' is str, which has no field 'X'");
    // Malformed paths are refused where they go wrong, never read past their end.
    for (std::string_view bad :
         {"", ".", "Tags.", "Tags[", "Tags[]", "Tags[0", "Tags['0]", "Tags]", "Ta gs", "[0]"})
        EXPECT_NE(message(bad).find("property path"), std::string::npos) << bad << ": " << message(bad);
    EXPECT_THROW(setPath(*actor, "RootComponent", Value(), "t"), sp::InvalidArgument); // read-only
}
