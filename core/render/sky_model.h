#pragma once
// The clear sky's radiance for a sun direction and the air's turbidity: Preetham, Shirley and Smits 1999,
// "A Practical Analytic Model for Daylight" (the Perez et al. 1993 luminance distribution, with the paper's
// fits of its coefficients and of the zenith's luminance and chromaticity to turbidity and sun angle).
//
// Units: the model gives luminance in cd/m^2. The engine's lights have no fixed unit (light.h), so the sky is
// scaled by the sun light's intensity over the sun's illuminance above the atmosphere, 128,000 lux: a sun
// light of intensity 128,000 (lux) gives a sky in cd/m^2, a sun of intensity pi a sky some ten times dimmer
// than the sun on a horizontal surface, as outdoors. Below the horizon is a ground of the given albedo lit
// by that sun and sky. The model covers a sun above the horizon; below it the sky fades to black over 6
// degrees (civil twilight, which the model does not describe).

#include <Eigen/Core>

#include "core/render/environment_map.h"

namespace sp::render {

struct SkyParameters {
    Eigen::Vector3f sunDirection{0.0f, 0.0f, -1.0f}; // world, the direction sunlight travels (as a Light's)
    Eigen::Vector3f sunIrradiance{3.14159265f, 3.14159265f,
                                  3.14159265f}; // the sun light's colour * intensity
    float turbidity = 3.0f;                     // 1.7 (very clear) to 10 (hazy), the model's range
    Eigen::Vector3f groundAlbedo{0.4f, 0.4f, 0.4f};

    // Throws sp::InvalidArgument naming `function` and the bad value.
    void validate(const char* function) const;
};

class PreethamSky {
  public:
    static constexpr float kSolarIlluminance = 128000.0f; // lux, above the atmosphere
    static constexpr float kMinTurbidity = 1.7f, kMaxTurbidity = 10.0f;

    explicit PreethamSky(const SkyParameters& parameters);

    // The model's zenith luminance (cd/m^2) and chromaticity (CIE x, y) for the sun's zenith angle.
    float zenithLuminance() const { return zenith_[0]; }
    Eigen::Vector2f zenithChromaticity() const { return {zenith_[1], zenith_[2]}; }
    // The model's CIE xyY (Y in cd/m^2) of the sky in unit direction `view` above the horizon.
    Eigen::Vector3f xyY(const Eigen::Vector3f& view) const;
    // The radiance (linear sRGB, the engine's units) arriving from unit direction `view`: sky above the
    // horizon, lit ground below.
    Eigen::Vector3f radiance(const Eigen::Vector3f& view) const;
    // The sky as an equirectangular map of width x height (EnvironmentMap's layout).
    RadianceImage image(int width, int height) const;

  private:
    float perez(int channel, float cosTheta, float gamma) const;

    Eigen::Vector3f toSun_ = Eigen::Vector3f::UnitZ(); // towards the sun, clamped to the horizon
    float thetaSun_ = 0.0f;
    float scale_ = 0.0f;                 // engine units per cd/m^2 (0 for a sun far below the horizon)
    float zenith_[3] = {0, 0, 0};        // Y, x, y
    float coefficients_[3][5] = {};      // Perez A..E for Y, x, y
    float normalisation_[3] = {1, 1, 1}; // 1 / F(0, theta_sun) for Y, x, y
    Eigen::Vector3f ground_ = Eigen::Vector3f::Zero();
};

// The linear sRGB (D65) colour of CIE xyY.
Eigen::Vector3f xyYToLinearSrgb(const Eigen::Vector3f& xyY);

} // namespace sp::render
