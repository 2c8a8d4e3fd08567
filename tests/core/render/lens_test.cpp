// The lens model against OpenCV's equations, its inverse, and the remap that turns a centred pinhole render
// into a distorted, off-centre image.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/error.h"
#include "core/render/lens.h"

namespace sp::render {
namespace {

LensModel lens(double k1, double k2, double k3, double p1, double p2) {
    LensModel model;
    model.fx = model.fy = 100.0;
    model.cx = 83.0;
    model.cy = 57.5;
    model.k1 = k1;
    model.k2 = k2;
    model.k3 = k3;
    model.p1 = p1;
    model.p2 = p2;
    return model;
}

TEST(Lens, DistortsAsOpenCvsEquations) {
    const LensModel model = lens(-0.2, 0.05, 0.01, 0.003, -0.002);
    const double x = 0.3, y = -0.4, r2 = x * x + y * y;
    const double radial = 1 - 0.2 * r2 + 0.05 * r2 * r2 + 0.01 * r2 * r2 * r2;
    const Eigen::Vector2d d = model.distortNormalized({x, y});
    EXPECT_NEAR(d.x(), x * radial + 2 * 0.003 * x * y - 0.002 * (r2 + 2 * x * x), 1e-15);
    EXPECT_NEAR(d.y(), y * radial + 0.003 * (r2 + 2 * y * y) + 2 * -0.002 * x * y, 1e-15);
    const Eigen::Vector2d pixel = model.distortPixel({100.0 * x + 83.0, 100.0 * y + 57.5});
    EXPECT_NEAR(pixel.x(), 100.0 * d.x() + 83.0, 1e-12);
    EXPECT_NEAR(pixel.y(), 100.0 * d.y() + 57.5, 1e-12);
}

TEST(Lens, UndistortingInvertsDistortingOverTheImage) {
    for (const LensModel& model : {lens(-0.25, 0.06, 0.0, 0.004, -0.003), lens(0.15, -0.02, 0.003, 0.0, 0.0),
                                   lens(0.0, 0.0, 0.0, 0.01, 0.01)})
        for (double u = 0.0; u <= 166.0; u += 16.6)
            for (double v = 0.0; v <= 115.0; v += 11.5) {
                const Eigen::Vector2d distorted{u, v};
                const Eigen::Vector2d back = model.distortPixel(model.undistortPixel(distorted));
                EXPECT_NEAR(back.x(), u, 1e-9) << "k1 " << model.k1 << " at " << u << ", " << v;
                EXPECT_NEAR(back.y(), v, 1e-9) << "k1 " << model.k1 << " at " << u << ", " << v;
            }
}

TEST(Lens, RemapTakesEachPixelFromTheRenderedPixelItsRayFallsIn) {
    const LensModel model = lens(-0.2, 0.04, 0.0, 0.002, 0.001);
    const LensRemap remap(model, 167, 116, "test");
    // Barrel distortion: the render reaches further than the image; it keeps the focal length.
    EXPECT_GT(remap.sourceWidth(), 167);
    EXPECT_NEAR(0.5 * remap.sourceWidth() / std::tan(0.5 * remap.sourceHfovDeg() * M_PI / 180.0), 100.0,
                1e-9);
    // A render whose every pixel holds its own index shows, at each lens pixel, the rendered pixel that
    // contains the lens pixel's undistorted ray.
    std::vector<std::uint32_t> source(std::size_t(remap.sourceWidth()) * std::size_t(remap.sourceHeight()));
    for (std::size_t i = 0; i < source.size(); ++i)
        source[i] = std::uint32_t(i);
    std::vector<std::uint32_t> image(167 * 116);
    remap.apply(reinterpret_cast<const std::byte*>(source.data()), reinterpret_cast<std::byte*>(image.data()),
                sizeof(std::uint32_t));
    for (int v = 0; v < 116; v += 5)
        for (int u = 0; u < 167; u += 5) {
            const Eigen::Vector2d ray = model.undistortNormalized({(u - 83.0) / 100.0, (v - 57.5) / 100.0});
            const double su = 100.0 * ray.x() + 0.5 * (remap.sourceWidth() - 1);
            const double sv = 100.0 * ray.y() + 0.5 * (remap.sourceHeight() - 1);
            const std::uint32_t index = image[std::size_t(v) * 167 + std::size_t(u)];
            EXPECT_LE(std::abs(double(index % std::uint32_t(remap.sourceWidth())) - su), 0.5)
                << u << ", " << v;
            EXPECT_LE(std::abs(double(index / std::uint32_t(remap.sourceWidth())) - sv), 0.5)
                << u << ", " << v;
        }
}

// Checks, on a grid of lens pixels, that each valid one shows the rendered pixel holding its ray, and counts
// the pixels that show none.
int checkRemap(const LensModel& model, int width, int height) {
    const LensRemap remap(model, width, height, "test");
    std::vector<std::uint32_t> source(std::size_t(remap.sourceWidth()) * std::size_t(remap.sourceHeight()));
    for (std::size_t i = 0; i < source.size(); ++i)
        source[i] = std::uint32_t(i) + 1; // 0 is "no ray"
    std::vector<std::uint32_t> image(std::size_t(width) * std::size_t(height));
    remap.apply(reinterpret_cast<const std::byte*>(source.data()), reinterpret_cast<std::byte*>(image.data()),
                sizeof(std::uint32_t));
    int empty = 0;
    for (int v = 0; v < height; ++v)
        for (int u = 0; u < width; ++u) {
            const std::uint32_t shown = image[std::size_t(v) * std::size_t(width) + std::size_t(u)];
            const auto ray =
                model.undistortNormalizedIfAny({(u - model.cx) / model.fx, (v - model.cy) / model.fy});
            EXPECT_EQ(shown == 0, !ray.has_value()) << u << ", " << v;
            if (!ray) {
                ++empty;
                continue;
            }
            EXPECT_TRUE(model.distortNormalized(*ray).isApprox(
                Eigen::Vector2d((u - model.cx) / model.fx, (v - model.cy) / model.fy), 1e-9));
            const double su = model.fx * ray->x() + 0.5 * (remap.sourceWidth() - 1);
            const double sv = model.fx * ray->y() + 0.5 * (remap.sourceHeight() - 1);
            const std::uint32_t index = shown - 1;
            EXPECT_LE(std::abs(double(index % std::uint32_t(remap.sourceWidth())) - su), 0.5)
                << u << ", " << v;
            EXPECT_LE(std::abs(double(index / std::uint32_t(remap.sourceWidth())) - sv), 0.5)
                << u << ", " << v;
        }
    return empty;
}

TEST(Lens, AMildBarrelPastItsFoldLeavesTheCornersEmptyAndTheRenderSmall) {
    // 90 degrees, K1 = -0.1: the model folds at r = 1.83 before the corners' 1.25 distorted radius is reached
    // (its largest distorted radius is 1.22), so the corners show no ray.
    LensModel model = lens(-0.1, 0.0, 0.0, 0.0, 0.0);
    model.fx = model.fy = 320.0;
    model.cx = 319.5;
    model.cy = 239.5;
    const LensRemap remap(model, 640, 480, "test");
    EXPECT_LE(remap.sourceWidth(), 2 * 640);
    EXPECT_LE(remap.sourceHeight(), 2 * 480);
    const int empty = checkRemap(model, 640, 480);
    EXPECT_GT(empty, 0);
    EXPECT_LT(empty, 640 * 480 / 50);
}

TEST(Lens, AStrongPincushionIsInvertedEverywhere) {
    // 120 degrees, K1 = 1: k1 r^2 reaches 4 at the corners, where a fixed-point inverse diverges.
    LensModel model = lens(1.0, 0.0, 0.0, 0.0, 0.0);
    model.fx = model.fy = 320.0 / std::tan(M_PI / 3.0);
    model.cx = 319.5;
    model.cy = 239.5;
    EXPECT_EQ(checkRemap(model, 640, 480), 0);
}

TEST(Lens, AWholePixelOffsetMapsPixelCentresExactly) {
    LensModel model = lens(0.0, 0.0, 0.0, 0.0, 0.0);
    model.cx = 0.5 * (31 - 1) + 4.0;
    model.cy = 0.5 * (20 - 1) - 3.0;
    const LensRemap remap(model, 31, 20, "test");
    EXPECT_EQ((remap.sourceWidth() - 31) % 2, 0);
    EXPECT_EQ((remap.sourceHeight() - 20) % 2, 0);
    for (int v = 0; v < 20; ++v)
        for (int u = 0; u < 31; ++u) {
            const double su = u - model.cx + 0.5 * (remap.sourceWidth() - 1);
            const double sv = v - model.cy + 0.5 * (remap.sourceHeight() - 1);
            EXPECT_EQ(su, std::round(su));
            EXPECT_EQ(sv, std::round(sv));
        }
    EXPECT_EQ(checkRemap(model, 31, 20), 0);
}

TEST(Lens, ARenderTooLargeIsRefusedNamingTheCaller) {
    LensModel model = lens(0.0, 0.0, 0.0, 0.0, 0.0);
    model.cx = 20000.0; // the image far off the axis: rays near 90 degrees
    try {
        LensRemap remap(model, 167, 116, "UCameraSensorComponent 'Cam'");
        FAIL() << "a render of " << remap.sourceWidth() << "x" << remap.sourceHeight() << " was accepted";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("UCameraSensorComponent 'Cam': the lens"), std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace sp::render
