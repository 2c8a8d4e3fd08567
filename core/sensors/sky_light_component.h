#pragma once
// The sky light: a uniform sky that lights every surface (scaled by material AO) and colours the pixels
// that hit no geometry. A world without one gets the renderer's default (a dim grey sky, black
// background); with several, the first spawned is used.

#include "core/world/actor.h"

/// Uniform sky light: ambient radiance on every surface, and the colour of pixels that hit nothing.
SPCLASS()
class USkyLightComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Linear RGB radiance of the uniform sky, multiplied by Intensity.
    SPPROPERTY()
    FLinearColor SkyColor{1.0f, 1.0f, 1.0f, 1.0f};

    /// Multiplier of SkyColor.
    SPPROPERTY()
    float Intensity = 0.03f;

    /// Linear HDR colour of the pixels that hit no geometry.
    SPPROPERTY()
    FLinearColor BackgroundColor{0.0f, 0.0f, 0.0f, 1.0f};
};

/// An actor with the sky light as its root.
SPCLASS()
class ASkyLight : public AActor {
    SP_GENERATED_BODY()
  public:
    ASkyLight() { SkyLightComponent = CreateDefaultSubobject<USkyLightComponent>("SkyLightComponent"); }

    /// The sky light (also the root component).
    SPPROPERTY(ReadOnly, NotNull)
    USkyLightComponent* SkyLightComponent = nullptr;
};
