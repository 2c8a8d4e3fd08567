#include "core/imageio/exr.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstring>
#include <exception>

#include "core/base/error.h"
#include "core/base/regular_file.h"

namespace sp::imageio {
namespace {

// What readExr takes: the camera's largest image (16384 pixels a side), and a file of it with four float
// channels uncompressed.
constexpr std::int64_t kMaxExrExtent = 16384;
constexpr std::size_t kMaxExrFileBytes =
    std::size_t(kMaxExrExtent * kMaxExrExtent) * 16 + (std::size_t(64) << 20);

// OpenEXR writes and reads through these, so that files go through writeRegularFile/readRegularFile (whole
// writes, the server's file roots, no FIFOs) like every other file the engine touches.
class StringOStream : public Imf::OStream {
  public:
    StringOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (position_ + std::size_t(n) > bytes_.size())
            bytes_.resize(position_ + std::size_t(n));
        std::memcpy(bytes_.data() + position_, c, std::size_t(n));
        position_ += std::size_t(n);
    }
    std::uint64_t tellp() override { return position_; }
    void seekp(std::uint64_t position) override { position_ = position; }
    std::string& bytes() { return bytes_; }

  private:
    std::string bytes_;
    std::size_t position_ = 0;
};

class StringIStream : public Imf::IStream {
  public:
    explicit StringIStream(const std::string& bytes) : Imf::IStream("memory"), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (position_ + std::size_t(n) > bytes_.size())
            throw std::runtime_error("the file ends early");
        std::memcpy(c, bytes_.data() + position_, std::size_t(n));
        position_ += std::size_t(n);
        return position_ < bytes_.size();
    }
    std::uint64_t tellg() override { return position_; }
    void seekg(std::uint64_t position) override { position_ = position; }

  private:
    const std::string& bytes_;
    std::size_t position_ = 0;
};

Imf::PixelType exrType(PixelType type) {
    switch (type) {
    case PixelType::Half:
        return Imf::HALF;
    case PixelType::Float:
        return Imf::FLOAT;
    default:
        return Imf::UINT;
    }
}

std::vector<std::string> channelNames(int channels) {
    switch (channels) {
    case 1:
        return {"Y"};
    case 2:
        return {"Y", "A"};
    case 3:
        return {"R", "G", "B"};
    default:
        return {"R", "G", "B", "A"};
    }
}

// The file's channels in the order readExr promises.
std::vector<std::string> orderedNames(const Imf::ChannelList& channels) {
    std::vector<std::string> names;
    for (auto it = channels.begin(); it != channels.end(); ++it)
        names.emplace_back(it.name());
    // The orders channelNames() writes ("Y" first; EXR files list channels alphabetically).
    static const std::vector<std::string> order{"Y", "R", "G", "B", "A"};
    if (std::all_of(names.begin(), names.end(), [](const std::string& n) {
            return std::find(order.begin(), order.end(), n) != order.end();
        }))
        std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
            return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
        });
    return names;
}

// A slice of channel `index` of the interleaved pixels at `base`, whose data window starts at (x0, y0).
Imf::Slice interleavedSlice(PixelType type, char* base, int index, int channels, int width, int x0, int y0) {
    const std::size_t bytes = bytesPerChannel(type);
    const std::size_t xStride = bytes * std::size_t(channels);
    const std::size_t yStride = xStride * std::size_t(width);
    char* origin = base + bytes * std::size_t(index) - std::ptrdiff_t(x0) * std::ptrdiff_t(xStride) -
                   std::ptrdiff_t(y0) * std::ptrdiff_t(yStride);
    return Imf::Slice(exrType(type), origin, xStride, yStride);
}

} // namespace

std::string encodeExr(const ImageView& image, std::string_view function) {
    SP_CHECK(image.type != PixelType::UInt8, InvalidArgument, function,
             ": 8-bit images go to PNG files, not EXR");
    SP_CHECK(image.channels >= 1 && image.channels <= 4, InvalidArgument, function,
             ": EXR files here hold 1 to 4 channels, not ", image.channels);
    SP_CHECK(image.width > 0 && image.height > 0, InvalidArgument, function, ": empty image (", image.width,
             "x", image.height, ")");
    const std::vector<std::string> names = channelNames(image.channels);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // Level 1: a third faster than the default (4) for files 0-25 % larger (BENCHMARKS.md, "Render
        // queue").
        header.zipCompressionLevel() = 1;
        Imf::FrameBuffer frame;
        for (int c = 0; c < image.channels; ++c) {
            header.channels().insert(names[std::size_t(c)], Imf::Channel(exrType(image.type)));
            // OpenEXR's slices take a char* but only read from it when writing.
            frame.insert(names[std::size_t(c)],
                         interleavedSlice(image.type, const_cast<char*>(static_cast<const char*>(image.data)),
                                          c, image.channels, image.width, 0, 0));
        }
        StringOStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(image.height);
        } // the file's destructor writes the line offset table
        return std::move(stream.bytes());
    } catch (const std::exception& error) {
        SP_THROW(InvalidArgument, function, ": cannot encode a ", image.width, "x", image.height,
                 " EXR: ", error.what());
    }
}

void writeExr(const std::string& path, const ImageView& image, std::string_view function) {
    writeRegularFile(path, encodeExr(image, std::string(function) + ": '" + path + "'"), function,
                     "EXR file");
}

Image readExr(const std::string& path, std::string_view function) {
    const std::string bytes = readRegularFile(path, function, "EXR file", kMaxExrFileBytes);
    try {
        StringIStream stream(bytes);
        Imf::InputFile file(stream);
        const Imath::Box2i window = file.header().dataWindow();
        Image image;
        const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
        const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
        image.channelNames = orderedNames(file.header().channels());
        SP_CHECK(!image.channelNames.empty() && image.channelNames.size() <= 4, InvalidArgument, function,
                 ": EXR file '", path, "' has ", image.channelNames.size(), " channels; 1 to 4 are read");
        // A small file may declare a huge image: the size is checked before anything is allocated.
        SP_CHECK(width > 0 && height > 0 && width <= kMaxExrExtent && height <= kMaxExrExtent,
                 InvalidArgument, function, ": EXR file '", path, "' declares a ", width, "x", height,
                 " image; at most ", kMaxExrExtent, "x", kMaxExrExtent, " is read");
        image.width = int(width);
        image.height = int(height);
        const Imf::PixelType type = file.header().channels()[image.channelNames.front()].type;
        image.type = type == Imf::HALF    ? PixelType::Half
                     : type == Imf::FLOAT ? PixelType::Float
                                          : PixelType::UInt32;
        const int channels = int(image.channelNames.size());
        image.pixels.resize(std::size_t(image.width) * std::size_t(image.height) * std::size_t(channels) *
                            bytesPerChannel(image.type));
        Imf::FrameBuffer frame;
        for (int c = 0; c < channels; ++c) {
            const std::string& name = image.channelNames[std::size_t(c)];
            SP_CHECK(file.header().channels()[name].type == type, InvalidArgument, function, ": EXR file '",
                     path, "' mixes pixel types (channel ", name, " against ", image.channelNames.front(),
                     ")");
            frame.insert(name, interleavedSlice(image.type, reinterpret_cast<char*>(image.pixels.data()), c,
                                                channels, image.width, window.min.x, window.min.y));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const sp::Error&) {
        throw;
    } catch (const std::exception& error) {
        SP_THROW(InvalidArgument, function, ": '", path, "' is not a readable EXR file: ", error.what());
    }
}

} // namespace sp::imageio
