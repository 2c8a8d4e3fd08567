#pragma once
// SkyEnvironment: the render environment (sp::render::Environment) of a world's sky light, sky atmosphere and
// sun, keeping the environment maps it made (an HDR panorama read from its file, an analytic sky) while what
// they were made from stays the same, so that a still sky costs nothing per frame and a moving sun one new
// sky (about 20 ms on two cores: the sky, its spherical harmonics, prefiltered chain and upload).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/render/scene.h"

class ULightComponent;
class USkyAtmosphereComponent;
class USkyLightComponent;

namespace sp::sensors {

// A Cubemap path's extension in lower case (".exr", ".hdr", ...): the format the setter admits and the loader
// reads.
std::string cubemapExtension(const std::string& path);

class SkyEnvironment {
  public:
    // Logs a message once per key (RenderScene::logOnce).
    using Log = std::function<void(const std::string& key, const std::string& message)>;

    // The environment for the first sky light and atmosphere in play (either may be null) and the sun (the
    // first visible directional light, or null). A panorama that cannot be read is logged, and the uniform
    // sky lights the world instead.
    sp::render::Environment update(const USkyLightComponent* sky, const USkyAtmosphereComponent* atmosphere,
                                   const ULightComponent* sun, const Log& log);

  private:
    std::shared_ptr<const sp::render::EnvironmentMap> panorama(const std::string& file, float angle,
                                                               const Log& log);
    std::shared_ptr<const sp::render::EnvironmentMap>
    atmosphereSky(const USkyAtmosphereComponent& atmosphere, const ULightComponent* sun, const Log& log);

    std::shared_ptr<const sp::render::EnvironmentMap> panorama_, sky_;
    std::string panoramaKey_;
    std::vector<float> skyKey_;
};

} // namespace sp::sensors
