#include "core/render/modality.h"

#include <array>
#include <bit>

#include "core/base/error.h"

namespace sp::render {
namespace {

constexpr std::array<ModalityInfo, kModalityCount> kInfos{{
#define SP_MODALITY_INFO(enumerator, name, dtype, channels)                                                  \
    {Modality::enumerator, #name, DType::dtype, channels},
    SP_RENDER_MODALITIES(SP_MODALITY_INFO)
#undef SP_MODALITY_INFO
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

Target targetOf(Modality modality) {
    switch (modality) {
    case Modality::FinalColor:
        return Target::FinalColor;
    case Modality::HdrColor:
        return Target::Hdr;
    case Modality::Depth:
        return Target::Depth;
    case Modality::Position:
        return Target::Position;
    case Modality::Normal:
        return Target::Normal;
    case Modality::ObjectIds:
    case Modality::MaterialIds:
        return Target::Ids;
    case Modality::BaseColor:
        return Target::BaseColor;
    case Modality::Roughness:
    case Modality::Metallic:
    case Modality::MaterialAo:
        return Target::Params;
    case Modality::DiffuseIllumination:
        return Target::DiffuseIllumination;
    case Modality::DiffuseOnly:
        return Target::DiffuseOnly;
    case Modality::SpecularResidual:
        return Target::SpecularResidual;
    }
    SP_THROW(InvalidArgument, "targetOf(): bad modality value ", int(modality));
}

std::string_view targetName(Target target) {
    static constexpr std::array<std::string_view, kTargetCount> kNames{"Position",    "Normal",
                                                                       "Depth",       "BaseColor",
                                                                       "Params",      "Ids",
                                                                       "Hdr",         "DiffuseIllumination",
                                                                       "DiffuseOnly", "SpecularResidual",
                                                                       "FinalColor",  "Record",
                                                                       "GBuffer",     "GBufferMaterial"};
    const auto index = static_cast<std::size_t>(target);
    SP_CHECK(index < kTargetCount, InvalidArgument, "targetName(): bad target value ", index);
    return kNames[index];
}

TargetMask ModalitySet::targets() const {
    TargetMask mask = 0;
    for (Modality m : list())
        mask |= targetBit(targetOf(m));
    return mask;
}

ModalitySet materialModalities() {
    return {Modality::BaseColor,  Modality::Roughness, Modality::Metallic,
            Modality::MaterialAo, Modality::ObjectIds, Modality::MaterialIds};
}

TargetMask ModalityPlan::targets() const {
    return rendered.targets() | (lookedUp.empty() ? 0 : targetBit(Target::Record));
}

ModalityPlan planModalities(const ModalitySet& modalities, bool softwareRasteriser,
                            const ModalitySet& uniform) {
    ModalityPlan plan{modalities, {}, {}};
    if (!softwareRasteriser)
        return plan;
    // Each step is taken while the plan needs more targets than one pass writes, and kept only where it
    // spares targets (a set that asked for none of a computed modality's inputs would render more).
    const auto targetCount = [](const ModalityPlan& p) { return std::popcount(p.targets()); };
    const bool diffuse = modalities.contains(Modality::DiffuseOnly);
    const bool residual = modalities.contains(Modality::SpecularResidual);
    if (targetCount(plan) > kMaxDrawTargets && (diffuse || residual)) {
        ModalityPlan candidate = plan;
        // diffuse_only's inputs; specular_residual needs diffuse_only's value, so those inputs too.
        candidate.rendered.remove(Modality::DiffuseOnly).remove(Modality::SpecularResidual);
        candidate.rendered.add(Modality::BaseColor)
            .add(Modality::Metallic)
            .add(Modality::DiffuseIllumination);
        if (diffuse)
            candidate.derived.add(Modality::DiffuseOnly);
        if (residual) {
            candidate.rendered.add(Modality::HdrColor);
            candidate.derived.add(Modality::SpecularResidual);
        }
        if (targetCount(candidate) < targetCount(plan))
            plan = candidate;
    }
    if (targetCount(plan) > kMaxDrawTargets && modalities.contains(Modality::Position)) {
        ModalityPlan candidate = plan;
        candidate.rendered.remove(Modality::Position).add(Modality::Depth); // the point at that depth
        candidate.derived.add(Modality::Position);
        if (targetCount(candidate) < targetCount(plan))
            plan = candidate;
    }
    // The uniform material modalities from the draw (its inputs to the intrinsics too), whenever that spares
    // a target and fits one pass: one R32UI target for up to three of base colour, parameters and ids.
    {
        ModalityPlan candidate = plan;
        for (Modality m : uniform.list())
            if (plan.rendered.contains(m) && materialModalities().contains(m)) {
                candidate.rendered.remove(m);
                candidate.lookedUp.add(m);
            }
        if (!candidate.lookedUp.empty() && targetCount(candidate) < targetCount(plan) &&
            targetCount(candidate) <= kMaxDrawTargets)
            plan = candidate;
    }
    return plan;
}

PassSet ModalitySet::requiredPasses(bool shadowsEnabled) const {
    PassSet passes;
    for (Modality m : list()) {
        passes.surface = true;
        passes.lighting = passes.lighting || needsLighting(m);
        passes.tonemap = passes.tonemap || m == Modality::FinalColor;
    }
    const TargetMask requested = targets();
    passes.shadow = passes.lighting && shadowsEnabled;
    if (!passes.surface)
        return passes;
    if (std::popcount(requested) <= kMaxDrawTargets) {
        passes.surfaceTargets = requested;
        return passes;
    }
    // The shaded targets go to the surface pass (only it shades), then the others in Target order
    // while draw buffers are left; the rest to the attribute pass.
    passes.surfaceTargets = requested & kShadedTargets;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        const TargetMask bit = TargetMask(1) << t;
        if ((requested & bit) == 0 || (passes.surfaceTargets & bit) != 0)
            continue;
        if (std::popcount(passes.surfaceTargets) < kMaxDrawTargets)
            passes.surfaceTargets |= bit;
        else
            passes.attributeTargets |= bit;
    }
    return passes;
}

namespace {
// The shaded targets in the surface pass and the exact ones in the attribute pass, in float targets: what
// averaging samples (multisampled or spatial) needs.
PassSet shadedApart(PassSet passes) {
    const TargetMask all = passes.surfaceTargets | passes.attributeTargets;
    passes.surfaceTargets = all & kShadedTargets;
    passes.attributeTargets = all & ~kShadedTargets;
    passes.compactTargets = false;
    return passes;
}
} // namespace

PassSet multisampled(PassSet passes, int samples) {
    if (samples <= 1 || !passes.lighting)
        return passes;
    passes = shadedApart(passes);
    passes.samples = samples;
    return passes;
}

PassSet spatiallySampled(PassSet passes, int count) {
    if (count <= 1 || !passes.lighting)
        return passes;
    passes = shadedApart(passes);
    passes.samples = 1; // see PassSet::spatialSamples
    passes.spatialSamples = count;
    return passes;
}

PassSet spatialSampleSurface(PassSet passes) {
    passes.attributeTargets = 0;
    passes.spatialSamples = 1;
    return passes;
}

} // namespace sp::render
