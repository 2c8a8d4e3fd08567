#pragma once
// The tone curve of final_color on the CPU: exposure, the camera's curve (ACES: Narkowicz's fit;
// Reinhard; linear clamp) and the exact sRGB OETF. The surface pass's shader computes the same (its sRGB
// within a quarter of an 8-bit step); the background colour and the path tracer's images use this.

#include "core/render/camera.h"

namespace sp::render {

// The sRGB-encoded value in [0, 1] of channel `channel` (0 red, 1 green, 2 blue) of a linear HDR colour:
// exposure and white balance, the tone curve, sRGB.
float toneMapChannel(float hdr, int channel, const CameraParams& params);

// The exact sRGB OETF of a linear value clamped to [0, 1], and its inverse (an encoded value in [0, 1] to
// linear).
double srgbEncode(double linear);
double srgbDecode(double encoded);

// The per-channel gains that balance a camera for light of colour temperature `kelvin` (in [2000, 25000]):
// a grey lit by a black body at that temperature comes out grey. Relative to 6500 K (which gives 1, 1, 1),
// from the Planckian locus (Kim et al.'s cubic fit) in linear sRGB, scaled so that a grey keeps its
// luminance. Lower temperatures (tungsten) raise blue, higher ones raise red.
Eigen::Vector3f whiteBalanceGains(double kelvin);

// The vignetting of a camera's pixels: at (u, v) (u right, v down, the pixel (0, 0)'s centre at (0.5, 0.5)),
// mix(1, cos^4 theta, params.vignetteIntensity), theta the angle of the pixel's ray to the optical axis (the
// cos^4 law of a lens's illumination falloff). The surface shader computes the same. The focal length is
// worked out once, for images evaluated pixel by pixel.
class Vignette {
  public:
    explicit Vignette(const CameraParams& params);
    float operator()(double u, double v) const;

  private:
    float intensity_;
    double focal_, centreU_, centreV_;
};

} // namespace sp::render
