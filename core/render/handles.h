#pragma once
// Generation-checked handles for renderer resources. A handle is an (index, generation) pair: the
// index names a slot in the owning Scene, the generation changes whenever that slot is reused, so a
// handle to a removed object can never silently reach a new one (Scene throws sp::StaleObject).

#include <compare>
#include <cstdint>
#include <limits>
#include <ostream>

namespace sp::render {

template <typename Tag> struct Handle {
    static constexpr std::uint32_t kInvalidIndex = std::numeric_limits<std::uint32_t>::max();

    std::uint32_t index = kInvalidIndex;
    std::uint32_t generation = 0;

    // True when the handle was returned by a Scene (it may still be stale).
    bool isSet() const { return index != kInvalidIndex; }
    auto operator<=>(const Handle&) const = default;
};

template <typename Tag> std::ostream& operator<<(std::ostream& out, const Handle<Tag>& id) {
    return out << Tag::kName << "{" << id.index << ":" << id.generation << "}";
}

struct MeshTag {
    static constexpr const char* kName = "MeshId";
};
struct MaterialTag {
    static constexpr const char* kName = "MaterialId";
};
struct LightTag {
    static constexpr const char* kName = "LightId";
};
struct InstanceTag {
    static constexpr const char* kName = "InstanceId";
};
struct TextureTag {
    static constexpr const char* kName = "TextureId";
};

using MeshId = Handle<MeshTag>;
using MaterialId = Handle<MaterialTag>;
using LightId = Handle<LightTag>;
using InstanceId = Handle<InstanceTag>;
using TextureId = Handle<TextureTag>;

} // namespace sp::render
