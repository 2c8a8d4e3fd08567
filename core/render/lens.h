#pragma once
// Lens models beyond the pinhole: a principal point off the image centre and Brown–Conrady distortion, in
// OpenCV's convention (so that K and the coefficients a camera reports are what cv2.undistort wants):
//
//   pixel (u right, v down, the centre of pixel [i, j] at u = j, v = i) = (fx x'' + cx, fy y'' + cy), where
//   (x, y) = (X/Z, Y/Z) in the OpenCV camera frame, r^2 = x^2 + y^2, and
//   x'' = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
//   y'' = y (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y
//
// The renderer rasterises pinhole images with the principal point at the centre; LensRemap turns such an
// image (rendered wide enough to hold every ray of the lens image) into the lens image, each lens pixel
// taking the rendered pixel its ray falls in. Nearest, not interpolated, so that every modality stays
// consistent: a pixel's id, depth, normal and colour all come from one surface point; the price is that a
// pixel shows its ray to within half a rendered pixel. Pure logic, no GL.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace sp::render {

struct LensModel {
    double fx = 1.0, fy = 1.0, cx = 0.0, cy = 0.0; // pixels
    double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;

    // No distortion (the principal point may still be anywhere).
    bool undistorted() const { return k1 == 0.0 && k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0; }
    // Normalised image coordinates (x, y) = (X/Z, Y/Z) to distorted ones.
    Eigen::Vector2d distortNormalized(const Eigen::Vector2d& undistorted) const;
    // d distorted / d undistorted at a point.
    Eigen::Matrix2d distortionJacobian(const Eigen::Vector2d& undistorted) const;
    // The undistorted point that distorts to `distorted` on the sheet of the model that holds the image
    // centre (where the lens maps one to one), to about 1e-13; none where the model folds over before
    // reaching it (strong barrel distortion far from the axis): no ray shows that point.
    std::optional<Eigen::Vector2d> undistortNormalizedIfAny(const Eigen::Vector2d& distorted) const;
    // Newton's method from `start`, staying on the sheet `start` is on (none when it leaves it or does not
    // converge).
    std::optional<Eigen::Vector2d> undistortFrom(const Eigen::Vector2d& distorted,
                                                 const Eigen::Vector2d& start) const;
    // The same, NaN where there is none.
    Eigen::Vector2d undistortNormalized(const Eigen::Vector2d& distorted) const;
    // The same in pixels: a pinhole pixel under (fx, fy, cx, cy) to the lens image's pixel, and back.
    Eigen::Vector2d distortPixel(const Eigen::Vector2d& pixel) const;
    Eigen::Vector2d undistortPixel(const Eigen::Vector2d& pixel) const;

    friend bool operator==(const LensModel&, const LensModel&) = default;
};

// Which rendered pixel each pixel of a lens image shows.
class LensRemap {
  public:
    // The largest pinhole render a lens image may need: a side, and its pixels over the image's.
    static constexpr int kMaxSourceSide = 16384;
    static constexpr int kMaxSourceToImage = 16;

    // The remap of a width x height lens image, for a pinhole render of focal length lens.fx (square pixels,
    // fx == fy), centred, just large enough to hold every lens pixel's ray. Pixels no ray shows (beyond
    // where the model folds over) stay empty. Throws sp::InvalidArgument, naming `context`, when the render
    // would exceed the limits above (rays too far from the axis).
    LensRemap(const LensModel& lens, int width, int height, const char* context);

    int width() const { return width_; }
    int height() const { return height_; }
    // The pinhole render it samples: its size and horizontal field of view.
    int sourceWidth() const { return sourceWidth_; }
    int sourceHeight() const { return sourceHeight_; }
    double sourceHfovDeg() const { return sourceHfovDeg_; }

    // Writes the lens image of `source` (sourceWidth x sourceHeight pixels of pixelBytes each, row 0 at the
    // top) into `target` (width x height pixels); pixels no ray shows are zero (the background of every
    // modality but colour).
    void apply(const std::byte* source, std::byte* target, std::size_t pixelBytes) const;

  private:
    int width_, height_, sourceWidth_ = 0, sourceHeight_ = 0;
    double sourceHfovDeg_ = 0.0;
    std::vector<std::int64_t> sourceIndex_; // per lens pixel, -1 for none
};

} // namespace sp::render
