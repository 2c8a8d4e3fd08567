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
    EXPECT_TRUE(ids.gbuffer);
    EXPECT_FALSE(ids.lighting);
    EXPECT_FALSE(ids.tonemap);
    EXPECT_FALSE(ids.shadow);
    PassSet hdr = ModalitySet{Modality::HdrColor}.requiredPasses(true);
    EXPECT_TRUE(hdr.lighting && hdr.shadow && !hdr.tonemap);
    PassSet color = ModalitySet{Modality::FinalColor}.requiredPasses(false);
    EXPECT_TRUE(color.gbuffer && color.lighting && color.tonemap && !color.shadow);
    EXPECT_FALSE(ModalitySet().requiredPasses(true).gbuffer);
}

TEST(ModalityTest, ShadingIsForwardWhenTheTargetsFitTheDrawBuffers) {
    // Colour, depth, normals and both ids: four targets, shaded where rasterised.
    const PassSet common = ModalitySet{Modality::FinalColor, Modality::Depth, Modality::Normal,
                                       Modality::ObjectIds, Modality::MaterialIds}
                               .requiredPasses(true);
    EXPECT_TRUE(common.forward);
    EXPECT_EQ(common.lightingTargets, 0u);
    EXPECT_EQ(common.surfaceTargets, targetBit(Target::Normal) | targetBit(Target::Depth) |
                                         targetBit(Target::Ids) | targetBit(Target::FinalColor));
    // The intrinsic images with their inputs: eight targets (roughness, metallic and AO share one).
    const ModalitySet intrinsics{
        Modality::FinalColor,      Modality::HdrColor,  Modality::BaseColor,           Modality::Metallic,
        Modality::Roughness,       Modality::ObjectIds, Modality::DiffuseIllumination, Modality::DiffuseOnly,
        Modality::SpecularResidual};
    EXPECT_TRUE(intrinsics.requiredPasses(true).forward);
    // Every modality: eleven targets, more than GL 4.5 promises, so a G-buffer and a lighting pass.
    const PassSet all = ModalitySet::all().requiredPasses(true);
    EXPECT_FALSE(all.forward);
    EXPECT_NE(all.surfaceTargets & targetBit(Target::Emissive), 0u);
    EXPECT_LE(std::popcount(all.surfaceTargets), kMaxForwardTargets);
    EXPECT_LE(std::popcount(all.lightingTargets), kMaxForwardTargets);
}

TEST(ModalityTest, HalfFloatRoundTrips) {
    for (float v : {0.0f, 1.0f, -2.5f, 0.1f, 1000.0f, 6.1e-5f, 65504.0f})
        EXPECT_NEAR(halfToFloat(floatToHalf(v)), v, std::abs(v) * 1e-3f + 1e-7f) << v;
    EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
    EXPECT_EQ(halfToFloat(0xc000), -2.0f);
}

} // namespace
} // namespace sp::render
