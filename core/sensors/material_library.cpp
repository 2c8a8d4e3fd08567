#include "core/sensors/material_library.h"

#include <array>
#include <cmath>
#include <string_view>

#include "core/render/material.h"

namespace sp::sensors {
namespace {

constexpr std::string_view kMaterialsPrefix = "/Engine/Materials/";

FMaterialDesc make(float r, float g, float b, float roughness, float metallic = 0.0f) {
    FMaterialDesc desc;
    desc.BaseColor = {r, g, b, 1.0f};
    desc.Roughness = roughness;
    desc.Metallic = metallic;
    return desc;
}

FMaterialDesc emissive() {
    FMaterialDesc desc = make(1.0f, 1.0f, 1.0f, 0.9f);
    desc.Emissive = {4.0f, 3.6f, 3.0f, 1.0f};
    return desc;
}

// Linear base colours of common surfaces (roughly measured albedos, not artistic sRGB values).
const std::array<std::pair<std::string_view, FMaterialDesc>, 19>& builtins() {
    static const std::array<std::pair<std::string_view, FMaterialDesc>, 19> table{{
        {"Default", make(0.8f, 0.8f, 0.8f, 0.5f)},
        {"White", make(0.9f, 0.9f, 0.9f, 0.6f)},
        {"Black", make(0.02f, 0.02f, 0.02f, 0.5f)},
        {"Grey", make(0.3f, 0.3f, 0.3f, 0.7f)},
        {"Red", make(0.7f, 0.05f, 0.04f, 0.4f)},
        {"Green", make(0.08f, 0.5f, 0.1f, 0.4f)},
        {"Blue", make(0.05f, 0.12f, 0.6f, 0.4f)},
        {"Yellow", make(0.8f, 0.6f, 0.05f, 0.4f)},
        {"Wood", make(0.35f, 0.18f, 0.08f, 0.6f)},
        {"Plaster", make(0.75f, 0.72f, 0.66f, 0.9f)},
        {"Fabric", make(0.25f, 0.3f, 0.45f, 1.0f)},
        {"Metal", make(0.91f, 0.92f, 0.92f, 0.3f, 1.0f)},
        {"Gold", make(1.0f, 0.77f, 0.34f, 0.25f, 1.0f)},
        {"Plastic", make(0.6f, 0.6f, 0.6f, 0.25f)},
        {"Mirror", make(0.97f, 0.97f, 0.97f, 0.02f, 1.0f)},
        {"Emissive", emissive()},
        // The lanes' drawn road (AZoneGraphData): asphalt, concrete sidewalks, white paint.
        {"Asphalt", make(0.06f, 0.06f, 0.065f, 0.9f)},
        {"Concrete", make(0.45f, 0.44f, 0.42f, 0.85f)},
        {"LaneMarking", make(0.8f, 0.8f, 0.75f, 0.6f)},
    }};
    return table;
}

bool nonNegative(const FLinearColor& c) {
    return std::isfinite(c.R) && std::isfinite(c.G) && std::isfinite(c.B) && c.R >= 0.0f && c.G >= 0.0f &&
           c.B >= 0.0f;
}

bool unit(float value) {
    return value >= 0.0f && value <= 1.0f;
}

} // namespace

void checkMaterial(const FMaterialDesc& m, const std::string& context) {
    SP_CHECK(nonNegative(m.BaseColor), InvalidArgument, context, ": BaseColor must be finite and >= 0, got (",
             m.BaseColor.R, ", ", m.BaseColor.G, ", ", m.BaseColor.B, ")");
    SP_CHECK(unit(m.Roughness), InvalidArgument, context, ": Roughness must be in [0, 1], got ", m.Roughness);
    SP_CHECK(unit(m.Metallic), InvalidArgument, context, ": Metallic must be in [0, 1], got ", m.Metallic);
    SP_CHECK(unit(m.AmbientOcclusion), InvalidArgument, context, ": AmbientOcclusion must be in [0, 1], got ",
             m.AmbientOcclusion);
    SP_CHECK(nonNegative(m.Emissive), InvalidArgument, context, ": Emissive must be finite and >= 0, got (",
             m.Emissive.R, ", ", m.Emissive.G, ", ", m.Emissive.B, ")");
    SP_CHECK(sp::render::Material::validTextureSize(m.TextureSize), InvalidArgument, context,
             ": TextureSize must be 0 (the mesh's uvs) or finite and >= 1e-6 m, got ", m.TextureSize);
}

const FMaterialDesc* builtinMaterial(const std::string& fullName) {
    std::string_view name = fullName;
    if (name.starts_with(kMaterialsPrefix))
        name.remove_prefix(kMaterialsPrefix.size());
    for (const auto& [builtinName, desc] : builtins())
        if (builtinName == name)
            return &desc;
    return nullptr;
}

std::vector<std::string> builtinMaterialNames() {
    std::vector<std::string> names;
    for (const auto& entry : builtins())
        names.emplace_back(entry.first);
    return names;
}

} // namespace sp::sensors

void AMaterialLibrary::SetMaterial(const std::string& Name, const FMaterialDesc& Material) {
    SP_CHECK(!Name.empty(), sp::InvalidArgument, "AMaterialLibrary.SetMaterial(): Name must not be empty");
    sp::sensors::checkMaterial(Material, "AMaterialLibrary.SetMaterial(): material '" + Name + "'");
    Materials[Name] = Material;
}

void AMaterialLibrary::SetMaterials(const std::map<std::string, FMaterialDesc>& NewMaterials) {
    for (const auto& [name, material] : NewMaterials) {
        SP_CHECK(!name.empty(), sp::InvalidArgument,
                 "AMaterialLibrary.SetMaterials(): a material name is empty");
        sp::sensors::checkMaterial(material, "AMaterialLibrary.SetMaterials(): material '" + name + "'");
    }
    Materials = NewMaterials;
}

FMaterialDesc AMaterialLibrary::GetMaterial(const std::string& Name) const {
    if (auto it = Materials.find(Name); it != Materials.end())
        return it->second;
    const FMaterialDesc* builtin = sp::sensors::builtinMaterial(Name.empty() ? "Default" : Name);
    return builtin ? *builtin : *sp::sensors::builtinMaterial("Default");
}

std::vector<std::string> AMaterialLibrary::GetBuiltinMaterialNames() const {
    return sp::sensors::builtinMaterialNames();
}
