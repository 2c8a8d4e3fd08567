#include "core/render/lens.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/base/error.h"

namespace sp::render {

Eigen::Vector2d LensModel::distortNormalized(const Eigen::Vector2d& undistorted) const {
    const double x = undistorted.x(), y = undistorted.y();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
            y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d LensModel::undistortNormalized(const Eigen::Vector2d& distorted) const {
    // Fixed-point iteration x = (x_d - tangential(x)) / radial(x), as OpenCV's undistortPoints, run until
    // it stops moving.
    Eigen::Vector2d point = distorted;
    for (int i = 0; i < 100; ++i) {
        const double x = point.x(), y = point.y();
        const double r2 = x * x + y * y;
        const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
        const Eigen::Vector2d next{(distorted.x() - 2.0 * p1 * x * y - p2 * (r2 + 2.0 * x * x)) / radial,
                                   (distorted.y() - p1 * (r2 + 2.0 * y * y) - 2.0 * p2 * x * y) / radial};
        const bool settled = (next - point).squaredNorm() < 1e-28;
        point = next;
        if (settled)
            break;
    }
    return point;
}

Eigen::Vector2d LensModel::distortPixel(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector2d d = distortNormalized({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
    return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector2d LensModel::undistortPixel(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector2d u = undistortNormalized({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
    return {fx * u.x() + cx, fy * u.y() + cy};
}

LensRemap::LensRemap(const LensModel& lens, int width, int height, const char* context,
                     std::int64_t maxSourcePixels)
    : width_(width), height_(height) {
    SP_CHECK(lens.fx > 0.0 && lens.fx == lens.fy, InvalidArgument, context,
             ": lens images need square pixels (fx == fy > 0), got fx ", lens.fx, ", fy ", lens.fy);
    // Every lens pixel's ray, as undistorted normalised coordinates; the render must hold them all.
    std::vector<Eigen::Vector2d> rays(std::size_t(width) * std::size_t(height));
    double reachX = 0.0, reachY = 0.0;
    bool finite = true;
    for (int v = 0; v < height; ++v)
        for (int u = 0; u < width; ++u) {
            const Eigen::Vector2d ray =
                lens.undistortNormalized({(u - lens.cx) / lens.fx, (v - lens.cy) / lens.fy});
            finite = finite && std::isfinite(ray.x()) && std::isfinite(ray.y());
            reachX = std::max(reachX, std::abs(ray.x()));
            reachY = std::max(reachY, std::abs(ray.y()));
            rays[std::size_t(v) * std::size_t(width) + std::size_t(u)] = ray;
        }
    // The render keeps the lens's focal length (the same pixel density at the centre), centred, with a
    // pixel of margin around the farthest ray.
    const double focal = lens.fx;
    const double halfWidth = reachX * focal + 1.5, halfHeight = reachY * focal + 1.5;
    SP_CHECK(finite && 2.0 * halfWidth * 2.0 * halfHeight <= double(maxSourcePixels), InvalidArgument,
             context, ": the lens (distortion and principal point) needs a render of ",
             finite ? std::to_string(std::int64_t(2.0 * halfWidth)) + "x" +
                          std::to_string(std::int64_t(2.0 * halfHeight))
                    : std::string("unbounded size"),
             " pixels to cover its ", width, "x", height,
             " image; the distortion is too strong for the model to be inverted there");
    sourceWidth_ = 2 * int(std::ceil(halfWidth));
    sourceHeight_ = 2 * int(std::ceil(halfHeight));
    sourceHfovDeg_ = 2.0 * std::atan(0.5 * sourceWidth_ / focal) * 180.0 / M_PI;
    const double sourceCx = 0.5 * (sourceWidth_ - 1), sourceCy = 0.5 * (sourceHeight_ - 1);
    sourceIndex_.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const long column = std::lround(focal * rays[i].x() + sourceCx);
        const long row = std::lround(focal * rays[i].y() + sourceCy);
        sourceIndex_[i] = column >= 0 && column < sourceWidth_ && row >= 0 && row < sourceHeight_
                              ? std::int64_t(row) * sourceWidth_ + column
                              : -1;
    }
}

void LensRemap::apply(const std::byte* source, std::byte* target, std::size_t pixelBytes) const {
    for (std::size_t i = 0; i < sourceIndex_.size(); ++i) {
        std::byte* out = target + i * pixelBytes;
        if (sourceIndex_[i] < 0)
            std::memset(out, 0, pixelBytes);
        else
            std::memcpy(out, source + std::size_t(sourceIndex_[i]) * pixelBytes, pixelBytes);
    }
}

} // namespace sp::render
