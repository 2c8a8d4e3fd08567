#pragma once
// The intrinsic images that are defined by other modalities, computed on the CPU from those images as read
// back (modality.h): diffuse_only = base_color * (1 - metallic) * diffuse_illumination, and
// specular_residual = hdr_color.rgb - diffuse_only. A software rasteriser writes every target of every pixel
// at a cost (about 4 ms a target at 1080p on two cores), and with all 14 modalities these two are what
// keeps base colour and the PBR parameters out of the surface pass's eight draw buffers; computing them here
// spares two targets and most of the attribute pass (planModalities()).
//
// float16 in and out, computed in float32 as the shader does (the same products in the same order), rounded
// to nearest even. Uses F16C where the CPU has it.

#include <cstddef>
#include <cstdint>

namespace sp::render {

// out (pixels x 3) = base (x 3) * (1 - metallic (x 1)) * illumination (x 3).
void computeDiffuseOnly(const std::uint16_t* base, const std::uint16_t* metallic,
                        const std::uint16_t* illumination, std::uint16_t* out, std::size_t pixels);
// out (pixels x 3) = hdr (pixels x 4, its first three channels) - diffuse (pixels x 3).
void computeSpecularResidual(const std::uint16_t* hdr, const std::uint16_t* diffuse, std::uint16_t* out,
                             std::size_t pixels);

} // namespace sp::render
