#pragma once
// MP4 video from 8-bit RGB(A) frames, through Debian's FFmpeg libraries: H.264 by libx264 (constant quality,
// CRF 18: no visible loss) where the build of libavcodec has it, else its native MPEG-4 part 2 encoder;
// 4:2:0 chroma, BT.709 colours, limited range, sRGB transfer (final_color's). H.264 in 4:2:0 needs even
// sizes: an odd width or height is padded by one column or row repeating the last (the video is that much
// larger). The file is built in memory and handed back whole, for sp::writeRegularFile to write at once.

#include <memory>
#include <string>
#include <string_view>

#include "core/imageio/image.h"

namespace sp::imageio {

class Mp4Encoder {
  public:
    // A video of width x height frames at `frameRate` frames a second (in (0, 1000]); `function` names the
    // caller in errors. Throws sp::InvalidArgument for a bad size or rate, sp::InvalidState when no encoder
    // can be opened.
    Mp4Encoder(int width, int height, double frameRate, std::string_view function);
    ~Mp4Encoder();
    Mp4Encoder(const Mp4Encoder&) = delete;
    Mp4Encoder& operator=(const Mp4Encoder&) = delete;

    // Appends a frame: UInt8, 3 or 4 channels (alpha ignored), the size given to the constructor.
    void add(const ImageView& frame);
    // Flushes the encoder and returns the file's bytes; nothing may be added after.
    std::string finish();

    // The encoder's name ("libx264", "mpeg4") and the video's size (even).
    const std::string& codecName() const { return codecName_; }
    int videoWidth() const;
    int videoHeight() const;
    int framesAdded() const { return frames_; }

  private:
    struct State;
    void drain(bool flushing);
    std::unique_ptr<State> state_;
    std::string function_;
    std::string codecName_;
    int width_ = 0;
    int height_ = 0;
    int frames_ = 0;
    bool finished_ = false;
};

} // namespace sp::imageio
