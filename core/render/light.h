#pragma once
// Analytic lights. Units are "physical-ish" linear radiometry: a directional light's intensity is the
// irradiance it delivers at normal incidence (W/m^2, or lux with photometric exposure); a point or spot
// light's intensity is its radiant intensity (W/sr, or candela), giving irradiance intensity / d^2.
// A white Lambertian surface facing a directional light of intensity pi therefore has radiance 1.
// A rect light is a one-sided Lambertian rectangle facing `direction`: its intensity is the radiant
// intensity along that normal (falling off as the cosine away from it), so its radiance is
// intensity / (width * height), and far away it lights like a point light of that intensity.

#include <Eigen/Core>

namespace sp::render {

enum class LightType { Directional, Point, Spot, Rect };

struct Light {
    LightType type = LightType::Directional;
    Eigen::Vector3f color{1.0f, 1.0f, 1.0f};            // linear RGB tint
    float intensity = 3.14159265f;                      // see the header comment for units
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); // world, point and spot
    Eigen::Vector3d direction{0.0, 0.0, -1.0};          // world, direction light travels (dir, spot, rect)
    float range = 0.0f;         // metres; 0 = unbounded; otherwise a smooth window to 0 at range
    float innerConeDeg = 30.0f; // spot: full intensity inside this half-angle
    float outerConeDeg = 45.0f; // spot: zero outside this half-angle
    // Rect: the rectangle spans `width` metres along `right` and `height` along `up` (unit vectors
    // perpendicular to `direction`), centred on `position`.
    Eigen::Vector3d right{0.0, 1.0, 0.0};
    Eigen::Vector3d up{0.0, 0.0, 1.0};
    float width = 0.5f;
    float height = 0.5f;
    // Shadow maps: directional and spot lights. The path tracer shadows every light.
    bool castShadows = true;

    // A point, spot or rect light of finite range: it adds exactly nothing past `range`.
    bool ranged() const { return type != LightType::Directional && range > 0.0f; }
    // A rect light's radiance (W/m^2/sr per unit of colour): its intensity spread over its area.
    float rectRadiance() const { return intensity / (width * height); }
    // Throws sp::InvalidArgument naming the bad field.
    void validate(const char* function) const;
};

} // namespace sp::render
