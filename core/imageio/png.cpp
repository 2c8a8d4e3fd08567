#include "core/imageio/png.h"

#include <zlib.h>

#include <cstdlib>

namespace {

// stb_image_write's own deflate is slow (75 ms for a 1280x720 frame); zlib at level 1 with every row
// filtered by "Up" takes 16 ms for files 6 % larger, which is the better trade for a render queue
// writing thousands of frames (measured in BENCHMARKS.md, "Render queue").
unsigned char* zlibCompress(unsigned char* data, int length, int* outLength, int /*quality*/) {
    uLongf size = compressBound(uLong(length));
    auto* out = static_cast<unsigned char*>(std::malloc(size));
    if (out == nullptr || compress2(out, &size, data, uLong(length), 1) != Z_OK) {
        std::free(out);
        return nullptr; // stb reports the failure
    }
    *outLength = int(size);
    return out;
}

} // namespace

#define STBIW_ZLIB_COMPRESS zlibCompress
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include "core/base/error.h"
#include "core/base/regular_file.h"

namespace sp::imageio {
namespace {

// "Up" for every row (see zlibCompress); set once, before any writer thread can read stb's global.
const bool kUpFilter = (stbi_write_force_png_filter = 2, true);

} // namespace

std::string encodePng(const ImageView& image, std::string_view function) {
    SP_CHECK(image.type == PixelType::UInt8, InvalidArgument, function, ": PNG holds 8-bit images, not ",
             toString(image.type));
    SP_CHECK(image.channels >= 1 && image.channels <= 4, InvalidArgument, function,
             ": PNG holds 1 to 4 channels, not ", image.channels);
    SP_CHECK(image.width > 0 && image.height > 0, InvalidArgument, function, ": empty image (", image.width,
             "x", image.height, ")");
    std::string file;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
    };
    const int ok = stbi_write_png_to_func(append, &file, image.width, image.height, image.channels,
                                          image.data, image.width * image.channels);
    SP_CHECK(ok != 0, InvalidArgument, function, ": cannot encode a ", image.width, "x", image.height,
             " PNG");
    return file;
}

void writePng(const std::string& path, const ImageView& image, std::string_view function) {
    writeRegularFile(path, encodePng(image, std::string(function) + ": '" + path + "'"), function,
                     "PNG file");
}

} // namespace sp::imageio
