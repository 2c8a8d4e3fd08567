// The computed intrinsic images against the definitions, value by value, in float32 rounded to float16.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/render/derived_images.h"
#include "core/render/image_buffer.h"

namespace sp::render {
namespace {

std::vector<std::uint16_t> halves(std::size_t count, float low, float high, std::mt19937& random) {
    std::uniform_real_distribution<float> value(low, high);
    std::vector<std::uint16_t> out(count);
    for (auto& h : out)
        h = floatToHalf(value(random));
    return out;
}

// Pixel counts around the eight the vector path takes at once: its tail goes through the scalar path.
class DerivedImages : public ::testing::TestWithParam<std::size_t> {};

TEST_P(DerivedImages, DiffuseOnlyIsBaseTimesDielectricTimesIllumination) {
    const std::size_t pixels = GetParam();
    std::mt19937 random(7);
    const auto base = halves(3 * pixels, 0.0f, 1.0f, random), metallic = halves(pixels, 0.0f, 1.0f, random),
               illumination = halves(3 * pixels, 0.0f, 40.0f, random);
    std::vector<std::uint16_t> out(3 * pixels, 0xffff);
    computeDiffuseOnly(base.data(), metallic.data(), illumination.data(), out.data(), pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const float expected = halfToFloat(base[3 * p + c]) * (1.0f - halfToFloat(metallic[p])) *
                                   halfToFloat(illumination[3 * p + c]);
            ASSERT_EQ(out[3 * p + c], floatToHalf(expected)) << "pixel " << p << " channel " << c;
        }
}

TEST_P(DerivedImages, SpecularResidualIsHdrLessDiffuse) {
    const std::size_t pixels = GetParam();
    std::mt19937 random(11);
    const auto hdr = halves(4 * pixels, -1.0f, 60.0f, random),
               diffuse = halves(3 * pixels, 0.0f, 30.0f, random);
    std::vector<std::uint16_t> out(3 * pixels, 0xffff);
    computeSpecularResidual(hdr.data(), diffuse.data(), out.data(), pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const float expected = halfToFloat(hdr[4 * p + c]) - halfToFloat(diffuse[3 * p + c]);
            ASSERT_EQ(out[3 * p + c], floatToHalf(expected)) << "pixel " << p << " channel " << c;
        }
}

// A unit normal's octahedral coordinates as the shaders' normalTarget() computes them, in float32.
std::array<float, 2> octahedral(const Eigen::Vector3f& n) {
    const float l1 = std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z());
    const float x = n.x() / l1, y = n.y() / l1;
    if (n.z() >= 0.0f)
        return {x, y};
    return {(1.0f - std::abs(y)) * (x >= 0.0f ? 1.0f : -1.0f),
            (1.0f - std::abs(x)) * (y >= 0.0f ? 1.0f : -1.0f)};
}

// Every direction comes back within a few float32 ulps, the axes and the folds' edges exactly; the
// background (kNoOctahedralNormal) and a value that is not a number come back as the zero vector.
TEST_P(DerivedImages, OctahedralNormalsDecodeToTheUnitVectorsEncoded) {
    const std::size_t pixels = GetParam();
    std::mt19937 random(13);
    std::normal_distribution<float> gauss;
    const std::vector<Eigen::Vector3f> exact{{0, 0, 1},  {0, 0, -1}, {1, 0, 0},
                                             {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}};
    std::vector<Eigen::Vector3f> normals(pixels);
    std::vector<float> encoded(2 * pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        Eigen::Vector3f n(gauss(random), gauss(random), gauss(random));
        if (p % 11 < exact.size())
            n = exact[p % 11];
        else if (p % 11 == 6)
            n.z() = 0.0f; // on the equator, where the lower hemisphere folds
        normals[p] = n.normalized();
        const auto xy = octahedral(normals[p]);
        encoded[2 * p] = xy[0];
        encoded[2 * p + 1] = xy[1];
        if (p % 11 == 7) {
            encoded[2 * p] = encoded[2 * p + 1] = kNoOctahedralNormal;
            normals[p].setZero();
        } else if (p % 11 == 8) {
            encoded[2 * p] = std::numeric_limits<float>::quiet_NaN();
            normals[p].setZero();
        }
    }
    std::vector<float> out(3 * pixels, -5.0f);
    decodeOctahedralNormals(encoded.data(), out.data(), pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        const Eigen::Vector3f decoded(out[3 * p], out[3 * p + 1], out[3 * p + 2]);
        if (p % 11 < exact.size() || p % 11 == 7 || p % 11 == 8)
            ASSERT_EQ(decoded, normals[p]) << "pixel " << p;
        else
            ASSERT_LE((decoded - normals[p]).cwiseAbs().maxCoeff(), 4e-7f) << "pixel " << p;
    }
}

// Each pixel gets its draw's ids and factors, the background (record 0) zeros, and only the images asked
// for are written; a record past the draws is refused naming the pixel.
TEST_P(DerivedImages, MaterialsAreLookedUpFromTheRecordedDraw) {
    const std::size_t pixels = GetParam();
    const std::vector<DrawMaterial> draws{{7, 70, {0x3c00, 0x3800, 0x3400}, 0x3a00, 0x0000, 0x3bff},
                                          {8, 80, {0x2e66, 0x0001, 0x7bff}, 0x3266, 0x3c00, 0x3c00}};
    std::vector<std::uint32_t> record(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        record[p] = std::uint32_t(p % 3); // background, first draw, second draw
    std::vector<std::uint32_t> objectIds(pixels, 99), materialIds(pixels, 99);
    std::vector<std::uint16_t> base(3 * pixels, 9), roughness(pixels, 9), ao(pixels, 9);
    MaterialImages out;
    out.objectIds = objectIds.data();
    out.materialIds = materialIds.data();
    out.baseColor = base.data();
    out.roughness = roughness.data();
    out.ambientOcclusion = ao.data(); // no metallic asked for
    lookUpMaterials(record.data(), draws, pixels, out);
    for (std::size_t p = 0; p < pixels; ++p) {
        const DrawMaterial expected = record[p] == 0 ? DrawMaterial{} : draws[record[p] - 1];
        ASSERT_EQ(objectIds[p], expected.objectId) << p;
        ASSERT_EQ(materialIds[p], expected.materialId) << p;
        for (std::size_t c = 0; c < 3; ++c)
            ASSERT_EQ(base[3 * p + c], expected.baseColor[c]) << p;
        ASSERT_EQ(roughness[p], expected.roughness) << p;
        ASSERT_EQ(ao[p], expected.ambientOcclusion) << p;
    }
    if (pixels < 2)
        return;
    record[pixels - 1] = 3;
    try {
        lookUpMaterials(record.data(), draws, pixels, out);
        FAIL() << "a record past the draws was accepted";
    } catch (const InvalidState& e) {
        EXPECT_EQ(std::string(e.what()), "lookUpMaterials(): pixel " + std::to_string(pixels - 1) +
                                             " holds record 3, past the 2 draws");
    }
}

INSTANTIATE_TEST_SUITE_P(PixelCounts, DerivedImages, ::testing::Values(0, 1, 7, 8, 9, 16, 61 * 37, 1 << 16));

} // namespace
} // namespace sp::render

