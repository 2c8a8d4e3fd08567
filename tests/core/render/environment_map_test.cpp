// The environment map against closed forms: its coordinates, a uniform map's terms (a white Lambertian
// surface reflects the map's radiance: the furnace), the hemisphere sky whose irradiance is exactly
// linear in the normal, the turn about the up axis, the content hash, and importance sampling that integrates
// the map.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include "core/base/error.h"
#include "core/render/environment_map.h"

namespace sp::render {
namespace {

constexpr float kPi = 3.14159265358979f;

RadianceImage filled(int width, int height, const std::function<Eigen::Vector3f(const Eigen::Vector3f&)>& f) {
    RadianceImage image{width, height, {}};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            image.texels.push_back(f(
                EnvironmentMap::fromUv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height))));
    return image;
}

TEST(EnvironmentMapTest, CoordinatesPutTheZenithOnTopAndPlusXInTheMiddle) {
    EXPECT_NEAR(EnvironmentMap::toUv(Eigen::Vector3f::UnitX()).x(), 0.5f, 1e-6f);
    EXPECT_NEAR(EnvironmentMap::toUv(Eigen::Vector3f::UnitY()).x(), 0.25f, 1e-6f); // left of the centre
    EXPECT_NEAR(EnvironmentMap::toUv(Eigen::Vector3f::UnitZ()).y(), 0.0f, 1e-6f);
    EXPECT_NEAR(EnvironmentMap::toUv(-Eigen::Vector3f::UnitZ()).y(), 1.0f, 1e-6f);
    for (const Eigen::Vector3f& d :
         {Eigen::Vector3f(0.3f, -0.5f, 0.2f), Eigen::Vector3f(-0.7f, 0.1f, -0.6f)}) {
        const Eigen::Vector2f uv = EnvironmentMap::toUv(d.normalized());
        EXPECT_TRUE(EnvironmentMap::fromUv(uv.x(), uv.y()).isApprox(d.normalized(), 1e-5f));
    }
}

TEST(EnvironmentMapTest, AUniformMapGivesItsRadianceToEveryTerm) {
    const Eigen::Vector3f sky(0.5f, 1.0f, 2.0f);
    const EnvironmentMap map(filled(64, 32, [&](const Eigen::Vector3f&) -> Eigen::Vector3f { return sky; }),
                             0.0f, "test");
    EXPECT_TRUE(map.average().isApprox(sky, 1e-4f));
    for (const Eigen::Vector3f& n : {Eigen::Vector3f::UnitZ().eval(), Eigen::Vector3f(0.6f, -0.8f, 0.0f),
                                     Eigen::Vector3f(0.0f, 0.6f, -0.8f)}) {
        EXPECT_TRUE(map.radiance(n).isApprox(sky, 1e-5f));
        // A white Lambertian surface reflects the sky's radiance, whatever its orientation.
        EXPECT_TRUE(map.diffuse(n).isApprox(sky, 2e-3f)) << map.diffuse(n).transpose();
    }
    ASSERT_EQ(map.specularLevels().size(), std::size_t(EnvironmentMap::kSpecularLevels));
    for (const RadianceImage& level : map.specularLevels())
        for (const Eigen::Vector3f& texel : level.texels)
            ASSERT_TRUE(texel.isApprox(sky, 1e-4f));
    // Uniform luminance: every direction is about as likely.
    Eigen::Vector3f d;
    EXPECT_NEAR(map.sample(0.3f, 0.7f, d), 1.0f / (4.0f * kPi), 0.01f / (4.0f * kPi));
}

TEST(EnvironmentMapTest, AHemisphereSkyLightsANormalByHalfOfOnePlusItsUpComponent) {
    // Radiance 1 above the horizon, 0 below: the irradiance at normal n is pi (1 + n.z) / 2, which the
    // first two spherical-harmonic bands hold exactly.
    const EnvironmentMap map(filled(512, 256,
                                    [](const Eigen::Vector3f& d) -> Eigen::Vector3f {
                                        return Eigen::Vector3f::Constant(d.z() > 0 ? 1.f : 0.f);
                                    }),
                             0.0f, "test");
    for (float z : {1.0f, 0.5f, 0.0f, -0.5f, -1.0f}) {
        const Eigen::Vector3f n(std::sqrt(1.0f - z * z), 0.0f, z);
        EXPECT_NEAR(map.diffuse(n).x(), 0.5f * (1.0f + z), 0.02f) << z;
    }
    // The prefiltered chain: a mirror sees the sky or the ground; the roughest level blurs the horizon.
    const RadianceImage& mirror = map.specularLevels().front();
    EXPECT_NEAR(mirror.at(0, 10).x(), 1.0f, 1e-4f);
    EXPECT_NEAR(mirror.at(0, mirror.height - 10).x(), 0.0f, 1e-4f);
    const RadianceImage& rough = map.specularLevels().back();
    const float up = rough.at(0, 0).x(), horizon = rough.at(0, rough.height / 2).x();
    EXPECT_GT(up, horizon);
    EXPECT_GT(horizon, 0.2f);
    EXPECT_LT(horizon, 0.8f);
}

