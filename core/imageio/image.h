#pragma once
// Images as the engine writes them to disk: interleaved channels of one pixel type, row 0 at the top, the
// layout read_pixels() hands to numpy ((H, W) or (H, W, C)).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sp::imageio {

enum class PixelType { UInt8, Half, Float, UInt32 };

std::size_t bytesPerChannel(PixelType type);
const char* toString(PixelType type);

// Borrowed pixels (width * height * channels values of `type`).
struct ImageView {
    int width = 0;
    int height = 0;
    int channels = 0;
    PixelType type = PixelType::UInt8;
    const void* data = nullptr;

    std::size_t byteSize() const {
        return std::size_t(width) * std::size_t(height) * std::size_t(channels) * bytesPerChannel(type);
    }
};

// Owned pixels, with the names their file gave the channels.
struct Image {
    int width = 0;
    int height = 0;
    PixelType type = PixelType::UInt8;
    std::vector<std::string> channelNames;
    std::vector<std::byte> pixels; // interleaved in channelNames order

    ImageView view() const { return {width, height, int(channelNames.size()), type, pixels.data()}; }
};

} // namespace sp::imageio
