#pragma once
// Spot lights: a point light (core/sensors/light_component.h) restricted to a cone around the component's
// forward (+X) axis, and the actor that holds one.

#include "core/sensors/light_component.h"
#include "core/world/actor.h"

/// A point light restricted to a cone around the component's forward axis.
SPCLASS()
class USpotLightComponent : public UPointLightComponent {
    SP_GENERATED_BODY()
  public:
    /// Half-angle in degrees inside which the light has full intensity.
    SPPROPERTY()
    float InnerConeAngle = 30.0f;

    /// Half-angle in degrees outside which the light is zero (>= InnerConeAngle, < 90).
    SPPROPERTY()
    float OuterConeAngle = 45.0f;
};

/// An actor with a spot light as its root.
SPCLASS()
class ASpotLight : public AActor {
    SP_GENERATED_BODY()
  public:
    ASpotLight() { LightComponent = CreateDefaultSubobject<USpotLightComponent>("LightComponent"); }

    /// The light (also the root component); its cone points along the actor's forward axis.
    SPPROPERTY(ReadOnly, NotNull)
    USpotLightComponent* LightComponent = nullptr;
};
