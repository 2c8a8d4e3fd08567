// PNG and EXR files hold exactly the pixels written: read back bit for bit, each pixel type and channel
// count the camera's modalities use, and bad input is refused with the function's name.

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

#include "core/base/error.h"
#include "core/imageio/exr.h"
#include "core/imageio/png.h"

namespace sp::imageio {
namespace {

namespace fs = std::filesystem;

class ImageFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() / ("spear_imageio_" + std::to_string(::getpid()));
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }
    std::string path(const std::string& name) const { return (folder_ / name).string(); }

  private:
    fs::path folder_;
};

// Distinct values per pixel and channel, so a swapped channel or row shows.
template <typename T> std::vector<T> pattern(int width, int height, int channels, T (*value)(int)) {
    std::vector<T> data(std::size_t(width * height * channels));
    for (std::size_t i = 0; i < data.size(); ++i)
        data[i] = value(int(i));
    return data;
}

TEST_F(ImageFiles, PngRoundTripsEveryChannelCount) {
    for (int channels = 1; channels <= 4; ++channels) {
        const auto data =
            pattern<std::uint8_t>(7, 5, channels, [](int i) { return std::uint8_t(i * 37 + 11); });
        const std::string file = path("image" + std::to_string(channels) + ".png");
        writePng(file, {7, 5, channels, PixelType::UInt8, data.data()}, "test");
        int width = 0, height = 0, stored = 0;
        stbi_uc* read = stbi_load(file.c_str(), &width, &height, &stored, 0);
        ASSERT_NE(read, nullptr) << stbi_failure_reason();
        EXPECT_EQ(width, 7);
        EXPECT_EQ(height, 5);
        EXPECT_EQ(stored, channels);
        EXPECT_EQ(std::memcmp(read, data.data(), data.size()), 0) << channels << " channels";
        stbi_image_free(read);
    }
}

TEST_F(ImageFiles, ExrRoundTripsHalfFloatAndUint32) {
    const auto halves = pattern<std::uint16_t>(9, 4, 3, [](int i) { return std::uint16_t(0x3c00 + i); });
    const auto floats = pattern<float>(9, 4, 1, [](int i) { return 0.25f * float(i) - 3.0f; });
    const auto ids = pattern<std::uint32_t>(9, 4, 1, [](int i) { return std::uint32_t(i) * 2654435761u; });
    const auto rgba = pattern<std::uint16_t>(9, 4, 4, [](int i) { return std::uint16_t(0x3800 + 3 * i); });
    struct Case {
        const char* name;
        ImageView view;
        std::vector<std::string> channels;
    };
    const Case cases[] = {
        {"half_rgb", {9, 4, 3, PixelType::Half, halves.data()}, {"R", "G", "B"}},
        {"float_y", {9, 4, 1, PixelType::Float, floats.data()}, {"Y"}},
        {"uint_y", {9, 4, 1, PixelType::UInt32, ids.data()}, {"Y"}},
        {"half_rgba", {9, 4, 4, PixelType::Half, rgba.data()}, {"R", "G", "B", "A"}},
        {"half_ya", {9, 4, 2, PixelType::Half, rgba.data()}, {"Y", "A"}},
    };
    for (const Case& c : cases) {
        const std::string file = path(std::string(c.name) + ".exr");
        writeExr(file, c.view, "test");
        const Image image = readExr(file, "test");
        EXPECT_EQ(image.width, 9) << c.name;
        EXPECT_EQ(image.height, 4) << c.name;
        EXPECT_EQ(image.type, c.view.type) << c.name;
        EXPECT_EQ(image.channelNames, c.channels) << c.name;
        ASSERT_EQ(image.pixels.size(), c.view.byteSize()) << c.name;
        EXPECT_EQ(std::memcmp(image.pixels.data(), c.view.data, c.view.byteSize()), 0) << c.name;
    }
}

TEST_F(ImageFiles, RefusesWrongTypesAndBadFiles) {
    const std::vector<std::uint8_t> bytes(12, 1);
    const std::vector<float> floats(12, 1.0f);
    EXPECT_THROW(writeExr(path("a.exr"), {2, 2, 3, PixelType::UInt8, bytes.data()}, "test"), InvalidArgument);
    EXPECT_THROW(writePng(path("a.png"), {2, 2, 3, PixelType::Float, floats.data()}, "test"),
                 InvalidArgument);
    EXPECT_THROW(writePng(path("a.png"), {0, 2, 3, PixelType::UInt8, bytes.data()}, "test"), InvalidArgument);
    EXPECT_THROW(readExr(path("missing.exr"), "test"), NotFound);
    std::ofstream(path("not.exr")) << "this is not an EXR file";
    try {
        readExr(path("not.exr"), "MyFunction()");
        FAIL() << "a text file was read as EXR";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("MyFunction(): '"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("is not a readable EXR file"), std::string::npos)
            << error.what();
    }
    // A failed write leaves no file behind.
    EXPECT_FALSE(fs::exists(path("a.exr")));
    EXPECT_FALSE(fs::exists(path("a.png")));
}

} // namespace
} // namespace sp::imageio
