#include "core/render/image_buffer.h"

#include <cmath>
#include <cstring>

#include "core/base/error.h"

namespace sp::render {

float ImageBuffer::at(int x, int y, int c) const {
    SP_CHECK(x >= 0 && x < width && y >= 0 && y < height && c >= 0 && c < channels(), InvalidArgument,
             "ImageBuffer::at(): (", x, ", ", y, ", ", c, ") is outside ", modalityName(modality), " (",
             height, ",", width, ",", channels(), ")");
    const std::size_t i = (std::size_t(y) * width + x) * channels() + c;
    switch (dtype()) {
    case DType::UInt8:
        return float(std::to_integer<std::uint8_t>(bytes[i]));
    case DType::UInt32:
        return float(as<std::uint32_t>()[i]);
    case DType::Float16:
        return halfToFloat(as<std::uint16_t>()[i]);
    case DType::Float32:
        return as<float>()[i];
    }
    return 0.0f;
}

std::uint32_t ImageBuffer::uintAt(int x, int y, int c) const {
    SP_CHECK(dtype() == DType::UInt32, InvalidArgument, "ImageBuffer::uintAt(): ", modalityName(modality),
             " is ", dtypeName(dtype()), ", not uint32");
    SP_CHECK(x >= 0 && x < width && y >= 0 && y < height && c >= 0 && c < channels(), InvalidArgument,
             "ImageBuffer::uintAt(): (", x, ", ", y, ") is outside the image");
    return as<std::uint32_t>()[(std::size_t(y) * width + x) * channels() + c];
}

const ImageBuffer& Frame::get(Modality modality) const {
    const auto& image = images_[static_cast<std::size_t>(modality)];
    SP_CHECK(image.has_value(), NotFound, "Frame::get(): modality '", modalityName(modality),
             "' was not rendered");
    return *image;
}

ImageBuffer& Frame::prepare(Modality modality, int w, int h) {
    auto& image = images_[static_cast<std::size_t>(modality)];
    if (!image)
        image.emplace();
    image->modality = modality;
    image->width = w;
    image->height = h;
    image->bytes.resize(modalityByteSize(modality, w, h));
    return *image;
}

void Frame::clear() {
    for (auto& image : images_)
        image.reset();
}

void Frame::retain(const ModalitySet& keep) {
    for (std::size_t i = 0; i < kModalityCount; ++i)
        if (!keep.contains(static_cast<Modality>(i)))
            images_[i].reset();
}

float halfToFloat(std::uint16_t bits) {
    const std::uint32_t sign = (bits & 0x8000u) << 16;
    const std::uint32_t exponent = (bits >> 10) & 0x1f;
    const std::uint32_t mantissa = bits & 0x3ffu;
    float magnitude;
    if (exponent == 0)
        magnitude = std::ldexp(float(mantissa), -24);
    else if (exponent == 31)
        magnitude = mantissa ? NAN : INFINITY;
    else
        magnitude = std::ldexp(float(mantissa | 0x400u), int(exponent) - 25);
    std::uint32_t out;
    std::memcpy(&out, &magnitude, 4);
    out |= sign;
    float result;
    std::memcpy(&result, &out, 4);
    return result;
}

std::uint16_t floatToHalf(float value) {
    // Round to nearest even via the float's bits (good enough for tests and tools; not on a hot path).
    std::uint32_t x;
    std::memcpy(&x, &value, 4);
    const std::uint16_t sign = static_cast<std::uint16_t>((x >> 16) & 0x8000u);
    const float magnitude = std::fabs(value);
    if (std::isnan(value))
        return sign | 0x7e00u;
    if (magnitude >= 65520.0f)
        return sign | 0x7c00u;
    if (magnitude < std::ldexp(1.0f, -14)) { // subnormal
        return sign | static_cast<std::uint16_t>(std::nearbyint(magnitude * std::ldexp(1.0f, 24)));
    }
    int exponent;
    const float fraction = std::frexp(magnitude, &exponent); // magnitude = fraction * 2^exponent, [0.5, 1)
    auto mantissa = static_cast<std::uint32_t>(std::nearbyint((fraction * 2.0f - 1.0f) * 1024.0f));
    int biased = exponent - 1 + 15;
    if (mantissa == 1024) {
        mantissa = 0;
        ++biased;
    }
    return sign | static_cast<std::uint16_t>((biased << 10) | mantissa);
}

} // namespace sp::render
