#pragma once
// PBR metallic-roughness material (glTF / UE4 conventions). Pure logic, no GL.

#include <cmath>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "core/render/handles.h"

namespace sp::render {

struct Material {
    Eigen::Vector4f baseColor{0.8f, 0.8f, 0.8f, 1.0f};  // linear RGB + alpha (alpha unused: opaque)
    float roughness = 0.5f;                             // perceptual roughness in [0, 1]
    float metallic = 0.0f;                              // [0, 1]
    float ambientOcclusion = 1.0f;                      // [0, 1], scales ambient light only
    Eigen::Vector3f emissive = Eigen::Vector3f::Zero(); // linear radiance added to hdr_color
    std::optional<TextureId> baseColorTexture;          // sRGB; multiplies baseColor
    // R = ambient occlusion, G = roughness, B = metallic, multiplying the factors: glTF's occlusion and
    // metallic-roughness maps packed (packOcclusionRoughnessMetallic(), which makes R 255 without occlusion).
    std::optional<TextureId> roughnessMetallicTexture;
    std::optional<TextureId> normalTexture; // tangent-space normal map (OpenGL convention, +Y up)
    // Metres one repeat of the textures covers, projected on the object's scaled box axes (box_uv.h); 0: the
    // textures follow the mesh's own uvs.
    float textureSize = 0.0f;
    std::uint32_t id = 0; // value in material_ids; 0 = handle index + 1

    bool hasTextures() const { return baseColorTexture || roughnessMetallicTexture || normalTexture; }
    // Whether the textures are projected on the object's box axes (box_uv.h) rather than the mesh's uvs.
    bool boxUv() const { return textureSize > 0.0f && hasTextures(); }
    // What validate() accepts as a texture size (so does the engine's AMaterialLibrary): 0, or finite and at
    // least a micrometre. A smaller texture would alias to noise at any distance; the bound also keeps its
    // inverse, which the renderers use, finite.
    static bool validTextureSize(float metres) {
        return metres == 0.0f || (std::isfinite(metres) && metres >= 1e-6f);
    }

    // Throws sp::InvalidArgument naming the bad field.
    void validate(const char* function) const;
};

} // namespace sp::render
