#include <bit>

#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/render/image_buffer.h"
#include "core/render/modality.h"

namespace sp::render {
namespace {

TEST(ModalityTest, TableMatchesTheDesign) {
    EXPECT_EQ(modalityName(Modality::FinalColor), "final_color");
    EXPECT_EQ(modalityInfo(Modality::FinalColor).dtype, DType::UInt8);
    EXPECT_EQ(modalityByteSize(Modality::FinalColor, 4, 3), 4u * 3 * 4);
    EXPECT_EQ(modalityByteSize(Modality::HdrColor, 4, 3), 4u * 3 * 4 * 2);
    EXPECT_EQ(modalityByteSize(Modality::Depth, 4, 3), 4u * 3 * 4);
    EXPECT_EQ(modalityByteSize(Modality::Position, 4, 3), 4u * 3 * 3 * 4);
    EXPECT_EQ(modalityByteSize(Modality::ObjectIds, 4, 3), 4u * 3 * 4);
    EXPECT_EQ(modalityByteSize(Modality::Roughness, 4, 3), 4u * 3 * 2);
    EXPECT_EQ(modalityByteSize(Modality::SpecularResidual, 4, 3), 4u * 3 * 3 * 2);
    for (Modality m : ModalitySet::all().list())
        EXPECT_EQ(modalityFromName(modalityName(m)), m);
    EXPECT_EQ(ModalitySet::all().size(), kModalityCount);
}

TEST(ModalityTest, UnknownNameIsNotFoundWithTheName) {
    try {
        modalityFromName("colour");
        FAIL();
    } catch (const NotFound& e) {
        EXPECT_NE(
            std::string(e.what()).find("modalityFromName(): unknown modality 'colour' (known: final_color,"),
            std::string::npos)
            << e.what();
    }
}

TEST(ModalityTest, OnlyNeededPassesAreRequired) {
    PassSet ids = ModalitySet{Modality::ObjectIds, Modality::Depth}.requiredPasses(true);
    EXPECT_TRUE(ids.surface);
    EXPECT_FALSE(ids.lighting);
    EXPECT_FALSE(ids.tonemap);
    EXPECT_FALSE(ids.shadow);
    PassSet hdr = ModalitySet{Modality::HdrColor}.requiredPasses(true);
    EXPECT_TRUE(hdr.lighting && hdr.shadow && !hdr.tonemap);
    PassSet color = ModalitySet{Modality::FinalColor}.requiredPasses(false);
    EXPECT_TRUE(color.surface && color.lighting && color.tonemap && !color.shadow);
    EXPECT_FALSE(ModalitySet().requiredPasses(true).surface);
}

TEST(ModalityTest, MultisampledPassesDrawTheShadedTargetsApartFromTheExactOnes) {
    PassSet common =
        ModalitySet{Modality::FinalColor, Modality::Depth, Modality::ObjectIds}.requiredPasses(true);
    common.compactTargets = true;
    const PassSet split = multisampled(common, 4);
    EXPECT_EQ(split.samples, 4);
    EXPECT_FALSE(split.compactTargets);
    EXPECT_EQ(split.surfaceTargets, targetBit(Target::FinalColor));
    EXPECT_EQ(split.attributeTargets, targetBit(Target::Depth) | targetBit(Target::Ids));
    const PassSet all = multisampled(ModalitySet::all().requiredPasses(true), 8);
    EXPECT_EQ(all.surfaceTargets, kShadedTargets);
    EXPECT_EQ(all.surfaceTargets | all.attributeTargets, ModalitySet::all().targets());
    // Nothing shaded, or one sample: unchanged.
    const PassSet ids = ModalitySet{Modality::ObjectIds}.requiredPasses(true);
    EXPECT_EQ(multisampled(ids, 4), ids);
    EXPECT_EQ(multisampled(common, 1), common);
}

TEST(ModalityTest, OnePassWhenTheTargetsFitTheDrawBuffers) {
    // Colour, depth, normals and both ids: four targets.
    const PassSet common = ModalitySet{Modality::FinalColor, Modality::Depth, Modality::Normal,
                                       Modality::ObjectIds, Modality::MaterialIds}
                               .requiredPasses(true);
    EXPECT_TRUE(common.lighting);
    EXPECT_EQ(common.attributeTargets, 0u);
    EXPECT_EQ(common.surfaceTargets, targetBit(Target::Normal) | targetBit(Target::Depth) |
                                         targetBit(Target::Ids) | targetBit(Target::FinalColor));
    // The intrinsic images with their inputs: eight targets (roughness, metallic and AO share one).
    const ModalitySet intrinsics{
        Modality::FinalColor,      Modality::HdrColor,  Modality::BaseColor,           Modality::Metallic,
        Modality::Roughness,       Modality::ObjectIds, Modality::DiffuseIllumination, Modality::DiffuseOnly,
        Modality::SpecularResidual};
    EXPECT_EQ(intrinsics.requiredPasses(true).attributeTargets, 0u);
}

TEST(ModalityTest, TargetsPastTheDrawBuffersGoToTheAttributePass) {
    // Every modality: eleven targets, more than GL 4.5 promises one pass. The shaded ones stay in the
    // surface pass (only it shades), the first attributes fill it up, the rest go to the attribute pass.
    const PassSet all = ModalitySet::all().requiredPasses(true);
    constexpr TargetMask kShaded = targetBit(Target::Hdr) | targetBit(Target::DiffuseIllumination) |
                                   targetBit(Target::DiffuseOnly) | targetBit(Target::SpecularResidual) |
                                   targetBit(Target::FinalColor);
    EXPECT_EQ(all.surfaceTargets,
              kShaded | targetBit(Target::Position) | targetBit(Target::Normal) | targetBit(Target::Depth));
    EXPECT_EQ(all.attributeTargets,
              targetBit(Target::BaseColor) | targetBit(Target::Params) | targetBit(Target::Ids));
    EXPECT_EQ(std::popcount(all.surfaceTargets), kMaxDrawTargets);
    EXPECT_EQ(all.surfaceTargets & all.attributeTargets, 0u);
    // Without colour nothing is shaded: the attributes alone fit one pass.
    ModalitySet attributes = ModalitySet::all();
    for (Modality m : {Modality::FinalColor, Modality::HdrColor, Modality::DiffuseIllumination,
                       Modality::DiffuseOnly, Modality::SpecularResidual})
        attributes.remove(m);
    const PassSet plain = attributes.requiredPasses(true);
    EXPECT_FALSE(plain.lighting || plain.shadow);
    EXPECT_EQ(plain.attributeTargets, 0u);
}

TEST(ModalityTest, ASoftwareRasteriserComputesTheIntrinsicsThatOtherModalitiesDefine) {
    // All 14 on a software rasteriser: diffuse_only and specular_residual come from the images read, and
    // position from depth, so eight targets are drawn instead of eleven, in one pass.
    const ModalityPlan all = planModalities(ModalitySet::all(), true);
    EXPECT_EQ(all.derived,
              (ModalitySet{Modality::DiffuseOnly, Modality::SpecularResidual, Modality::Position}));
    EXPECT_FALSE(all.rendered.contains(Modality::DiffuseOnly) ||
                 all.rendered.contains(Modality::SpecularResidual) ||
                 all.rendered.contains(Modality::Position));
    EXPECT_TRUE(all.rendered.contains(Modality::Depth));
    EXPECT_EQ(std::popcount(all.rendered.targets()), 8);
    EXPECT_EQ(all.rendered.requiredPasses(true).attributeTargets, 0u);
    // Once the intrinsics are computed, a set that fits one pass keeps its position rendered: all but depth.
    ModalitySet noDepth = ModalitySet::all();
    noDepth.remove(Modality::Depth);
    EXPECT_EQ(planModalities(noDepth, true).derived,
              (ModalitySet{Modality::DiffuseOnly, Modality::SpecularResidual}));
    // On a GPU, and for sets one pass writes, everything is rendered.
    EXPECT_EQ(planModalities(ModalitySet::all(), false), (ModalityPlan{ModalitySet::all(), {}, {}}));
    const ModalitySet intrinsics{Modality::HdrColor,    Modality::BaseColor,
                                 Modality::Metallic,    Modality::DiffuseIllumination,
                                 Modality::DiffuseOnly, Modality::SpecularResidual};
    EXPECT_EQ(planModalities(intrinsics, true), (ModalityPlan{intrinsics, {}, {}}));
    // specular_residual alone beside many attributes: its inputs (diffuse_only's among them) are rendered,
    // diffuse_only is not returned (and position still needs a target too many).
    ModalitySet residual = ModalitySet::all();
    residual.remove(Modality::DiffuseOnly);
    const ModalityPlan plan = planModalities(residual, true);
    EXPECT_EQ(plan.derived, (ModalitySet{Modality::SpecularResidual, Modality::Position}));
    EXPECT_TRUE(plan.rendered.contains(Modality::BaseColor) && plan.rendered.contains(Modality::Metallic));
    // When computing the intrinsics would draw more targets than it spares, they are rendered: position,
    // normal, depth, ids, final colour, HDR colour, diffuse illumination, diffuse only and specular residual
    // (9 targets) would need base colour and the parameters (10). Position from the depth the set has
    // spares one, so that set is drawn in one pass.
    const ModalitySet without{Modality::Position,
                              Modality::Normal,
                              Modality::Depth,
                              Modality::ObjectIds,
                              Modality::FinalColor,
                              Modality::HdrColor,
                              Modality::DiffuseIllumination,
                              Modality::DiffuseOnly,
                              Modality::SpecularResidual};
    ModalitySet withoutPosition = without;
    withoutPosition.remove(Modality::Position);
    EXPECT_EQ(planModalities(without, true), (ModalityPlan{withoutPosition, {Modality::Position}, {}}));
}

// A software rasteriser looks the material modalities each draw gives all its pixels up from the draw
// (Target::Record) whenever that draws fewer targets in one pass; never on a GPU, and base colour, roughness
// and metallic only where no texture varies them.
TEST(ModalityTest, MaterialModalitiesAreLookedUpWhereThatSparesTargets) {
    const ModalitySet untextured = materialModalities();
    const ModalityPlan all = planModalities(ModalitySet::all(), true, untextured);
    EXPECT_EQ(all.lookedUp, materialModalities());
    EXPECT_EQ(all.derived,
              (ModalitySet{Modality::DiffuseOnly, Modality::SpecularResidual, Modality::Position}));
    EXPECT_EQ(all.targets(), targetBit(Target::FinalColor) | targetBit(Target::Hdr) |
                                 targetBit(Target::Depth) | targetBit(Target::Normal) |
                                 targetBit(Target::DiffuseIllumination) | targetBit(Target::Record));
    EXPECT_TRUE(planModalities(ModalitySet::all(), true).lookedUp.empty()) << "nothing uniform";
    EXPECT_TRUE(planModalities(ModalitySet::all(), false, untextured).lookedUp.empty()) << "a GPU";
    // A base colour texture: the parameters and ids from the draw, base colour drawn (7 targets).
    ModalitySet noBase = untextured;
    noBase.remove(Modality::BaseColor);
    const ModalityPlan textured = planModalities(ModalitySet::all(), true, noBase);
    EXPECT_EQ(textured.lookedUp, noBase);
    EXPECT_TRUE(textured.rendered.contains(Modality::BaseColor));
    EXPECT_EQ(std::popcount(textured.targets()), 7);
    // A roughness-metallic texture: base colour, AO and ids from the draw; the parameters drawn (7 targets).
    ModalitySet noParams = untextured;
    noParams.remove(Modality::Roughness).remove(Modality::Metallic);
    const ModalityPlan rm = planModalities(ModalitySet::all(), true, noParams);
    EXPECT_EQ(rm.lookedUp, noParams);
    EXPECT_TRUE(rm.rendered.contains(Modality::Roughness) && rm.rendered.contains(Modality::Metallic));
    EXPECT_EQ(std::popcount(rm.targets()), 7);
    // Base colour and ids (two targets) become one; one of them alone, or beside colour, spares nothing.
    const ModalitySet two{Modality::BaseColor, Modality::ObjectIds};
    EXPECT_EQ(planModalities(two, true, untextured), (ModalityPlan{{}, {}, two}));
    EXPECT_TRUE(
        planModalities({Modality::FinalColor, Modality::ObjectIds, Modality::MaterialIds}, true, untextured)
            .lookedUp.empty());
    EXPECT_TRUE(planModalities({Modality::Roughness, Modality::Metallic}, true, untextured).lookedUp.empty());
    // Colour, depth, normal, ids and base colour: ids and base colour from the draw.
    const ModalityPlan dataset = planModalities(
        {Modality::FinalColor, Modality::Depth, Modality::Normal, Modality::ObjectIds, Modality::BaseColor},
        true, untextured);
    EXPECT_EQ(dataset.lookedUp, (ModalitySet{Modality::ObjectIds, Modality::BaseColor}));
    EXPECT_EQ(std::popcount(dataset.targets()), 4);
}

TEST(ModalityTest, HalfFloatRoundTrips) {
    for (float v : {0.0f, 1.0f, -2.5f, 0.1f, 1000.0f, 6.1e-5f, 65504.0f})
        EXPECT_NEAR(halfToFloat(floatToHalf(v)), v, std::abs(v) * 1e-3f + 1e-7f) << v;
    EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
    EXPECT_EQ(halfToFloat(0xc000), -2.0f);
}

} // namespace
} // namespace sp::render
