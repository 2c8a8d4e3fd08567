#pragma once
// Rect lights: a light panel, a one-sided Lambertian rectangle facing the component's forward (+X) axis,
// SourceWidth along its right (+Y) axis and SourceHeight along its up (+Z) axis; and the actor that holds
// one. Like Unreal's, the light itself is not seen by the camera (give it an emissive mesh to show the
// panel). Both renderers light with the whole rectangle: soft light and wide highlights where a point light
// gives hard ones. The path tracer's shadows are soft; the rasteriser's come from a shadow map seen from the
// panel's centre, so they are hard.

#include "core/sensors/light_component.h"
#include "core/world/actor.h"

/// A rectangular area light facing the component's forward axis (UE's URectLightComponent, sizes in metres).
SPCLASS()
class URectLightComponent : public ULightComponent {
    SP_GENERATED_BODY()
  public:
    URectLightComponent() { Intensity = 50.0f; }

    /// Width in metres of the rectangle, along the component's right (+Y) axis (> 0).
    SPPROPERTY(Setter = SetSourceWidth)
    float SourceWidth = 0.64f;

    /// Height in metres of the rectangle, along the component's up (+Z) axis (> 0).
    SPPROPERTY(Setter = SetSourceHeight)
    float SourceHeight = 0.64f;

    /// Distance in metres beyond which the light has no effect (0: unbounded).
    SPPROPERTY()
    float AttenuationRadius = 10.0f;

    /// Sets SourceWidth (metres, finite, >= 1e-6).
    SPFUNCTION()
    void SetSourceWidth(float NewWidth);
    /// Sets SourceHeight (metres, finite, >= 1e-6).
    SPFUNCTION()
    void SetSourceHeight(float NewHeight);
};

/// An actor with a rect light as its root.
SPCLASS()
class ARectLight : public AActor {
    SP_GENERATED_BODY()
  public:
    ARectLight() { LightComponent = CreateDefaultSubobject<URectLightComponent>("LightComponent"); }

    /// The light (also the root component); it faces along the actor's forward axis.
    SPPROPERTY(ReadOnly, NotNull)
    URectLightComponent* LightComponent = nullptr;
};
