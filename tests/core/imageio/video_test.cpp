// MP4 video (Mp4Encoder): decoded by FFmpeg again, the file has every frame, at its size (odd sizes padded
// to even), its rate, and colours within the codec's loss of the frames given; bad input is refused naming
// the function.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include "core/base/error.h"
#include "core/imageio/video.h"

namespace sp::imageio {
namespace {

// Frame `i` of a test clip: a colour gradient with a bright square moving one step a frame.
std::vector<std::uint8_t> clipFrame(int width, int height, int channels, int i) {
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * std::size_t(channels));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p =
                &pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels)];
            const bool square = x >= 4 * i && x < 4 * i + 12 && y >= 8 && y < 20;
            p[0] = square ? 240 : std::uint8_t(40 + 150 * x / width);
            p[1] = square ? 240 : std::uint8_t(60 + 120 * y / height);
            p[2] = square ? 240 : 90;
            if (channels == 4)
                p[3] = 255;
        }
    return pixels;
}

struct Decoded {
    int width = 0, height = 0, frames = 0;
    double frameRate = 0.0;
    std::string codec;
    std::vector<std::vector<std::uint8_t>> rgb; // each frame, RGB24
};

Decoded decode(const std::string& path) {
    Decoded result;
    AVFormatContext* format = nullptr;
    EXPECT_EQ(avformat_open_input(&format, path.c_str(), nullptr, nullptr), 0);
    EXPECT_GE(avformat_find_stream_info(format, nullptr), 0);
    EXPECT_EQ(format->nb_streams, 1u);
    AVStream* stream = format->streams[0];
    const AVCodec* codec = avcodec_find_decoder(stream->codecpar->codec_id);
    result.codec = codec->name;
    AVCodecContext* context = avcodec_alloc_context3(codec);
    avcodec_parameters_to_context(context, stream->codecpar);
    EXPECT_EQ(avcodec_open2(context, codec, nullptr), 0);
    result.width = context->width;
    result.height = context->height;
    result.frameRate = av_q2d(stream->avg_frame_rate);
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    SwsContext* convert = nullptr;
    const auto receive = [&] {
        while (avcodec_receive_frame(context, frame) == 0) {
            convert = sws_getCachedContext(convert, frame->width, frame->height, AVPixelFormat(frame->format),
                                           frame->width, frame->height, AV_PIX_FMT_RGB24, SWS_BICUBIC,
                                           nullptr, nullptr, nullptr);
            const int* coefficients = sws_getCoefficients(SWS_CS_ITU709);
            sws_setColorspaceDetails(convert, coefficients, 0, coefficients, 1, 0, 1 << 16, 1 << 16);
            std::vector<std::uint8_t> rgb(std::size_t(frame->width) * std::size_t(frame->height) * 3);
            std::uint8_t* planes[1] = {rgb.data()};
            const int strides[1] = {frame->width * 3};
            sws_scale(convert, frame->data, frame->linesize, 0, frame->height, planes, strides);
            result.rgb.push_back(std::move(rgb));
            ++result.frames;
        }
    };
    while (av_read_frame(format, packet) == 0) {
        avcodec_send_packet(context, packet);
        av_packet_unref(packet);
        receive();
    }
    avcodec_send_packet(context, nullptr);
    receive();
    sws_freeContext(convert);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&context);
    avformat_close_input(&format);
    return result;
}

class Video : public ::testing::Test {
  protected:
    void SetUp() override {
        file_ =
            (std::filesystem::temp_directory_path() / ("spear_video_" + std::to_string(::getpid()) + ".mp4"))
                .string();
    }
    void TearDown() override { std::filesystem::remove(file_); }
    void write(const std::string& bytes) const {
        std::ofstream(file_, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    }
    std::string file_;
};

TEST_F(Video, HoldsEveryFrameAtItsSizeAndRateWithinTheCodecsLoss) {
    const int width = 96, height = 64, frames = 12;
    Mp4Encoder encoder(width, height, 24.0, "test");
    EXPECT_EQ(encoder.codecName(), "libx264"); // Debian's libavcodec has it
    std::vector<std::vector<std::uint8_t>> given;
    for (int i = 0; i < frames; ++i) {
        given.push_back(clipFrame(width, height, 4, i));
        encoder.add({width, height, 4, PixelType::UInt8, given.back().data()});
    }
    const std::string bytes = encoder.finish();
    ASSERT_GT(bytes.size(), 1000u);
    EXPECT_EQ(bytes.substr(4, 4), "ftyp");
    write(bytes);
    const Decoded video = decode(file_);
    EXPECT_EQ(video.codec, "h264");
    EXPECT_EQ(video.width, width);
    EXPECT_EQ(video.height, height);
    EXPECT_NEAR(video.frameRate, 24.0, 1e-6);
    ASSERT_EQ(video.frames, frames);
    for (int i = 0; i < frames; ++i) { // frame i is the i-th given, in order: the square is where it was
        double difference = 0.0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 3; ++c)
                    difference +=
                        std::abs(double(video.rgb[std::size_t(i)][std::size_t((y * width + x) * 3 + c)]) -
                                 double(given[std::size_t(i)][std::size_t((y * width + x) * 4 + c)]));
        EXPECT_LT(difference / (width * height * 3), 4.0) << "frame " << i;
    }
}

TEST_F(Video, OddSizesArePaddedByOneRepeatedColumnAndRow) {
    const int width = 33, height = 21;
    Mp4Encoder encoder(width, height, 30.0, "test");
    EXPECT_EQ(encoder.videoWidth(), 34);
    EXPECT_EQ(encoder.videoHeight(), 22);
    for (int i = 0; i < 3; ++i) {
        const std::vector<std::uint8_t> rgb = clipFrame(width, height, 3, i);
        encoder.add({width, height, 3, PixelType::UInt8, rgb.data()});
    }
    write(encoder.finish());
    const Decoded video = decode(file_);
    EXPECT_EQ(video.width, 34);
    EXPECT_EQ(video.height, 22);
    EXPECT_EQ(video.frames, 3);
}

TEST_F(Video, BadInputIsRefusedNamingTheFunction) {
    EXPECT_THROW(Mp4Encoder(0, 10, 30.0, "f"), InvalidArgument);
    EXPECT_THROW(Mp4Encoder(10, 10, 0.0, "f"), InvalidArgument);
    EXPECT_THROW(Mp4Encoder(10, 10, std::nan(""), "f"), InvalidArgument);
    Mp4Encoder encoder(16, 16, 30.0, "render job 'x'");
    const std::vector<std::uint8_t> small(8 * 8 * 3, 0);
    try {
        encoder.add({8, 8, 3, PixelType::UInt8, small.data()});
        FAIL() << "expected InvalidArgument";
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "render job 'x': frame 0 is 8x8, the video 16x16");
    }
    const std::vector<float> floats(16 * 16, 0.0f);
    EXPECT_THROW(encoder.add({16, 16, 1, PixelType::Float, floats.data()}), InvalidArgument);
    EXPECT_THROW(encoder.finish(), InvalidState); // no frame
}

} // namespace
} // namespace sp::imageio
