#include "core/sensors/rect_light_component.h"

#include <cmath>

#include "core/base/error.h"

void URectLightComponent::SetSourceWidth(float NewWidth) {
    sp::checkSetting(std::isfinite(NewWidth) && NewWidth >= 1e-6f, "URectLightComponent", "SourceWidth",
                     ">= 1e-6 m", NewWidth);
    SourceWidth = NewWidth;
}

void URectLightComponent::SetSourceHeight(float NewHeight) {
    sp::checkSetting(std::isfinite(NewHeight) && NewHeight >= 1e-6f, "URectLightComponent", "SourceHeight",
                     ">= 1e-6 m", NewHeight);
    SourceHeight = NewHeight;
}
