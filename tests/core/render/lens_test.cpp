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

TEST(Lens, AFoldingLensIsRefusedNamingTheCaller) {
    LensModel model = lens(-0.9, 0.0, 0.0, 0.0, 0.0);
    model.fx = model.fy = 20.0; // a very wide view: the model folds over inside the image
    try {
        LensRemap remap(model, 167, 116, "UCameraSensorComponent 'Cam'");
        FAIL() << "a folding lens was accepted";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("UCameraSensorComponent 'Cam': the lens"), std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace sp::render
