#pragma once
// The sky atmosphere: the daylight sky of the world's sun (its first directional light), from a published
// analytic model (Preetham, Shirley and Smits 1999; core/render/sky_model.h) for the sun's direction and the
// air's turbidity. It is the background of every camera and, through a sky light whose SourceType is
// SLS_CapturedScene (or alone, without a sky light), the light of the sky on every surface, in both
// renderers. Its brightness follows the sun light's Intensity (sky_model.h, "Units"). With several, the first
// spawned is used.

#include "core/world/actor.h"

/// An analytic clear sky for the world's sun.
SPCLASS()
class USkyAtmosphereComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Haze of the air (the model's turbidity): 2 very clear, 3 clear (the default), 6 hazy, 10 very hazy;
    /// in [1.7, 10], the model's range.
    SPPROPERTY(Setter = SetTurbidity, meta = (ClampMin = 1.7, ClampMax = 10))
    float Turbidity = 3.0f;

    /// Linear RGB albedo of the ground below the horizon, in [0, 1], lit by the sun and the sky.
    SPPROPERTY(Setter = SetGroundAlbedo)
    FLinearColor GroundAlbedo{0.4f, 0.4f, 0.4f, 1.0f};

    /// Sets Turbidity (in [1.7, 10]).
    SPFUNCTION()
    void SetTurbidity(float NewTurbidity);
    /// Sets GroundAlbedo (each of R, G, B in [0, 1]).
    SPFUNCTION()
    void SetGroundAlbedo(const FLinearColor& NewAlbedo);
};

/// An actor with the sky atmosphere as its root.
SPCLASS()
class ASkyAtmosphere : public AActor {
    SP_GENERATED_BODY()
  public:
    ASkyAtmosphere() {
        SkyAtmosphereComponent = CreateDefaultSubobject<USkyAtmosphereComponent>("SkyAtmosphereComponent");
    }

    /// The sky atmosphere (also the root component).
    SPPROPERTY(ReadOnly, NotNull)
    USkyAtmosphereComponent* SkyAtmosphereComponent = nullptr;
};
