#include "core/imageio/video.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "core/base/error.h"

namespace sp::imageio {
namespace {

std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

} // namespace

struct Mp4Encoder::State {
    AVFormatContext* format = nullptr;
    AVCodecContext* codec = nullptr;
    AVStream* stream = nullptr;
    AVFrame* frame = nullptr;
    AVPacket* packet = nullptr;
    SwsContext* convert = nullptr;
    std::vector<std::uint8_t> padded; // an odd-sized frame, its last column or row repeated

    ~State() {
        sws_freeContext(convert);
        av_packet_free(&packet);
        av_frame_free(&frame);
        avcodec_free_context(&codec);
        if (format != nullptr && format->pb != nullptr) {
            std::uint8_t* bytes = nullptr;
            avio_close_dyn_buf(format->pb, &bytes);
            av_free(bytes);
        }
        avformat_free_context(format);
    }
};

Mp4Encoder::Mp4Encoder(int width, int height, double frameRate, std::string_view function)
    : state_(std::make_unique<State>()), function_(function), width_(width), height_(height) {
    SP_CHECK(width >= 1 && width <= 16384 && height >= 1 && height <= 16384, InvalidArgument, function_,
             ": a video must be 1 to 16384 pixels a side, got ", width, "x", height);
    SP_CHECK(frameRate > 0.0 && frameRate <= 1000.0, InvalidArgument, function_,
             ": the frame rate must be in (0, 1000] frames a second, got ", frameRate);
    // x264 reports its settings and statistics on stderr for every video; errors are enough.
    av_log_set_level(AV_LOG_ERROR);
    State& s = *state_;
    int error = avformat_alloc_output_context2(&s.format, nullptr, "mp4", nullptr);
    SP_CHECK(error >= 0 && s.format != nullptr, InvalidState, function_, ": no MP4 muxer (", avError(error),
             ")");
    // x264 where libavcodec was built with it (Debian's is); FFmpeg's own MPEG-4 encoder otherwise.
    const AVCodec* encoder = avcodec_find_encoder_by_name("libx264");
    if (encoder == nullptr)
        encoder = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
    SP_CHECK(encoder != nullptr, InvalidState, function_,
             ": libavcodec has neither libx264 nor an MPEG-4 encoder");
    codecName_ = encoder->name;
    s.stream = avformat_new_stream(s.format, nullptr);
    s.codec = avcodec_alloc_context3(encoder);
    SP_CHECK(s.stream != nullptr && s.codec != nullptr, InvalidState, function_, ": out of memory");
    s.codec->width = (width + 1) & ~1;
    s.codec->height = (height + 1) & ~1;
    s.codec->pix_fmt = AV_PIX_FMT_YUV420P;
    const AVRational rate = av_d2q(frameRate, 100000);
    s.codec->framerate = rate;
    s.codec->time_base = av_inv_q(rate);
    s.codec->color_primaries = AVCOL_PRI_BT709;
    s.codec->color_trc = AVCOL_TRC_IEC61966_2_1; // final_color is sRGB-encoded
    s.codec->colorspace = AVCOL_SPC_BT709;
    s.codec->color_range = AVCOL_RANGE_MPEG;
    if (codecName_ == "libx264") {
        av_opt_set(s.codec->priv_data, "crf", "18", 0);
        av_opt_set(s.codec->priv_data, "preset", "medium", 0);
    } else {
        s.codec->bit_rate = std::int64_t(0.25 * double(s.codec->width) * double(s.codec->height) * frameRate);
        s.codec->gop_size = 12;
    }
    if ((s.format->oformat->flags & AVFMT_GLOBALHEADER) != 0)
        s.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    error = avcodec_open2(s.codec, encoder, nullptr);
    SP_CHECK(error >= 0, InvalidState, function_, ": cannot open the ", codecName_, " encoder (",
             avError(error), ")");
    error = avcodec_parameters_from_context(s.stream->codecpar, s.codec);
    SP_CHECK(error >= 0, InvalidState, function_, ": ", avError(error));
    s.stream->time_base = s.codec->time_base;
    // In memory (seekable: the muxer writes the index at the end and goes back for the sizes).
    error = avio_open_dyn_buf(&s.format->pb);
    SP_CHECK(error >= 0, InvalidState, function_, ": ", avError(error));
    error = avformat_write_header(s.format, nullptr);
    SP_CHECK(error >= 0, InvalidState, function_, ": cannot start the MP4 file (", avError(error), ")");

    s.frame = av_frame_alloc();
    s.packet = av_packet_alloc();
    SP_CHECK(s.frame != nullptr && s.packet != nullptr, InvalidState, function_, ": out of memory");
    s.frame->format = s.codec->pix_fmt;
    s.frame->width = s.codec->width;
    s.frame->height = s.codec->height;
    error = av_frame_get_buffer(s.frame, 0);
    SP_CHECK(error >= 0, InvalidState, function_, ": ", avError(error));
}

Mp4Encoder::~Mp4Encoder() = default;

int Mp4Encoder::videoWidth() const {
    return state_->codec->width;
}
int Mp4Encoder::videoHeight() const {
    return state_->codec->height;
}

void Mp4Encoder::add(const ImageView& frame) {
    SP_CHECK(!finished_, InvalidState, function_, ": the video is finished");
    SP_CHECK(frame.type == PixelType::UInt8 && (frame.channels == 3 || frame.channels == 4), InvalidArgument,
             function_, ": a video frame must be 8-bit RGB or RGBA, got ", frame.channels, " channels of ",
             toString(frame.type));
    SP_CHECK(frame.width == width_ && frame.height == height_, InvalidArgument, function_, ": frame ",
             frames_, " is ", frame.width, "x", frame.height, ", the video ", width_, "x", height_);
    State& s = *state_;
    const int w = s.codec->width, h = s.codec->height, c = frame.channels;
    const std::uint8_t* pixels = static_cast<const std::uint8_t*>(frame.data);
    int stride = width_ * c;
    if (w != width_ || h != height_) { // odd: the last column and row repeated
        s.padded.resize(std::size_t(w) * std::size_t(h) * std::size_t(c));
        for (int y = 0; y < h; ++y) {
            const std::uint8_t* row = pixels + std::size_t(std::min(y, height_ - 1)) * std::size_t(stride);
            std::uint8_t* out = s.padded.data() + std::size_t(y) * std::size_t(w) * std::size_t(c);
            std::memcpy(out, row, std::size_t(stride));
            if (w != width_)
                std::memcpy(out + stride, row + stride - c, std::size_t(c));
        }
        pixels = s.padded.data();
        stride = w * c;
    }
    const AVPixelFormat source = c == 3 ? AV_PIX_FMT_RGB24 : AV_PIX_FMT_RGBA;
    s.convert = sws_getCachedContext(s.convert, w, h, source, w, h, AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr,
                                     nullptr, nullptr);
    SP_CHECK(s.convert != nullptr, InvalidState, function_, ": no RGB to YUV conversion");
    // BT.709 coefficients, full-range RGB in, limited-range YUV out (as the stream says).
    const int* coefficients = sws_getCoefficients(SWS_CS_ITU709);
    sws_setColorspaceDetails(s.convert, coefficients, 1, coefficients, 0, 0, 1 << 16, 1 << 16);
    int error = av_frame_make_writable(s.frame);
    SP_CHECK(error >= 0, InvalidState, function_, ": ", avError(error));
    const std::uint8_t* planes[1] = {pixels};
    const int strides[1] = {stride};
    sws_scale(s.convert, planes, strides, 0, h, s.frame->data, s.frame->linesize);
    s.frame->pts = frames_++;
    error = avcodec_send_frame(s.codec, s.frame);
    SP_CHECK(error >= 0, InvalidState, function_, ": encoding frame ", frames_ - 1, " failed (",
             avError(error), ")");
    drain(false);
}

void Mp4Encoder::drain(bool flushing) {
    State& s = *state_;
    for (;;) {
        int error = avcodec_receive_packet(s.codec, s.packet);
        if (error == AVERROR(EAGAIN) || error == AVERROR_EOF)
            return;
        SP_CHECK(error >= 0, InvalidState, function_, ": encoding failed (", avError(error), ")");
        if (s.packet->duration == 0) // one frame: the file's length then counts the last frame too
            s.packet->duration = 1;
        av_packet_rescale_ts(s.packet, s.codec->time_base, s.stream->time_base);
        s.packet->stream_index = s.stream->index;
        error = av_interleaved_write_frame(s.format, s.packet); // takes the packet's data
        SP_CHECK(error >= 0, InvalidState, function_, ": writing ", flushing ? "the last frames" : "a frame",
                 " failed (", avError(error), ")");
    }
}

std::string Mp4Encoder::finish() {
    SP_CHECK(!finished_, InvalidState, function_, ": the video is finished");
    SP_CHECK(frames_ > 0, InvalidState, function_, ": a video needs at least one frame");
    finished_ = true;
    State& s = *state_;
    int error = avcodec_send_frame(s.codec, nullptr);
    SP_CHECK(error >= 0, InvalidState, function_, ": ", avError(error));
    drain(true);
    error = av_write_trailer(s.format);
    SP_CHECK(error >= 0, InvalidState, function_, ": cannot finish the MP4 file (", avError(error), ")");
    std::uint8_t* bytes = nullptr;
    const int size = avio_close_dyn_buf(s.format->pb, &bytes);
    s.format->pb = nullptr;
    std::string file(reinterpret_cast<const char*>(bytes), std::size_t(std::max(size, 0)));
    av_free(bytes);
    return file;
}

} // namespace sp::imageio
