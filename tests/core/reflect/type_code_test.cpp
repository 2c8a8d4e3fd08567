#include <gtest/gtest.h>

#include "core/engine/engine.h"
#include "core/reflect/registry.h"
#include "core/reflect/type_code.h"
#include "core/world/actor.h"

using namespace sp::reflect;
using Kind = TypeCode::Kind;

TEST(TypeCode, SpellsThePythonAnnotation) {
    EXPECT_EQ(TypeCode(Kind::Void).spelling(), "None");
    EXPECT_EQ(TypeCode(Kind::Float).spelling(), "float");
    EXPECT_EQ(TypeCode(Kind::Object, "AActor", true).spelling(), "AActor | None");
    EXPECT_EQ(TypeCode(Kind::Class, "APawn", true).spelling(), "type[APawn] | None");
    EXPECT_EQ(TypeCode(Kind::Array, "float32").spelling(), "NDArray[np.float32]");
    EXPECT_EQ(TypeCode(Kind::List, TypeCode(Kind::Object, "AActor")).spelling(), "list[AActor]");
    EXPECT_EQ(TypeCode(Kind::Dict, TypeCode(Kind::List, TypeCode(Kind::Struct, "FVector"))).spelling(),
              "dict[str, list[FVector]]");
}

TEST(TypeCode, WireFormIsKindNameOptionalElement) {
    const Value wire = TypeCode(Kind::List, TypeCode(Kind::Enum, "EComponentMobility")).toValue();
    const auto& parts = wire.as<Value::List>();
    ASSERT_EQ(parts.size(), 4u);
    EXPECT_EQ(parts[0].as<std::string>(), "list");
    EXPECT_EQ(parts[1].as<std::string>(), "");
    EXPECT_FALSE(parts[2].as<bool>());
    const auto& element = parts[3].as<Value::List>();
    EXPECT_EQ(element[0].as<std::string>(), "enum");
    EXPECT_EQ(element[1].as<std::string>(), "EComponentMobility");
    EXPECT_TRUE(element[3].isNone());
}

// The generated registry records each member's declared type as the IR says, nullability included.
TEST(TypeCode, RegistryRecordsDeclaredTypes) {
    sp::engine::registerEngineTypes();
    const TypeInfo& actor = Registry::get().getClass("AActor", "test");
    EXPECT_EQ(actor.findProperty("RootComponent")->type, TypeCode(Kind::Object, "USceneComponent", true));
    EXPECT_EQ(actor.findProperty("Tags")->type, TypeCode(Kind::List, TypeCode(Kind::Str)));
    const FunctionInfo* bounds = actor.findFunction("GetActorBounds");
    ASSERT_NE(bounds, nullptr);
    EXPECT_EQ(bounds->returnType, TypeCode(Kind::Void));
    for (const ParamInfo& param : bounds->params) {
        if (param.isOut) {
            EXPECT_EQ(param.type, TypeCode(Kind::Struct, "FVector")) << param.name;
        }
    }
}
