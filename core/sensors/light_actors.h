#pragma once
// Light actors: an actor whose root component is a light.

#include "core/sensors/light_component.h"
#include "core/world/actor.h"

/// An actor with a directional light (the sun) as its root.
SPCLASS()
class ADirectionalLight : public AActor {
    SP_GENERATED_BODY()
  public:
    ADirectionalLight() {
        LightComponent = CreateDefaultSubobject<UDirectionalLightComponent>("LightComponent");
    }

    /// The light (also the root component).
    SPPROPERTY(ReadOnly, NotNull)
    UDirectionalLightComponent* LightComponent = nullptr;
};

/// An actor with a point light as its root.
SPCLASS()
class APointLight : public AActor {
    SP_GENERATED_BODY()
  public:
    APointLight() { LightComponent = CreateDefaultSubobject<UPointLightComponent>("LightComponent"); }

    /// The light (also the root component).
    SPPROPERTY(ReadOnly, NotNull)
    UPointLightComponent* LightComponent = nullptr;
};
