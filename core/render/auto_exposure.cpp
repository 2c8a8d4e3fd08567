#include "core/render/auto_exposure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

#include "core/base/error.h"
#include "core/render/image_buffer.h"
#include "core/render/luminance.h"
#include "core/render/tone.h"

namespace sp::render {
namespace {

constexpr double kLog2MeterScale = 3.0; // log2(100 / 12.5)
constexpr int kMaxSamples = 16384;

// The stride of a square grid of at most about kMaxSamples pixels over the image.
int sampleStride(int width, int height) {
    const double pixels = double(width) * double(height);
    return std::max(1, int(std::ceil(std::sqrt(pixels / kMaxSamples))));
}

// Calls visit(x, y) for the grid's pixels, the grid centred in the image.
template <typename Visit> void forSamples(int width, int height, Visit&& visit) {
    const int stride = sampleStride(width, height);
    for (int y = (height % stride) / 2 + stride / 2; y < height; y += stride)
        for (int x = (width % stride) / 2 + stride / 2; x < width; x += stride)
            visit(x, y);
}

// The metered EV100 of the samples' EV100s (each already clamped to the settings' range).
double metered(std::vector<double>& ev, const MeteringSettings& settings) {
    if (ev.empty())
        return std::clamp(0.0, settings.minEv100, settings.maxEv100);
    auto first = ev.begin(), last = ev.end();
    if (settings.mode == MeteringMode::Histogram) {
        const auto at = [&](double percent) {
            return ev.begin() + std::ptrdiff_t(std::floor(percent / 100.0 * double(ev.size())));
        };
        first = at(settings.lowPercent);
        last = std::max(first + 1, at(settings.highPercent));
        last = std::min(last, ev.end());
        first = std::min(first, last - 1);
        // Only the samples in [first, last) of the sorted order count; partitioning finds them.
        std::nth_element(ev.begin(), first, ev.end());
        std::nth_element(first, last - 1, ev.end());
    }
    return std::accumulate(first, last, 0.0) / double(last - first);
}

double clampedEv(double luminance, const MeteringSettings& settings) {
    // A black pixel (or a NaN) meters as the darkest scene the camera adapts to.
    const double ev = luminance > 0.0 ? ev100FromLuminance(luminance) : settings.minEv100;
    return std::clamp(std::isnan(ev) ? settings.minEv100 : ev, settings.minEv100, settings.maxEv100);
}

// The scene radiance (at exposure 1, no white balance) of each 8-bit code of final_color under `toneMap`:
// the code's centre through the inverse of the tone curve and sRGB, found by bisection (every curve rises).
// Code 0 reads as a quarter of code 1 (its light is anything below); a code at the curve's top reads as the
// least that reaches it. Worked out once per curve.
const std::array<double, 256>& codeRadiance(ToneMap toneMap) {
    static const std::array<std::array<double, 256>, 3> tables = [] {
        std::array<std::array<double, 256>, 3> result{};
        for (ToneMap curve : {ToneMap::Aces, ToneMap::Reinhard, ToneMap::Linear}) {
            CameraParams unit;
            unit.toneMap = curve;
            const auto encoded = [&](double x) { return double(toneMapChannel(float(x), 0, unit)); };
            const double top = encoded(1e9);
            std::array<double, 256>& linear = result[std::size_t(curve)];
            for (int code = 1; code < 256; ++code) {
                const double wanted = std::min((code + (code == 255 ? 0.0 : 0.5)) / 255.0, top - 1e-6);
                double lo = 0.0, hi = 1.0;
                while (encoded(hi) < wanted && hi < 1e9)
                    hi *= 2.0;
                for (int i = 0; i < 60; ++i) {
                    const double mid = 0.5 * (lo + hi);
                    (encoded(mid) < wanted ? lo : hi) = mid;
                }
                linear[std::size_t(code)] = hi;
            }
            linear[0] = 0.25 * linear[1];
        }
        return result;
    }();
    return tables[std::size_t(toneMap)];
}

} // namespace

void MeteringSettings::validate(const char* function) const {
    SP_CHECK(std::isfinite(lowPercent) && std::isfinite(highPercent) && lowPercent >= 0.0 &&
                 highPercent <= 100.0 && lowPercent < highPercent,
             InvalidArgument, function,
             "(): the metered percentiles must satisfy 0 <= low < high <= 100, got ", lowPercent, " and ",
             highPercent);
    SP_CHECK(std::isfinite(minEv100) && std::isfinite(maxEv100) && minEv100 <= maxEv100, InvalidArgument,
             function, "(): the metered EV100 range must be finite with min <= max, got ", minEv100, " and ",
             maxEv100);
}

double ev100FromLuminance(double luminance) {
    return std::log2(luminance) + kLog2MeterScale;
}

double luminanceFromEv100(double ev100) {
    return std::exp2(ev100 - kLog2MeterScale);
}

double exposureForEv100(double ev100, double biasStops) {
    return kMiddleGrey * std::exp2(biasStops) / luminanceFromEv100(ev100);
}

double meterLuminance(int width, int height, const std::function<double(int x, int y)>& luminanceAt,
                      const MeteringSettings& settings) {
    std::vector<double> ev;
    forSamples(width, height, [&](int x, int y) { ev.push_back(clampedEv(luminanceAt(x, y), settings)); });
    return metered(ev, settings);
}

double meterHdr(const float* rgb, int width, int height, int stride, const MeteringSettings& settings) {
    return meterLuminance(
        width, height,
        [&](int x, int y) {
            const float* p =
                rgb + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(stride);
            return luminance<double>(p[0], p[1], p[2]);
        },
        settings);
}

double meterHdrHalf(const std::uint16_t* rgba, int width, int height, const MeteringSettings& settings) {
    return meterLuminance(
        width, height,
        [&](int x, int y) {
            const std::uint16_t* p = rgba + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
            return luminance<double>(halfToFloat(p[0]), halfToFloat(p[1]), halfToFloat(p[2]));
        },
        settings);
}

FinalColorMetering meterFinalColor(const std::uint8_t* rgba, int width, int height,
                                   const CameraParams& params, const MeteringSettings& settings) {
    const std::array<double, 256>& linear = codeRadiance(params.toneMap);
    std::array<double, 3> gain{};
    for (int c = 0; c < 3; ++c)
        gain[std::size_t(c)] =
            1.0 / std::max(1e-30, double(params.exposure) * double(params.whiteBalance[c]));
    std::size_t samples = 0, bright = 0, dark = 0;
    const double ev = meterLuminance(
        width, height,
        [&](int x, int y) {
            const std::uint8_t* p = rgba + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
            const std::uint8_t top = std::max({p[0], p[1], p[2]});
            ++samples;
            bright += top == 255;
            dark += top == 0;
            return luminance(linear[p[0]] * gain[0], linear[p[1]] * gain[1], linear[p[2]] * gain[2]);
        },
        settings);
    const bool histogram = settings.mode == MeteringMode::Histogram;
    const double n = double(std::max<std::size_t>(samples, 1));
    const bool exact = double(bright) / n <= (histogram ? 1.0 - settings.highPercent / 100.0 : 0.02) &&
                       double(dark) / n <= (histogram ? settings.lowPercent / 100.0 : 0.02);
    return {ev, exact};
}

double adaptEv100(double current, double target, double seconds, double speedUp, double speedDown) {
    const double speed = target > current ? speedUp : speedDown;
    return current + (target - current) * (1.0 - std::exp2(-std::max(0.0, seconds) * speed));
}

} // namespace sp::render
