// The engine's reflected ECameraModality and FCameraPixels have exactly the renderer's modalities, in its
// order and with its names (render_subsystem.cpp checks each entry at compile time; this checks there is
// nothing more).

#include <gtest/gtest.h>

#include <string>

#include "core/engine/engine.h"
#include "core/reflect/registry.h"
#include "core/render/modality.h"

namespace {

TEST(CameraModalities, TheReflectedEnumAndPixelsHaveExactlyTheRenderersModalities) {
    sp::engine::Engine engine; // registers the engine's types
    const sp::reflect::EnumInfo* modalities = sp::reflect::Registry::get().findEnum("ECameraModality");
    const sp::reflect::TypeInfo* pixels = sp::reflect::Registry::get().findType("FCameraPixels");
    ASSERT_NE(modalities, nullptr);
    ASSERT_NE(pixels, nullptr);
    ASSERT_EQ(modalities->entries.size(), sp::render::kModalityCount);
    ASSERT_EQ(pixels->properties.size(), sp::render::kModalityCount);
    for (std::size_t i = 0; i < sp::render::kModalityCount; ++i) {
        const std::string name(sp::render::modalityName(static_cast<sp::render::Modality>(i)));
        EXPECT_EQ(modalities->entries[i].second, int64_t(i)) << name;
        EXPECT_EQ(pixels->properties[i].name, name);
    }
}

} // namespace
