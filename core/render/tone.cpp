#include "core/render/tone.h"
#include "core/render/luminance.h"

#include <algorithm>
#include <cmath>

namespace sp::render {

namespace {

// Linear sRGB of the black body at `kelvin`, with luminance Y = 1.
Eigen::Vector3d planckianRgb(double t) {
    const double t2 = t * t, t3 = t2 * t;
    const double x = t <= 4000.0 ? -0.2661239e9 / t3 - 0.2343589e6 / t2 + 0.8776956e3 / t + 0.179910
                                 : -3.0258469e9 / t3 + 2.1070379e6 / t2 + 0.2226347e3 / t + 0.240390;
    const double x2 = x * x, x3 = x2 * x;
    const double y = t <= 2222.0   ? -1.1063814 * x3 - 1.34811020 * x2 + 2.18555832 * x - 0.20219683
                     : t <= 4000.0 ? -0.9549476 * x3 - 1.37418593 * x2 + 2.09137015 * x - 0.16748867
                                   : 3.0817580 * x3 - 5.87338670 * x2 + 3.75112997 * x - 0.37001483;
    const Eigen::Vector3d xyz{x / y, 1.0, (1.0 - x - y) / y};
    Eigen::Matrix3d toRgb;
    toRgb << 3.2404542, -1.5371385, -0.4985314, -0.9692660, 1.8760108, 0.0415560, 0.0556434, -0.2040259,
        1.0572252;
    return toRgb * xyz;
}

} // namespace

Eigen::Vector3f whiteBalanceGains(double kelvin) {
    const Eigen::Vector3d gains = planckianRgb(6500.0).cwiseQuotient(planckianRgb(kelvin));
    return (gains / luminance(gains)).cast<float>();
}

Vignette::Vignette(const CameraParams& params)
    : intensity_(params.vignetteIntensity),
      focal_(Camera{Eigen::Isometry3d::Identity(), params}.focalLengthPixels()), centreU_(0.5 * params.width),
      centreV_(0.5 * params.height) {}

float Vignette::operator()(double u, double v) const {
    if (intensity_ == 0.0f)
        return 1.0f;
    const double du = (u - centreU_) / focal_, dv = (v - centreV_) / focal_;
    const double cos2 = 1.0 / (1.0 + du * du + dv * dv);
    return float(1.0 + (cos2 * cos2 - 1.0) * intensity_);
}

float toneMapChannel(float hdr, int channel, const CameraParams& params) {
    const double x = std::max(double(hdr), 0.0) * params.exposure * params.whiteBalance[channel];
    double mapped = x;
    switch (params.toneMap) {
    case ToneMap::Aces:
        mapped = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
        break;
    case ToneMap::Reinhard:
        mapped = x / (1.0 + x);
        break;
    case ToneMap::Linear:
        break;
    }
    return float(srgbEncode(mapped));
}

double srgbEncode(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    return c < 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

} // namespace sp::render
