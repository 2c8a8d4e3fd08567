#pragma once
// CPU outputs of a render: one tightly packed image per modality (row 0 = top row), and the view type
// used to read straight into caller-provided memory (e.g. a shared-memory region).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/render/modality.h"

namespace sp::render {

// One modality's pixels; dtype and channels as in modalityInfo().
struct ImageBuffer {
    Modality modality = Modality::FinalColor;
    int width = 0;
    int height = 0;
    std::vector<std::byte> bytes; // (height, width[, channels]) of the modality's dtype

    int channels() const { return modalityInfo(modality).channels; }
    DType dtype() const { return modalityInfo(modality).dtype; }
    // Typed view; T must match the dtype in size (float16 is read as std::uint16_t bits).
    template <typename T> std::span<const T> as() const {
        return {reinterpret_cast<const T*>(bytes.data()), bytes.size() / sizeof(T)};
    }
    // Channel c of pixel (x, y) converted to float (float16 decoded).
    float at(int x, int y, int c = 0) const;
    std::uint32_t uintAt(int x, int y, int c = 0) const;
};

// Caller-provided destination for one modality: exactly modalityByteSize(modality, width, height)
// bytes, written tightly packed with row 0 = top row.
struct OutputView {
    Modality modality;
    void* data;
    std::size_t size;
};

// The outputs of one frame.
class Frame {
  public:
    std::uint64_t frameNumber = 0; // 1 for the first submit of a RenderTarget
    int width = 0;
    int height = 0;

    bool has(Modality modality) const { return images_[static_cast<std::size_t>(modality)].has_value(); }
    // Throws sp::NotFound "Frame::get(): modality 'x' was not rendered".
    const ImageBuffer& get(Modality modality) const;
    // Allocates (or reuses) the buffer for a modality at the given size.
    ImageBuffer& prepare(Modality modality, int width, int height);
    void clear();
    // Drops the buffers of modalities outside `keep` (buffers inside are kept for reuse).
    void retain(const ModalitySet& keep);

  private:
    std::array<std::optional<ImageBuffer>, kModalityCount> images_;
};

// IEEE 754 binary16 <-> binary32.
float halfToFloat(std::uint16_t bits);
std::uint16_t floatToHalf(float value);

} // namespace sp::render
