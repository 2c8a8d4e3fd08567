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
// consistent: a pixel's id, depth, normal and colour all come from one surface point. Pure logic, no GL.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sp::render {

struct LensModel {
    double fx = 1.0, fy = 1.0, cx = 0.0, cy = 0.0; // pixels
    double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;

    // No distortion (the principal point may still be anywhere).
    bool undistorted() const { return k1 == 0.0 && k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0; }
    // Normalised image coordinates (x, y) = (X/Z, Y/Z) to distorted ones, and back (iteratively, as OpenCV's
    // undistortPoints; exact to about 1e-12 where the model is invertible).
    Eigen::Vector2d distortNormalized(const Eigen::Vector2d& undistorted) const;
    Eigen::Vector2d undistortNormalized(const Eigen::Vector2d& distorted) const;
    // The same in pixels: a pinhole pixel under (fx, fy, cx, cy) to the lens image's pixel, and back.
    Eigen::Vector2d distortPixel(const Eigen::Vector2d& pixel) const;
    Eigen::Vector2d undistortPixel(const Eigen::Vector2d& pixel) const;

    friend bool operator==(const LensModel&, const LensModel&) = default;
};

// Which rendered pixel each pixel of a lens image shows.
class LensRemap {
  public:
    // The remap of a width x height lens image, for a pinhole render of focal length lens.fx (square pixels,
    // fx == fy), centred, just large enough to hold every lens pixel's ray. Throws sp::InvalidArgument,
    // naming `context`, when that render would exceed maxSourcePixels (a distortion so strong that the
    // model folds over, or rays near 90 degrees).
    LensRemap(const LensModel& lens, int width, int height, const char* context,
              std::int64_t maxSourcePixels = std::int64_t(16384) * 16384);

    int width() const { return width_; }
    int height() const { return height_; }
    // The pinhole render it samples: its size and horizontal field of view.
    int sourceWidth() const { return sourceWidth_; }
    int sourceHeight() const { return sourceHeight_; }
    double sourceHfovDeg() const { return sourceHfovDeg_; }

    // Writes the lens image of `source` (sourceWidth x sourceHeight pixels of pixelBytes each, row 0 at the
    // top) into `target` (width x height pixels); pixels whose ray misses the render (none, by
    // construction) are zero.
    void apply(const std::byte* source, std::byte* target, std::size_t pixelBytes) const;

  private:
    int width_, height_, sourceWidth_ = 0, sourceHeight_ = 0;
    double sourceHfovDeg_ = 0.0;
    std::vector<std::int64_t> sourceIndex_; // per lens pixel, -1 for none
};

} // namespace sp::render