namespace sp::render {
namespace {

// Each computed point lies on its pixel's centre ray at the pixel's depth: the camera projects it back to
// that pixel's centre and depth; the background (depth 0) is 0.
TEST(PositionFromDepth, EachPointProjectsBackToItsPixelCentreAtItsDepth) {
    Camera camera;
    camera.params.width = 37; // odd sizes: the centre falls inside a pixel, not on its edge
    camera.params.height = 23;
    camera.params.hfovDeg = 70.0;
    camera.pose = Eigen::Translation3d(12.5, -40.25, 3.0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
    std::mt19937 random(11);
    std::uniform_real_distribution<float> metres(0.1f, 400.0f);
    const std::size_t pixels = 37 * 23;
    std::vector<float> depth(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        depth[p] = p % 5 == 0 ? 0.0f : metres(random);
    std::vector<float> position(3 * pixels, -1.0f);
    computePositionFromDepth(depth.data(), camera, position.data());
    for (int v = 0; v < 23; ++v)
        for (int u = 0; u < 37; ++u) {
            const std::size_t p = std::size_t(v) * 37 + std::size_t(u);
            const Eigen::Vector3d point(position[3 * p], position[3 * p + 1], position[3 * p + 2]);
            if (depth[p] == 0.0f) {
                EXPECT_EQ(point, Eigen::Vector3d::Zero()) << u << "," << v;
                continue;
            }
            // Rounded once to float32: within a few ulps of the point's coordinates, which reach 440 m.
            const Eigen::Vector3d back = camera.project(point);
            const double ulps = 4.0 * 440.0 * 6e-8;
            EXPECT_NEAR(back.z(), depth[p], ulps) << u << "," << v;
            EXPECT_NEAR(back.x(), u + 0.5, ulps * camera.focalLengthPixels() / depth[p]) << u << "," << v;
            EXPECT_NEAR(back.y(), v + 0.5, ulps * camera.focalLengthPixels() / depth[p]) << u << "," << v;
        }
}

} // namespace
} // namespace sp::render
