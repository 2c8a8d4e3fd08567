#include "core/sensors/camera_exposure.h"

#include <algorithm>

#include "core/base/error.h"

namespace sp::sensors {

sp::render::MeteringSettings meteringSettings(const UCameraSensorComponent& camera) {
    const std::string who = camera.GetDebugName() + ": ";
    SP_CHECK(camera.AutoExposureMinBrightness <= camera.AutoExposureMaxBrightness, sp::InvalidArgument, who,
             "AutoExposureMinBrightness (", camera.AutoExposureMinBrightness,
             ") must not exceed AutoExposureMaxBrightness (", camera.AutoExposureMaxBrightness, ")");
    SP_CHECK(camera.AutoExposureLowPercent < camera.AutoExposureHighPercent, sp::InvalidArgument, who,
             "AutoExposureLowPercent (", camera.AutoExposureLowPercent,
             ") must be below AutoExposureHighPercent (", camera.AutoExposureHighPercent, ")");
    sp::render::MeteringSettings settings;
    settings.mode = camera.AutoExposureMethod == EAutoExposureMethod::AEM_Basic
                        ? sp::render::MeteringMode::Mean
                        : sp::render::MeteringMode::Histogram;
    settings.lowPercent = camera.AutoExposureLowPercent;
    settings.highPercent = camera.AutoExposureHighPercent;
    settings.minEv100 = camera.AutoExposureMinBrightness;
    settings.maxEv100 = camera.AutoExposureMaxBrightness;
    settings.validate("UCameraSensorComponent");
    return settings;
}

float CameraExposure::exposureFor(
    const UCameraSensorComponent& camera, double now,
    const std::function<double(const sp::render::MeteringSettings&)>& meterView) {
    if (camera.AutoExposureMethod == EAutoExposureMethod::AEM_Manual) {
        reset();
        return camera.Exposure;
    }
    const sp::render::MeteringSettings settings = meteringSettings(camera);
    if (!adapted_) {
        adapted_ = meterView(settings);
    } else if (metered_) {
        if (!exact_)
            metered(meterView(settings));
        adapted_ = sp::render::adaptEv100(*adapted_, *metered_, now - lastTime_, camera.AutoExposureSpeedUp,
                                          camera.AutoExposureSpeedDown);
    }
    lastTime_ = now;
    const double ev = std::clamp(*adapted_, settings.minEv100, settings.maxEv100);
    return float(sp::render::exposureForEv100(ev, camera.AutoExposureBias));
}

void CameraExposure::reset() {
    adapted_.reset();
    metered_.reset();
}

} // namespace sp::sensors
