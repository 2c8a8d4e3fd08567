#include "core/sensors/sky_light_component.h"

#include <cmath>
#include <filesystem>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/sensors/sky_environment.h"

void USkyLightComponent::SetIntensity(float NewIntensity) {
    sp::checkSetting(std::isfinite(NewIntensity) && NewIntensity >= 0.0f, "USkyLightComponent", "Intensity",
                     ">= 0", NewIntensity);
    Intensity = NewIntensity;
}

void USkyLightComponent::SetCubemap(const std::string& NewCubemap) {
    if (!NewCubemap.empty()) {
        const std::string extension = sp::sensors::cubemapExtension(NewCubemap);
        SP_CHECK(extension == ".exr" || extension == ".hdr", sp::InvalidArgument,
                 "USkyLightComponent.Cubemap must be an OpenEXR (.exr) or Radiance HDR (.hdr) file, got '",
                 NewCubemap, "'");
        std::error_code error;
        SP_CHECK(std::filesystem::is_regular_file(sp::findAsset(NewCubemap), error), sp::NotFound,
                 "USkyLightComponent.Cubemap: no file '", NewCubemap,
                 "' (searched the working directory and ", "the asset folders)");
    }
    Cubemap = NewCubemap;
}

void USkyLightComponent::SetSourceCubemapAngle(float NewAngle) {
    sp::checkSetting(std::isfinite(NewAngle), "USkyLightComponent", "SourceCubemapAngle", "finite", NewAngle);
    SourceCubemapAngle = NewAngle;
}
