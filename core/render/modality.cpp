#include "core/render/modality.h"

#include <array>

#include "core/base/error.h"

namespace sp::render {
namespace {

constexpr std::array<ModalityInfo, kModalityCount> kInfos{{
    {Modality::FinalColor, "final_color", DType::UInt8, 4},
    {Modality::HdrColor, "hdr_color", DType::Float16, 4},
    {Modality::Depth, "depth", DType::Float32, 1},
    {Modality::Position, "position", DType::Float32, 3},
    {Modality::Normal, "normal", DType::Float32, 3},
    {Modality::ObjectIds, "object_ids", DType::UInt32, 1},
    {Modality::MaterialIds, "material_ids", DType::UInt32, 1},
    {Modality::BaseColor, "base_color", DType::Float16, 3},
    {Modality::Roughness, "roughness", DType::Float16, 1},
    {Modality::Metallic, "metallic", DType::Float16, 1},
    {Modality::MaterialAo, "material_ao", DType::Float16, 1},
    {Modality::DiffuseIllumination, "diffuse_illumination", DType::Float16, 3},
    {Modality::DiffuseOnly, "diffuse_only", DType::Float16, 3},
    {Modality::SpecularResidual, "specular_residual", DType::Float16, 3},
}};

bool needsLighting(Modality m) {
    return m == Modality::FinalColor || m == Modality::HdrColor || m == Modality::DiffuseIllumination ||
           m == Modality::DiffuseOnly || m == Modality::SpecularResidual;
}

} // namespace

const ModalityInfo& modalityInfo(Modality modality) {
    auto index = static_cast<std::size_t>(modality);
    SP_CHECK(index < kModalityCount, InvalidArgument, "modalityInfo(): bad modality value ", index);
    return kInfos[index];
}

std::string_view modalityName(Modality modality) {
    return modalityInfo(modality).name;
}

std::size_t dtypeSize(DType dtype) {
    switch (dtype) {
    case DType::UInt8:
        return 1;
    case DType::Float16:
        return 2;
    case DType::UInt32:
    case DType::Float32:
        return 4;
    }
    return 0;
}

std::string_view dtypeName(DType dtype) {
    switch (dtype) {
    case DType::UInt8:
        return "uint8";
    case DType::UInt32:
        return "uint32";
    case DType::Float16:
        return "float16";
    case DType::Float32:
        return "float32";
    }
    return "?";
}

std::size_t modalityByteSize(Modality modality, int width, int height) {
    const ModalityInfo& info = modalityInfo(modality);
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
           static_cast<std::size_t>(info.channels) * dtypeSize(info.dtype);
}

Modality modalityFromName(std::string_view name) {
    for (const ModalityInfo& info : kInfos)
        if (info.name == name)
            return info.modality;
    std::string known;
    for (const ModalityInfo& info : kInfos)
        known += (known.empty() ? "" : ", ") + std::string(info.name);
    SP_THROW(NotFound, "modalityFromName(): unknown modality '", name, "' (known: ", known, ")");
}

ModalitySet::ModalitySet(std::initializer_list<Modality> modalities) {
    for (Modality m : modalities)
        add(m);
}

ModalitySet ModalitySet::all() {
    ModalitySet set;
    set.bits_.set();
    return set;
}

ModalitySet ModalitySet::fromNames(const std::vector<std::string>& names) {
    ModalitySet set;
    for (const std::string& name : names)
        set.add(modalityFromName(name));
    return set;
}

ModalitySet& ModalitySet::add(Modality modality) {
    bits_.set(static_cast<std::size_t>(modalityInfo(modality).modality));
    return *this;
}

ModalitySet& ModalitySet::remove(Modality modality) {
    bits_.reset(static_cast<std::size_t>(modalityInfo(modality).modality));
    return *this;
}

std::vector<Modality> ModalitySet::list() const {
    std::vector<Modality> out;
    for (std::size_t i = 0; i < kModalityCount; ++i)
        if (bits_.test(i))
            out.push_back(static_cast<Modality>(i));
    return out;
}

std::vector<std::string> ModalitySet::names() const {
    std::vector<std::string> out;
    for (Modality m : list())
        out.emplace_back(modalityName(m));
    return out;
}

PassSet ModalitySet::requiredPasses(bool shadowsEnabled) const {
    PassSet passes;
    for (Modality m : list()) {
        passes.gbuffer = true;
        passes.lighting = passes.lighting || needsLighting(m);
        passes.tonemap = passes.tonemap || m == Modality::FinalColor;
    }
    passes.shadow = passes.lighting && shadowsEnabled;
    return passes;
}

} // namespace sp::render
