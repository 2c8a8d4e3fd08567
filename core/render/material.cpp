#include "core/render/material.h"

#include "core/base/error.h"

namespace sp::render {

void Material::validate(const char* function) const {
    SP_CHECK(baseColor.allFinite() && (baseColor.array() >= 0.0f).all(), InvalidArgument, function,
             "(): baseColor must be finite and >= 0, got (", baseColor.transpose(), ")");
    SP_CHECK(roughness >= 0.0f && roughness <= 1.0f, InvalidArgument, function,
             "(): roughness must be in [0, 1], got ", roughness);
    SP_CHECK(metallic >= 0.0f && metallic <= 1.0f, InvalidArgument, function,
             "(): metallic must be in [0, 1], got ", metallic);
    SP_CHECK(ambientOcclusion >= 0.0f && ambientOcclusion <= 1.0f, InvalidArgument, function,
             "(): ambientOcclusion must be in [0, 1], got ", ambientOcclusion);
    SP_CHECK(emissive.allFinite() && (emissive.array() >= 0.0f).all(), InvalidArgument, function,
             "(): emissive must be finite and >= 0, got (", emissive.transpose(), ")");
    SP_CHECK(validTextureSize(textureSize), InvalidArgument, function,
             "(): textureSize must be 0 (the mesh's uvs) or finite and >= 1e-6 m, got ", textureSize);
}

} // namespace sp::render
