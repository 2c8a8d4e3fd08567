#include "core/render/tone.h"

#include <algorithm>
#include <cmath>

namespace sp::render {

float toneMapChannel(float hdr, const CameraParams& params) {
    const double x = std::max(double(hdr), 0.0) * params.exposure;
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
    const double c = std::clamp(mapped, 0.0, 1.0);
    return float(c < 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

} // namespace sp::render
