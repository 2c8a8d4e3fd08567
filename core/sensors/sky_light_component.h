#pragma once
// The sky light: the light that comes from the sky rather than from a lamp or the sun, which lights every
// surface (scaled by material AO) and colours the pixels that hit no geometry. Its source is a uniform sky,
// the world's ASkyAtmosphere (an analytic sky for the sun's direction) or an HDR panorama (Cubemap); both
// renderers light a scene from the same source (core/render/README.md, "Sky and environment light"). A world
// without one gets the renderer's default (a dim grey sky, black background), or its atmosphere's sky; with
// several, the first spawned is used.

#include <string>

#include "core/world/actor.h"

/// Where a sky light's light comes from (UE's ESkyLightSourceType).
SPENUM()
enum class ESkyLightSourceType : uint8_t {
    /// The world's sky: its ASkyAtmosphere's when it has one, else the uniform SkyColor.
    SLS_CapturedScene = 0,
    /// The HDR panorama named by Cubemap.
    SLS_SpecifiedCubemap = 1,
};

/// Sky light: ambient radiance on every surface, and the colour of pixels that hit nothing.
SPCLASS()
class USkyLightComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Linear RGB radiance of the uniform sky, multiplied by Intensity; the tint of a captured sky or a
    /// Cubemap.
    SPPROPERTY()
    FLinearColor SkyColor{1.0f, 1.0f, 1.0f, 1.0f};

    /// Multiplier of SkyColor for the uniform sky, and of a Cubemap (1 shows it as it is; the default, 0.03,
    /// suits the uniform sky). A captured ASkyAtmosphere is not scaled: its sun sets its brightness. At least
    /// 0.
    SPPROPERTY(Setter = SetIntensity)
    float Intensity = 0.03f;

    /// Linear HDR colour of the pixels that hit no geometry under the uniform sky (a captured sky or a
    /// Cubemap is its own background).
    SPPROPERTY()
    FLinearColor BackgroundColor{0.0f, 0.0f, 0.0f, 1.0f};

    /// The light's source: the world's sky (default) or Cubemap.
    SPPROPERTY()
    ESkyLightSourceType SourceType = ESkyLightSourceType::SLS_CapturedScene;

    /// An equirectangular HDR panorama in linear RGB (an OpenEXR .exr or Radiance .hdr file, width twice its
    /// height, the zenith at the top, the image's centre looking along +X), used when SourceType is
    /// SLS_SpecifiedCubemap: a path,
    /// relative ones found as assets are ("assets/environments/..."). Setting a file that does not exist
    /// raises; one that cannot be read is logged and the uniform sky lights the world instead.
    SPPROPERTY(Setter = SetCubemap)
    std::string Cubemap;

    /// Turns the Cubemap about the up axis, in degrees; positive turns it to the left (counter-clockwise seen
    /// from above). An ASkyAtmosphere's sky is not turned: it follows its sun.
    SPPROPERTY(Setter = SetSourceCubemapAngle)
    float SourceCubemapAngle = 0.0f;

    /// Sets Intensity (>= 0, finite).
    SPFUNCTION()
    void SetIntensity(float NewIntensity);
    /// Sets Cubemap: "" or an existing .exr or .hdr file.
    SPFUNCTION()
    void SetCubemap(const std::string& NewCubemap);
    /// Sets SourceCubemapAngle (degrees, finite).
    SPFUNCTION()
    void SetSourceCubemapAngle(float NewAngle);
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
