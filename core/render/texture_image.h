#pragma once
// An 8-bit RGBA image in CPU memory, decoded from PNG/JPG with stb_image. Pure logic, no GL.

#include <cstdint>
#include <string>
#include <vector>

namespace sp::render {

struct TextureImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // uint8 (height, width, 4), row 0 = top row
    std::string source;             // file path or "<memory>"

    // Throws sp::NotFound naming the path when the file is missing, sp::InvalidArgument when it cannot
    // be decoded.
    static TextureImage load(const std::string& path);
    // Decodes an encoded PNG/JPG held in memory; throws sp::InvalidArgument when it cannot be decoded.
    static TextureImage decode(const std::uint8_t* bytes, std::size_t size, const std::string& source);
    // Wraps raw pixels uint8 (height, width, 4); throws sp::InvalidArgument on a size mismatch.
    static TextureImage fromPixels(int width, int height, std::vector<std::uint8_t> rgba);
};

// The one texture a Material's roughnessMetallicTexture is: glTF's occlusion map's R in R, its
// metallic-roughness map's G (roughness) and B (metallic), the packing glTF files and UE's ORM textures
// share. Either map may be absent: without an occlusion map R is 255 (nothing occluded, whatever the
// metallic-roughness map held in its unused R); without a metallic-roughness map G and B are 255 (the
// material's factors unscaled). Two maps must have one size; throws sp::InvalidArgument naming both
// otherwise, and when neither is given.
TextureImage packOcclusionRoughnessMetallic(const TextureImage* roughnessMetallic,
                                            const TextureImage* occlusion);

// Writes uint8 (height, width, channels) pixels as PNG; throws sp::InvalidState when writing fails.
void writePng(const std::string& path, int width, int height, int channels, const std::uint8_t* pixels);

} // namespace sp::render
