#include "core/imageio/image.h"

namespace sp::imageio {

std::size_t bytesPerChannel(PixelType type) {
    switch (type) {
    case PixelType::UInt8:
        return 1;
    case PixelType::Half:
        return 2;
    case PixelType::Float:
    case PixelType::UInt32:
        return 4;
    }
    return 0;
}

const char* toString(PixelType type) {
    switch (type) {
    case PixelType::UInt8:
        return "uint8";
    case PixelType::Half:
        return "float16";
    case PixelType::Float:
        return "float32";
    case PixelType::UInt32:
        return "uint32";
    }
    return "?";
}

} // namespace sp::imageio
