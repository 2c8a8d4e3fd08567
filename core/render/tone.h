#pragma once
// The tone curve of final_color on the CPU: exposure, the camera's curve (ACES: Narkowicz's fit;
// Reinhard; linear clamp) and the exact sRGB OETF. The surface pass's shader computes the same (its sRGB
// within a quarter of an 8-bit step); the background colour and the path tracer's images use this.

#include "core/render/camera.h"

namespace sp::render {

// The sRGB-encoded value in [0, 1] of one linear HDR channel.
float toneMapChannel(float hdr, const CameraParams& params);

} // namespace sp::render
