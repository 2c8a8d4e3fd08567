#pragma once
// PNG files of 8-bit images (1 to 4 channels: grey, grey+alpha, RGB, RGBA), through stb_image_write.

#include <string>
#include <string_view>

#include "core/imageio/image.h"

namespace sp::imageio {

// The PNG file of `image` (UInt8); throws sp::InvalidArgument, naming `function`, for any other image.
std::string encodePng(const ImageView& image, std::string_view function);

// Writes `image` to `path` whole (a reader never sees half a file; see sp::writeRegularFile).
void writePng(const std::string& path, const ImageView& image, std::string_view function);

} // namespace sp::imageio
