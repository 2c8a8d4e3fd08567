#pragma once
// Automatic exposure (Unreal's AutoExposure* settings): metering an image's luminance, the exposure a
// metered luminance asks for, and the eye's adaptation to it over time. Pure logic, no GL. The camera
// sensor meters the final_color it reads back (and, when a camera starts or is cut to a new view, a small
// HDR render of the view), the path tracer its own HDR image; core/render/README.md says why.

#include <cstdint>
#include <functional>

#include "core/render/camera.h"

namespace sp::render {

enum class MeteringMode {
    Mean,      // the mean of every pixel's log luminance (Unreal's Basic)
    Histogram, // the mean of the log luminances between two percentiles (Unreal's Histogram)
};

struct MeteringSettings {
    MeteringMode mode = MeteringMode::Histogram;
    double lowPercent = 10.0;  // Histogram: the darkest lowPercent % of the pixels are left out
    double highPercent = 90.0; // Histogram: the pixels above the highPercent percentile are left out
    // Each pixel's luminance, and so the metered one, is clamped to [minEv100, maxEv100] (as EV100):
    // the darkest and brightest scenes the camera adapts to.
    double minEv100 = -10.0;
    double maxEv100 = 20.0;

    // Throws sp::InvalidArgument naming `function` and the bad field.
    void validate(const char* function) const;
};

// The light meter's relation of luminance (cd/m^2) and exposure value at ISO 100 (calibration K = 12.5):
// EV100 = log2(L * 100 / 12.5).
double ev100FromLuminance(double luminance);
double luminanceFromEv100(double ev100);

// The exposure that shows a metered luminance as middle grey (0.18 before the tone curve), brightened by
// biasStops: 0.18 * 2^biasStops / L.
constexpr double kMiddleGrey = 0.18;
double exposureForEv100(double ev100, double biasStops);

// The EV100 a view meters from its pixels' luminance, luminanceAt(x, y), taken on a grid of at most about
// 16384 pixels (every metering below is this one with its own pixels).
double meterLuminance(int width, int height, const std::function<double(int x, int y)>& luminanceAt,
                      const MeteringSettings& settings);
// The same for a linear HDR image: `rgb` holds `stride` floats a pixel, red, green, blue first.
double meterHdr(const float* rgb, int width, int height, int stride, const MeteringSettings& settings);
// The same for an RGBA float16 image (hdr_color).
double meterHdrHalf(const std::uint16_t* rgba, int width, int height, const MeteringSettings& settings);
// What an RGBA8 final_color image meters: its pixels turned back into scene luminance through the tone
// curve, white balance and exposure of `params` it was rendered with. A pixel at a channel's top code (or
// black) says only that its light is at least (at most) what reaches it; `exact` is false when more of them
// than the metering leaves out (Histogram: its percentiles; Mean: 2 %) could have moved the result, so that
// a frame far off its exposure is metered again from HDR (CameraExposure) instead of adapting slowly
// towards a bound.
struct FinalColorMetering {
    double ev100 = 0.0;
    bool exact = true;
};
FinalColorMetering meterFinalColor(const std::uint8_t* rgba, int width, int height,
                                   const CameraParams& params, const MeteringSettings& settings);

// Eye adaptation: the EV100 the exposure is set for moves from `current` towards `target` exponentially,
// half the way in 1 / speed seconds (speeds in f-stops per second, as Unreal's): speedUp when the scene
// turned brighter (target > current), speedDown when darker. `seconds` >= 0 of world time passed.
double adaptEv100(double current, double target, double seconds, double speedUp, double speedDown);

} // namespace sp::render
