#include "core/render/lens.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/base/error.h"

namespace sp::render {

Eigen::Vector2d LensModel::distortNormalized(const Eigen::Vector2d& undistorted) const {
    const double x = undistorted.x(), y = undistorted.y();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
            y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Matrix2d LensModel::distortionJacobian(const Eigen::Vector2d& undistorted) const {
    const double x = undistorted.x(), y = undistorted.y();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double slope = k1 + r2 * (2.0 * k2 + 3.0 * k3 * r2); // d radial / d r^2
    const double cross = 2.0 * x * y * slope + 2.0 * p1 * x + 2.0 * p2 * y;
    Eigen::Matrix2d jacobian;
    jacobian << radial + 2.0 * x * x * slope + 2.0 * p1 * y + 6.0 * p2 * x, cross, cross,
        radial + 2.0 * y * y * slope + 6.0 * p1 * y + 2.0 * p2 * x;
    return jacobian;
}

std::optional<Eigen::Vector2d> LensModel::undistortFrom(const Eigen::Vector2d& distorted,
                                                        const Eigen::Vector2d& start) const {
    // Newton's method on distort(p) = distorted. A step where the Jacobian's determinant is not positive
    // has left the sheet of the model that holds the image centre (the model folds over there).
    Eigen::Vector2d point = start;
    for (int i = 0; i < 50; ++i) {
        const Eigen::Matrix2d jacobian = distortionJacobian(point);
        if (!(jacobian.determinant() > 1e-12))
            return std::nullopt;
        const Eigen::Vector2d error = distortNormalized(point) - distorted;
        if (error.squaredNorm() < 1e-26)
            return point;
        point -= jacobian.inverse() * error;
        if (!point.allFinite())
            return std::nullopt;
    }
    return std::nullopt;
}

std::optional<Eigen::Vector2d> LensModel::undistortNormalizedIfAny(const Eigen::Vector2d& distorted) const {
    // Followed from the centre out (distorted * t, t = 1/8 ... 1), each step starting from the last one's
    // solution, so that it stays on the sheet that holds the image centre.
    constexpr int kSteps = 8;
    std::optional<Eigen::Vector2d> point = Eigen::Vector2d::Zero();
    for (int step = 1; step <= kSteps && point; ++step)
        point = undistortFrom(distorted * (double(step) / kSteps), *point);
    return point;
}

Eigen::Vector2d LensModel::undistortNormalized(const Eigen::Vector2d& distorted) const {
    return undistortNormalizedIfAny(distorted).value_or(
        Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
}

Eigen::Vector2d LensModel::distortPixel(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector2d d = distortNormalized({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
    return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector2d LensModel::undistortPixel(const Eigen::Vector2d& pixel) const {
    const Eigen::Vector2d u = undistortNormalized({(pixel.x() - cx) / fx, (pixel.y() - cy) / fy});
    return {fx * u.x() + cx, fy * u.y() + cy};
}

LensRemap::LensRemap(const LensModel& lens, int width, int height, const char* context)
    : width_(width), height_(height) {
    SP_CHECK(lens.fx > 0.0 && lens.fx == lens.fy, InvalidArgument, context,
             ": lens images need square pixels (fx == fy > 0), got fx ", lens.fx, ", fy ", lens.fy);
    // Every lens pixel's ray, as undistorted normalised coordinates (none where the model folds over:
    // those pixels stay empty, as cv2.remap leaves them); the render must hold them all.
    std::vector<std::optional<Eigen::Vector2d>> rays(std::size_t(width) * std::size_t(height));
    double reachX = 0.0, reachY = 0.0;
    for (int v = 0; v < height; ++v)
        for (int u = 0; u < width; ++u) {
            auto& ray = rays[std::size_t(v) * std::size_t(width) + std::size_t(u)];
            const Eigen::Vector2d distorted{(u - lens.cx) / lens.fx, (v - lens.cy) / lens.fy};
            // The neighbour's ray is a start a step or two from this one, on the same sheet; from the
            // centre out when there is none.
            if (u > 0 && rays[std::size_t(v) * std::size_t(width) + std::size_t(u) - 1])
                ray = lens.undistortFrom(distorted,
                                         *rays[std::size_t(v) * std::size_t(width) + std::size_t(u) - 1]);
            if (!ray)
                ray = lens.undistortNormalizedIfAny(distorted);
            if (ray) {
                reachX = std::max(reachX, std::abs(ray->x()));
                reachY = std::max(reachY, std::abs(ray->y()));
            }
        }
    // The render keeps the lens's focal length (the same pixel density at the centre), centred, with a
    // pixel of margin around the farthest ray, and the image's parity, so that a principal point offset by
    // whole pixels maps pixel centres onto pixel centres.
    const double focal = lens.fx;
    const auto side = [](double reach, int image) {
        int size = 2 * int(std::min(std::ceil(reach + 1.5), 1e6));
        return size + ((size - image) % 2 != 0 ? 1 : 0);
    };
    const int sourceWidth = side(reachX * focal, width), sourceHeight = side(reachY * focal, height);
    // A render far larger than the image means rays near 90 degrees: a lens (or an offset) the pinhole
    // render cannot serve.
    SP_CHECK(sourceWidth <= kMaxSourceSide && sourceHeight <= kMaxSourceSide &&
                 double(sourceWidth) * sourceHeight <= kMaxSourceToImage * double(width) * height,
             InvalidArgument, context, ": the lens (distortion and principal point) needs a ", sourceWidth,
             "x", sourceHeight, " pinhole render to cover its ", width, "x", height, " image (at most ",
             kMaxSourceSide, " a side and ", kMaxSourceToImage,
             " times the image's pixels); its rays reach too far from the axis");
    sourceWidth_ = sourceWidth;
    sourceHeight_ = sourceHeight;
    sourceHfovDeg_ = 2.0 * std::atan(0.5 * sourceWidth_ / focal) * 180.0 / M_PI;
    const double sourceCx = 0.5 * (sourceWidth_ - 1), sourceCy = 0.5 * (sourceHeight_ - 1);
    sourceIndex_.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!rays[i]) {
            sourceIndex_[i] = -1;
            continue;
        }
        const long column = std::lround(focal * rays[i]->x() + sourceCx);
        const long row = std::lround(focal * rays[i]->y() + sourceCy);
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
