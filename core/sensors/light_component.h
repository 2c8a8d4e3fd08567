#pragma once
// Light components: plain reflected data that the renderer reads (colour, intensity, range), beside the
// other lights of core/sensors (spot, rect, sky), whose render subsystem is what reads them. They have
// no behaviour of their own; a light's position and direction come from its scene component transform
// (a directional light shines along its forward, +X, axis).

#include "core/world/scene_component.h"

/// A scene component that emits light.
SPCLASS(Abstract)
class ULightComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Brightness: lux for directional lights, candela for point lights.
    SPPROPERTY()
    float Intensity = 1.0f;

    /// Colour of the emitted light (linear).
    SPPROPERTY()
    FLinearColor LightColor{1.0f, 1.0f, 1.0f, 1.0f};

    /// Whether this light casts shadows.
    SPPROPERTY()
    bool bCastShadows = true;
};

/// A light infinitely far away that shines along the component's forward (+X) axis, like the sun.
SPCLASS()
class UDirectionalLightComponent : public ULightComponent {
    SP_GENERATED_BODY()
  public:
    UDirectionalLightComponent() { Intensity = 3.0f; }
};

/// A light that shines equally in every direction from the component's location.
SPCLASS()
class UPointLightComponent : public ULightComponent {
    SP_GENERATED_BODY()
  public:
    UPointLightComponent() { Intensity = 50.0f; }

    /// Distance in metres beyond which the light has no effect.
    SPPROPERTY()
    float AttenuationRadius = 10.0f;
};
