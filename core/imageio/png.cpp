#include "core/imageio/png.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include "core/base/error.h"
#include "core/base/regular_file.h"

namespace sp::imageio {

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
    writeRegularFile(path, encodePng(image, function), function, "PNG file");
}

} // namespace sp::imageio
