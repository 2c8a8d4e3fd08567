#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/sensors/material_library.h"

TEST(MaterialLibraryTest, BuiltinsWithOrWithoutPrefixAndLibraryOverrides) {
    ASSERT_NE(sp::sensors::builtinMaterial("Gold"), nullptr);
    EXPECT_EQ(sp::sensors::builtinMaterial("/Engine/Materials/Gold"), sp::sensors::builtinMaterial("Gold"));
    EXPECT_EQ(sp::sensors::builtinMaterial("Unobtainium"), nullptr);
    EXPECT_EQ(sp::sensors::builtinMaterialNames().front(), "Default");

    sp::engine::Engine engine;
    auto* library =
        static_cast<AMaterialLibrary*>(engine.GetGameWorld().spawn_actor(&AMaterialLibrary::StaticClass()));
    FMaterialDesc red;
    red.BaseColor = {1.0f, 0.0f, 0.0f, 1.0f};
    library->SetMaterial("Gold", red);
    EXPECT_EQ(library->GetMaterial("Gold"), red);                                     // the library wins
    EXPECT_EQ(library->GetMaterial("Metal"), *sp::sensors::builtinMaterial("Metal")); // then built-ins
    EXPECT_EQ(library->GetMaterial("Nope"), *sp::sensors::builtinMaterial("Default"));
    EXPECT_THROW(library->SetMaterial("", red), sp::InvalidArgument);
}
