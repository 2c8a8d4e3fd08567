#pragma once
// The modalities that are defined by other modalities, computed on the CPU from those images as read back
// (modality.h): diffuse_only = base_color * (1 - metallic) * diffuse_illumination, specular_residual =
// hdr_color.rgb - diffuse_only, and position = the point `depth` metres along the optical axis on the
// pixel's centre ray. A software rasteriser writes every target of every pixel at a cost (about 4 ms a
// target at 1080p on two cores), and with all 14 modalities these three are what keeps the targets within
// the surface pass's eight draw buffers; computing them here spares three targets and the attribute pass
// (planModalities()).
//
// The intrinsics: float16 in and out, computed in float32 as the shader does (the same products in the same
// order), rounded to nearest even; F16C where the CPU has it.

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/render/camera.h"

namespace sp::render {

// out (pixels x 3) = base (x 3) * (1 - metallic (x 1)) * illumination (x 3).
void computeDiffuseOnly(const std::uint16_t* base, const std::uint16_t* metallic,
                        const std::uint16_t* illumination, std::uint16_t* out, std::size_t pixels);
// out (pixels x 3) = hdr (pixels x 4, its first three channels) - diffuse (pixels x 3).
void computeSpecularResidual(const std::uint16_t* hdr, const std::uint16_t* diffuse, std::uint16_t* out,
                             std::size_t pixels);
// out (height x width x 3, float32) = the world point on each pixel's centre ray at depth (height x width)
// metres along `camera`'s optical axis, computed in double precision and rounded once; 0 where depth is 0
// (the background). The rasterised position is the same point interpolated in float32 across the
// triangle: the two agree within float32 rounding of the coordinates (render_intrinsics_gl_test.cpp).
void computePositionFromDepth(const float* depth, const Camera& camera, float* out);

// out (pixels x 3, float32) = the unit normals whose octahedral coordinates a compact normal target holds
// (encoded: pixels x 2, the shaders' normalTarget()), in float32; (0, 0, 0) where it holds
// kNoOctahedralNormal (modality.h: the background), as a float normal target is cleared. Within a few units
// in the last place of the normal the shader encoded (derived_images_test.cpp).
void decodeOctahedralNormals(const float* encoded, float* out, std::size_t pixels);

// What a draw gives every pixel of its surface when its material has no base colour or roughness-metallic
// texture: its ids, and its material's factors as the float16 targets would hold them (rounded to nearest).
struct DrawMaterial {
    std::uint32_t objectId = 0, materialId = 0;
    std::uint16_t baseColor[3] = {0, 0, 0};
    std::uint16_t roughness = 0, metallic = 0, ambientOcclusion = 0;
};
// The images lookUpMaterials() fills, each null where not wanted: ids (pixels x 1), base colour (pixels x 3)
// and the parameters (pixels x 1 each).
struct MaterialImages {
    std::uint32_t* objectIds = nullptr;
    std::uint32_t* materialIds = nullptr;
    std::uint16_t* baseColor = nullptr;
    std::uint16_t* roughness = nullptr;
    std::uint16_t* metallic = nullptr;
    std::uint16_t* ambientOcclusion = nullptr;
};
// Each pixel's material modalities from the draw Target::Record names: record k > 0 gives draws[k - 1]'s,
// 0 (no surface) zeros, as the rendered targets are cleared. Throws sp::InvalidState naming the pixel when
// a record is past the draws.
void lookUpMaterials(const std::uint32_t* record, std::span<const DrawMaterial> draws, std::size_t pixels,
                     const MaterialImages& out);

} // namespace sp::render
