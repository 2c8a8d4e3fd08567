#include "core/render/texture_image.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_HDR
#define STBI_FAILURE_USERMSG
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb_image_write.h>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/base/regular_file.h"
#include "core/render/environment_map.h"

namespace sp::render {

TextureImage TextureImage::load(const std::string& path) {
    // Found as every asset is (asset_path.h): a /Game/ name or a path relative to the assets' folders loads
    // from any working directory. Read here rather than by stb_image's fopen: a regular file of bounded size
    // only, never a FIFO or a device that would block or never end, and a missing one (or a directory) is
    // sp::NotFound (core/base/regular_file.h).
    const std::string bytes = readRegularFile(findAsset(path), "TextureImage::load()", "texture");
    return decode(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), path);
}

TextureImage TextureImage::decode(const std::uint8_t* bytes, std::size_t size, const std::string& source) {
    int width = 0, height = 0, channels = 0;
    stbi_uc* pixels = stbi_load_from_memory(bytes, static_cast<int>(size), &width, &height, &channels, 4);
    SP_CHECK(pixels != nullptr, InvalidArgument, "TextureImage::decode(): cannot decode '", source,
             "': ", stbi_failure_reason());
    TextureImage image;
    image.width = width;
    image.height = height;
    image.rgba.assign(pixels, pixels + std::size_t(width) * height * 4);
    image.source = source;
    stbi_image_free(pixels);
    return image;
}

TextureImage TextureImage::fromPixels(int width, int height, std::vector<std::uint8_t> rgba) {
    SP_CHECK(width > 0 && height > 0 && rgba.size() == std::size_t(width) * height * 4, InvalidArgument,
             "TextureImage::fromPixels(): expected ", width, "x", height, "x4 bytes, got ", rgba.size());
    TextureImage image;
    image.width = width;
    image.height = height;
    image.rgba = std::move(rgba);
    image.source = "<memory>";
    return image;
}

TextureImage packOcclusionRoughnessMetallic(const TextureImage* roughnessMetallic,
                                            const TextureImage* occlusion) {
    SP_CHECK(roughnessMetallic != nullptr || occlusion != nullptr, InvalidArgument,
             "packOcclusionRoughnessMetallic(): neither a metallic-roughness nor an occlusion map");
    if (roughnessMetallic != nullptr && occlusion != nullptr)
        SP_CHECK(roughnessMetallic->width == occlusion->width &&
                     roughnessMetallic->height == occlusion->height,
                 InvalidArgument, "packOcclusionRoughnessMetallic(): the occlusion map '", occlusion->source,
                 "' is ", occlusion->width, "x", occlusion->height, ", the metallic-roughness map '",
                 roughnessMetallic->source, "' ", roughnessMetallic->width, "x", roughnessMetallic->height,
                 "; pack them into one image of one size");
    TextureImage packed = roughnessMetallic != nullptr ? *roughnessMetallic : *occlusion;
    for (std::size_t i = 0; i < packed.rgba.size(); i += 4) {
        packed.rgba[i] = occlusion != nullptr ? occlusion->rgba[i] : 255;
        if (roughnessMetallic == nullptr)
            packed.rgba[i + 1] = packed.rgba[i + 2] = 255;
    }
    if (roughnessMetallic != nullptr && occlusion != nullptr &&
        occlusion->source != roughnessMetallic->source)
        packed.source = roughnessMetallic->source + " + occlusion " + occlusion->source;
    return packed;
}

RadianceImage readRadianceHdr(const std::string& path, const char* function) {
    // readRegularFile throws sp::NotFound for a missing file (or a directory).
    const std::string bytes = readRegularFile(findAsset(path), function, "Radiance HDR image");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    SP_CHECK(stbi_is_hdr_from_memory(data, static_cast<int>(bytes.size())) != 0, InvalidArgument, function,
             ": '", path, "' is not a Radiance HDR (.hdr) file");
    int width = 0, height = 0, channels = 0;
    float* pixels =
        stbi_loadf_from_memory(data, static_cast<int>(bytes.size()), &width, &height, &channels, 3);
    SP_CHECK(pixels != nullptr, InvalidArgument, function, ": cannot decode '", path,
             "': ", stbi_failure_reason());
    RadianceImage image{width, height,
                        std::vector<Eigen::Vector3f>(std::size_t(width) * std::size_t(height))};
    for (std::size_t i = 0; i < image.texels.size(); ++i)
        image.texels[i] = Eigen::Vector3f(pixels[3 * i], pixels[3 * i + 1], pixels[3 * i + 2]);
    stbi_image_free(pixels);
    return image;
}

void writePng(const std::string& path, int width, int height, int channels, const std::uint8_t* pixels) {
    SP_CHECK(stbi_write_png(path.c_str(), width, height, channels, pixels, width * channels) != 0,
             InvalidState, "writePng(): cannot write '", path, "'");
}

} // namespace sp::render
