#pragma once
// OpenEXR files (through Debian's libopenexr): half, float and uint32 images, lossless (ZIP). Channels
// are named as image viewers expect: one channel "Y", two "Y", "A", three "R", "G", "B", four "R", "G",
// "B", "A".

#include <string>
#include <string_view>

#include "core/imageio/image.h"

namespace sp::imageio {

// The EXR file of `image` (Half, Float or UInt32); throws sp::InvalidArgument, naming `function`, for an
// 8-bit image (PNG holds those) or an empty one.
std::string encodeExr(const ImageView& image, std::string_view function);

// Writes `image` to `path` whole (a reader never sees half a file; see sp::writeRegularFile).
void writeExr(const std::string& path, const ImageView& image, std::string_view function);

// Reads the EXR file at `path`: its channels in R, G, B, A order when it has only those, else in the
// file's (alphabetical) order ("Y" before "A"), all of one pixel type, 1 to 4 channels, at most 16384 pixels
// a side. Throws sp::NotFound when there is no such file and sp::InvalidArgument when it is not an EXR file,
// mixes pixel types or exceeds those bounds.
Image readExr(const std::string& path, std::string_view function);

} // namespace sp::imageio
