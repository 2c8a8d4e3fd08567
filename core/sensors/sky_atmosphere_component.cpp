#include "core/sensors/sky_atmosphere_component.h"

#include <cmath>
#include <sstream>

#include "core/base/error.h"
#include "core/render/sky_model.h"

void USkyAtmosphereComponent::SetTurbidity(float NewTurbidity) {
    using Sky = sp::render::PreethamSky;
    std::ostringstream range;
    range << "in [" << Sky::kMinTurbidity << ", " << Sky::kMaxTurbidity << "]";
    sp::checkSetting(std::isfinite(NewTurbidity) && NewTurbidity >= Sky::kMinTurbidity &&
                         NewTurbidity <= Sky::kMaxTurbidity,
                     "USkyAtmosphereComponent", "Turbidity", range.str(), NewTurbidity);
    Turbidity = NewTurbidity;
}

void USkyAtmosphereComponent::SetGroundAlbedo(const FLinearColor& NewAlbedo) {
    const float channels[3] = {NewAlbedo.R, NewAlbedo.G, NewAlbedo.B};
    for (float c : channels)
        SP_CHECK(std::isfinite(c) && c >= 0.0f && c <= 1.0f, sp::InvalidArgument,
                 "USkyAtmosphereComponent.GroundAlbedo must be in [0, 1] per channel, got (", NewAlbedo.R,
                 ", ", NewAlbedo.G, ", ", NewAlbedo.B, ")");
    GroundAlbedo = NewAlbedo;
}
