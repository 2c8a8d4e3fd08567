#pragma once
// The automatic exposure of one camera (UCameraSensorComponent's AutoExposure* settings): the EV100 the
// camera is adapted to, moved each frame towards what its last read final_color metered, over the world time
// between its frames. A cut (the camera's first frame, or ResetAutoExposure()) has nothing to adapt from,
// and a frame too far off its exposure (clipped) meters only a bound: then the view is metered before it
// renders.

#include <functional>
#include <optional>

#include "core/render/auto_exposure.h"
#include "core/sensors/camera_sensor_component.h"

namespace sp::sensors {

// The camera's metering settings. Throws sp::InvalidArgument naming the camera when its percentiles or
// brightness range contradict each other (each is checked alone when set).
sp::render::MeteringSettings meteringSettings(const UCameraSensorComponent& camera);

class CameraExposure {
  public:
    // The exposure of the camera's frame about to render at world time `now` (seconds): its Exposure with
    // AEM_Manual (which also forgets the adaptation: turning a method on again is a cut); else the metered
    // one, from the adaptation or, at a cut, from meterView(settings) (the EV100 the view about to render
    // meters with the camera's metering settings).
    float exposureFor(const UCameraSensorComponent& camera, double now,
                      const std::function<double(const sp::render::MeteringSettings&)>& meterView);
    // What a frame of the camera metered (EV100), read back after it rendered; not `exact` when its pixels
    // clipped too much to tell (sp::render::meterFinalColor): the next frame meters its view instead.
    void metered(double ev100, bool exact = true) {
        metered_ = ev100;
        exact_ = exact;
    }
    // The next frame is a cut.
    void reset();

  private:
    std::optional<double> adapted_; // EV100
    std::optional<double> metered_; // EV100 of the last metered frame since the cut
    bool exact_ = true;
    double lastTime_ = 0.0;
};

} // namespace sp::sensors