TEST(EnvironmentMapTest, SourceAngleTurnsThePanoramaToTheLeft) {
    // A bright patch straight ahead (+X), turned by 90 degrees, is seen on the left (+Y).
    auto patch = [](const Eigen::Vector3f& d) -> Eigen::Vector3f {
        return Eigen::Vector3f::Constant(d.dot(Eigen::Vector3f::UnitX()) > 0.95f ? 10.0f : 0.1f);
    };
    const EnvironmentMap turned(filled(256, 128, patch), 90.0f, "test");
    EXPECT_NEAR(turned.radiance(Eigen::Vector3f::UnitY()).x(), 10.0f, 0.01f);
    EXPECT_NEAR(turned.radiance(Eigen::Vector3f::UnitX()).x(), 0.1f, 0.01f);
}

TEST(EnvironmentMapTest, MapsMadeAlikeHashAlikeAndAnyChangeShows) {
    // What the path tracer seeds its samples with: the radiance, not which object holds it.
    auto sky = [](const Eigen::Vector3f& d) -> Eigen::Vector3f {
        return Eigen::Vector3f(0.2f, 0.3f, 0.5f) * (1.5f + d.z() + 0.5f * d.x());
    };
    const EnvironmentMap a(filled(64, 32, sky), 0.0f, "test"), b(filled(64, 32, sky), 0.0f, "test");
    EXPECT_NE(a.uid(), b.uid());
    EXPECT_EQ(a.contentHash(), b.contentHash());
    RadianceImage brighter = filled(64, 32, sky);
    brighter.texels[100].x() += 1e-3f;
    EXPECT_NE(EnvironmentMap(std::move(brighter), 0.0f, "test").contentHash(), a.contentHash());
    EXPECT_NE(EnvironmentMap(filled(64, 32, sky), 45.0f, "test").contentHash(), a.contentHash());
}

TEST(EnvironmentMapTest, ImportanceSamplingIntegratesTheMap) {
    // A dim sky with a small sun: sampling by luminance finds the sun, and the estimate of the integral of
    // the radiance over the sphere (radiance / pdf) is right with few samples.
    const Eigen::Vector3f toSun = Eigen::Vector3f(0.3f, 0.2f, 0.9f).normalized();
    const EnvironmentMap map(filled(512, 256,
                                    [&](const Eigen::Vector3f& d) -> Eigen::Vector3f {
                                        return Eigen::Vector3f::Constant(d.dot(toSun) > 0.998f ? 5000.0f
                                                                                               : 0.2f);
                                    }),
                             0.0f, "test");
    const double exact = 4.0 * kPi * map.average().x();
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    double sum = 0.0;
    constexpr int kSamples = 4096;
    for (int i = 0; i < kSamples; ++i) {
        Eigen::Vector3f d;
        const float pdf = map.sample(uniform(random), uniform(random), d);
        ASSERT_GT(pdf, 0.0f);
        EXPECT_NEAR(map.pdf(d), pdf, 1e-3f * pdf);
        sum += map.radiance(d).x() / pdf;
    }
    EXPECT_NEAR(sum / kSamples / exact, 1.0, 0.05);
}

TEST(EnvironmentMapTest, ReadsRadianceHdrFiles) {
    // A flat (not run-length encoded) RGBE file, 8 x 4: radiance 1 (mantissa 128, exponent 129) on the top
    // row, 0.5 (exponent 128) below it, a colour (0.5, 1, 255 / 128) on the third row, 0 on the last.
    const std::string path = testing::TempDir() + "spear_environment_map_test.hdr";
    std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n";
    const unsigned char rows[4][4] = {
        {128, 128, 128, 129}, {128, 128, 128, 128}, {64, 128, 255, 129}, {0, 0, 0, 0}};
    for (const auto& rgbe : rows)
        for (int x = 0; x < 8; ++x)
            bytes.append(reinterpret_cast<const char*>(rgbe), 4);
    std::ofstream(path, std::ios::binary) << bytes;
    const RadianceImage image = readRadianceHdr(path, "Loader");
    ASSERT_EQ(image.width, 8);
    ASSERT_EQ(image.height, 4);
    EXPECT_TRUE(image.at(3, 0).isApprox(Eigen::Vector3f::Ones(), 1e-6f));
    EXPECT_TRUE(image.at(5, 1).isApprox(Eigen::Vector3f::Constant(0.5f), 1e-6f));
    EXPECT_TRUE(image.at(0, 2).isApprox(Eigen::Vector3f(0.5f, 1.0f, 255.0f / 128.0f), 1e-6f));
    EXPECT_EQ(image.at(7, 3), Eigen::Vector3f::Zero());
    EXPECT_THROW(readRadianceHdr(testing::TempDir() + "no_such_file.hdr", "Loader"), NotFound);
    std::ofstream(path, std::ios::binary) << "not an image";
    try {
        readRadianceHdr(path, "Loader");
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_EQ(std::string(e.what()), "Loader: '" + path + "' is not a Radiance HDR (.hdr) file");
    }
}

TEST(EnvironmentMapTest, RefusesWhatIsNotAnEquirectangularRadianceMap) {
    try {
        EnvironmentMap(RadianceImage{30, 20, std::vector<Eigen::Vector3f>(600, Eigen::Vector3f::Ones())},
                       0.0f, "Loader");
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(),
                     "Loader: an environment map must be equirectangular (width = 2 x height), 8 x 4 to "
                     "16384 x 8192 texels, got 30 x 20");
    }
    RadianceImage negative{8, 4, std::vector<Eigen::Vector3f>(32, Eigen::Vector3f::Ones())};
    negative.texels[5] = Eigen::Vector3f(1.0f, -1.0f, 0.0f);
    EXPECT_THROW(EnvironmentMap(negative, 0.0f, "Loader"), InvalidArgument);
}

} // namespace
} // namespace sp::render
