#include "core/sensors/sky_environment.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/imageio/exr.h"
#include "core/render/image_buffer.h"
#include "core/render/sky_model.h"
#include "core/sensors/light_component.h"
#include "core/sensors/linear_color.h"
#include "core/sensors/sky_atmosphere_component.h"
#include "core/sensors/sky_light_component.h"

namespace sp::sensors {
namespace {

// An analytic sky is smooth: this many texels show it without visible steps and make it in milliseconds.
constexpr int kSkyWidth = 512, kSkyHeight = 256;

// The RGB radiance of an EXR panorama (half or float R, G, B and perhaps A channels).
sp::render::RadianceImage readPanorama(const std::string& path) {
    const char* function = "USkyLightComponent.Cubemap";
    const sp::imageio::Image image = sp::imageio::readExr(path, function);
    const std::size_t channels = image.channelNames.size();
    SP_CHECK(channels >= 3 && image.channelNames[0] == "R" && image.channelNames[1] == "G" &&
                 image.channelNames[2] == "B",
             sp::InvalidArgument, function, ": '", path, "' has no R, G, B channels");
    SP_CHECK(image.type == sp::imageio::PixelType::Half || image.type == sp::imageio::PixelType::Float,
             sp::InvalidArgument, function, ": '", path, "' holds ", sp::imageio::toString(image.type),
             " pixels, not half or float radiance");
    sp::render::RadianceImage out{image.width, image.height, {}};
    const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
    out.texels.resize(count);
    for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c) {
            float value;
            if (image.type == sp::imageio::PixelType::Half) {
                std::uint16_t h;
                std::memcpy(&h, image.pixels.data() + (i * channels + std::size_t(c)) * 2, 2);
                value = sp::render::halfToFloat(h);
            } else {
                std::memcpy(&value, image.pixels.data() + (i * channels + std::size_t(c)) * 4, 4);
            }
            // Negative or non-finite texels (a photograph's noise, an infinity) carry no light.
            out.texels[i][c] = std::isfinite(value) ? std::max(value, 0.0f) : 0.0f;
        }
    return out;
}

} // namespace

std::string cubemapExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

sp::render::Environment SkyEnvironment::update(const USkyLightComponent* sky,
                                               const USkyAtmosphereComponent* atmosphere,
                                               const ULightComponent* sun, const Log& log) {
    sp::render::Environment environment;
    const Eigen::Vector3f scale =
        sky ? Eigen::Vector3f(rgb(sky->SkyColor) * sky->Intensity) : Eigen::Vector3f::Ones();
    const float angle = sky ? sky->SourceCubemapAngle : 0.0f;
    std::shared_ptr<const sp::render::EnvironmentMap> map;
    if (sky && sky->SourceType == ESkyLightSourceType::SLS_SpecifiedCubemap) {
        if (sky->Cubemap.empty())
            log("cubemap:",
                "USkyLightComponent: SourceType is SLS_SpecifiedCubemap but Cubemap is empty; the "
                "uniform sky lights the world");
        else
            map = panorama(sky->Cubemap, angle, log);
    } else if (atmosphere) {
        // Not turned: the sky is the sun's, where the sun is. Tinted by the sky light's colour but not scaled
        // by its Intensity, the uniform sky's radiance (0.03 by default), so that a default sky light does
        // not dim the sky its sun makes; the sun light's intensity sets the sky's brightness.
        environment.map = atmosphereSky(*atmosphere, sun, log);
        environment.mapScale = sky ? rgb(sky->SkyColor) : Eigen::Vector3f::Ones();
        return environment;
    }
    if (map) {
        environment.map = std::move(map);
        environment.mapScale = scale;
    } else if (sky) {
        environment.ambient = scale;
        environment.background = rgb(sky->BackgroundColor);
    }
    return environment;
}

std::shared_ptr<const sp::render::EnvironmentMap> SkyEnvironment::panorama(const std::string& file,
                                                                           float angle, const Log& log) {
    const std::string path = sp::findAsset(file);
    std::error_code error;
    const auto modified = std::filesystem::last_write_time(path, error);
    const std::string key = path + "|" + std::to_string(error ? 0 : modified.time_since_epoch().count()) +
                            "|" + std::to_string(angle);
    if (key == panoramaKey_)
        return panorama_;
    panoramaKey_ = key;
    panorama_.reset();
    // The worlds of a vectorised environment name the same file: one map (read, prefiltered, sampled) serves
    // them all while any holds it.
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<const sp::render::EnvironmentMap>> shared;
    std::lock_guard lock(mutex);
    std::erase_if(shared, [](const auto& entry) { return entry.second.expired(); });
    if (auto it = shared.find(key); it != shared.end()) {
        panorama_ = it->second.lock();
        return panorama_;
    }
    try {
        panorama_ = std::make_shared<const sp::render::EnvironmentMap>(
            cubemapExtension(path) == ".hdr" ? sp::render::readRadianceHdr(path, "USkyLightComponent.Cubemap")
                                             : readPanorama(path),
            angle, "USkyLightComponent.Cubemap");
        shared[key] = panorama_;
    } catch (const sp::Error& e) {
        log("cubemap:" + key, std::string("RenderSubsystem: the sky light's Cubemap '") + file +
                                  "' is not used (the uniform sky lights the world): " + e.what());
    }
    return panorama_;
}

std::shared_ptr<const sp::render::EnvironmentMap>
SkyEnvironment::atmosphereSky(const USkyAtmosphereComponent& atmosphere, const ULightComponent* sun,
                              const Log& log) {
    sp::render::SkyParameters parameters;
    parameters.turbidity = atmosphere.Turbidity;
    parameters.groundAlbedo = rgb(atmosphere.GroundAlbedo);
    if (sun) {
        parameters.sunDirection = sun->GetForwardVector().toEigen().cast<float>();
        parameters.sunIrradiance = rgb(sun->LightColor) * sun->Intensity;
    } else {
        log("atmosphere:sun",
            "RenderSubsystem: the sky atmosphere has no sun (no visible directional light in "
            "the world); its sky is black");
        parameters.sunIrradiance.setZero();
    }
    const std::vector<float> key = {parameters.sunDirection.x(),  parameters.sunDirection.y(),
                                    parameters.sunDirection.z(),  parameters.sunIrradiance.x(),
                                    parameters.sunIrradiance.y(), parameters.sunIrradiance.z(),
                                    parameters.turbidity,         parameters.groundAlbedo.x(),
                                    parameters.groundAlbedo.y(),  parameters.groundAlbedo.z()};
    if (sky_ && key == skyKey_)
        return sky_;
    skyKey_ = key;
    sky_ = std::make_shared<const sp::render::EnvironmentMap>(
        sp::render::PreethamSky(parameters).image(kSkyWidth, kSkyHeight), 0.0f, "USkyAtmosphereComponent");
    return sky_;
}

} // namespace sp::sensors
