#pragma once
// UCameraSensorComponent: a scene component that renders ground-truth images of its world. It holds
// only settings; the world's RenderSubsystem owns the GL context, the render scene and one render
// target per camera, renders every camera at the end of each frame (after actors and physics), and
// hands the pixels to read_pixels().
//
// Frames and latency: the frame rendered at the end of world frame k is what read_pixels() returns
// inside `with instance.end_frame():` of frame k when Latency is 0. With Latency N (1 or 2: double or
// triple buffering) it returns the frame rendered N frames earlier; for the first N frames after the
// camera starts (or changes Latency) there is none yet and read_pixels() returns an empty dict
// (priming). GetPixelsFrame() tells which world frame the last read_pixels() result shows.
//
// read_pixels() returns the due frame whenever it is called: nothing renders between end_frame and the
// next begin_frame, so inside `with instance.begin_frame():` of frame k + 1 it returns what end_frame of
// frame k did (an agent's last observation), and before the camera's first frame an empty dict.

#include <cstdint>
#include <string>
#include <vector>

#include "core/reflect/sp_array.h"
#include "core/render/lens.h"
#include "core/world/primitive_component.h"

/// A ground-truth image a camera can render; read_pixels() returns it under its snake_case name.
SPENUM()
enum class ECameraModality : uint8_t {
    /// "final_color": tone-mapped sRGB, uint8 (H, W, 4).
    FinalColor = 0,
    /// "hdr_color": linear HDR radiance before exposure and tone mapping, float16 (H, W, 4).
    HdrColor = 1,
    /// "depth": metres along the optical axis, 0 for background, float32 (H, W).
    Depth = 2,
    /// "position": world-space position in metres, 0 for background, float32 (H, W, 3).
    Position = 3,
    /// "normal": world-space unit normal facing the camera, 0 for background, float32 (H, W, 3).
    Normal = 4,
    /// "object_ids": one id per (component, material slot), 0 for background, uint32 (H, W).
    ObjectIds = 5,
    /// "material_ids": the id of the material, 0 for background, uint32 (H, W).
    MaterialIds = 6,
    /// "base_color": linear base colour, float16 (H, W, 3).
    BaseColor = 7,
    /// "roughness": perceptual roughness, float16 (H, W).
    Roughness = 8,
    /// "metallic": metalness, float16 (H, W).
    Metallic = 9,
    /// "material_ao": material ambient occlusion, float16 (H, W).
    MaterialAo = 10,
    /// "diffuse_illumination": radiance of a white Lambertian surface at the pixel, float16 (H, W, 3).
    DiffuseIllumination = 11,
    /// "diffuse_only": base_color * (1 - metallic) * diffuse_illumination, float16 (H, W, 3).
    DiffuseOnly = 12,
    /// "specular_residual": hdr_color.rgb - diffuse_only (specular, emission, sky), float16 (H, W, 3).
    SpecularResidual = 13,
};

/// The tone curve that maps exposed HDR radiance to final_color.
SPENUM()
enum class ECameraToneCurve : uint8_t {
    /// The ACES filmic approximation.
    Aces = 0,
    /// Reinhard's x / (1 + x).
    Reinhard = 1,
    /// Clamped linear.
    Linear = 2,
};

/// Which renderer makes a camera's final_color and hdr_color.
SPENUM()
enum class ECameraRenderer : uint8_t {
    /// The real-time rasteriser (OpenGL): every modality, every frame.
    Raster = 0,
    /// The reference path tracer (Embree, on the CPU): global illumination, accumulated over frames while
    /// nothing in the scene changes. final_color, hdr_color and the intrinsic images (diffuse_illumination,
    /// diffuse_only, specular_residual, indirect light included) are path traced; the geometric and
    /// material modalities still come from the rasteriser.
    PathTraced = 1,
};

/// How a camera sets the exposure of final_color (Unreal's names and values). The automatic methods meter the
/// view's luminance and show it as middle grey: Exposure = 0.18 * 2^AutoExposureBias / L for a metered
/// luminance L (cd/m^2, read as EV100 = log2(L * 100 / 12.5) and clamped to [AutoExposureMinBrightness,
/// AutoExposureMaxBrightness]), adapting to a change at AutoExposureSpeedUp / AutoExposureSpeedDown. A
/// camera's first frame, and the first after ResetAutoExposure(), is exposed for what it shows.
SPENUM()
enum class EAutoExposureMethod : uint8_t {
    /// The mean log luminance of the pixels between the AutoExposureLowPercent and AutoExposureHighPercent
    /// percentiles: the darkest and brightest parts (a lamp, the sun, a black sky) leave it unmoved.
    AEM_Histogram = 0,
    /// The mean log luminance of every pixel.
    AEM_Basic = 1,
    /// Exposure exactly as set (the default): the same scene always gives the same pixels, so a dataset's
    /// views stay comparable.
    AEM_Manual = 2,
};

/// How a rasterised camera's final_color is anti-aliased (Unreal's names and values). The exact modalities
/// (depth, position, normal, ids, material inputs) are never filtered: one exact value per pixel, at its
/// centre.
SPENUM()
enum class EAntiAliasingMethod : uint8_t {
    /// None: each pixel shows the surface at its centre.
    AAM_None = 0,
    /// Fast approximate anti-aliasing (Lottes 2009): edges found by their luma and blended along their
    /// staircase, in linear light, as the image is read back (core/render/fxaa.h).
    AAM_FXAA = 1,
    /// Multisampling: final_color, hdr_color and the intrinsic images are drawn with MSAASampleCount
    /// coverage samples a pixel and averaged (final_color in linear light). The exact modalities are drawn
    /// in a pass of their own. Best at silhouettes; on a software rasteriser a frame costs about three
    /// times as much (llvmpipe: Table 3's 1080p view of 64 objects, 25 -> 78-88 ms), on a GPU little.
    AAM_MSAA = 3,
};

/// How much indirect light a rasterised camera shows: the world's irradiance probes (a grid over the scene,
/// lit by the path tracer's rays, blended per pixel on a GPU and per vertex on a software rasteriser;
/// core/render/README.md, "Global illumination"). The names follow Unreal's scalability levels
/// (sg.GlobalIlluminationQuality). A world lights its probes at the highest quality any of its rasterised
/// cameras asks for.
SPENUM()
enum class EGlobalIlluminationQuality : uint8_t {
    /// No indirect light: the sky's term alone (the sky light's uniform radiance, or the spherical harmonics
    /// of its map or of the sky atmosphere), with no occlusion by the scene.
    Off = 0,
    /// Probes 1 m apart (at most 16 along an axis), 128 rays each, 2 bounces.
    Low = 1,
    /// Probes 0.5 m apart (at most 24 along an axis), 256 rays each, 3 bounces.
    Medium = 2,
    /// Probes 0.35 m apart (at most 32 along an axis), 512 rays each, 4 bounces.
    High = 3,
    /// Probes 0.25 m apart (at most 48 along an axis), 1024 rays each, 4 bounces.
    Epic = 4,
};

/// Brown–Conrady lens distortion in OpenCV's convention (radial K1, K2, K3; tangential P1, P2): all zero is a
/// pinhole. See UCameraSensorComponent.LensDistortion.
SPSTRUCT()
struct FLensDistortion {
    SP_GENERATED_BODY()

    /// Radial coefficient of r^2 (negative: barrel, positive: pincushion).
    SPPROPERTY()
    double K1 = 0.0;
    /// Radial coefficient of r^4.
    SPPROPERTY()
    double K2 = 0.0;
    /// Radial coefficient of r^6.
    SPPROPERTY()
    double K3 = 0.0;
    /// First tangential coefficient.
    SPPROPERTY()
    double P1 = 0.0;
    /// Second tangential coefficient.
    SPPROPERTY()
    double P2 = 0.0;

    friend bool operator==(const FLensDistortion&, const FLensDistortion&) = default;
};

/// The images of one frame, keyed by modality name; only the modalities the camera renders (its Modalities)
/// are present.
SPSTRUCT(TypedDict, Partial)
struct FCameraPixels {
    SP_GENERATED_BODY()

    /// Tone-mapped sRGB, uint8 (H, W, 4).
    SPPROPERTY()
    sp::reflect::SpArray<uint8_t> final_color{"final_color"};
    /// Linear HDR radiance, float16 (H, W, 4).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> hdr_color{"hdr_color"};
    /// Metres along the optical axis, 0 for background, float32 (H, W).
    SPPROPERTY()
    sp::reflect::SpArray<float> depth{"depth"};
    /// World-space position in metres, float32 (H, W, 3).
    SPPROPERTY()
    sp::reflect::SpArray<float> position{"position"};
    /// World-space unit normal, float32 (H, W, 3).
    SPPROPERTY()
    sp::reflect::SpArray<float> normal{"normal"};
    /// Object ids (component, material slot), 0 for background, uint32 (H, W).
    SPPROPERTY()
    sp::reflect::SpArray<uint32_t> object_ids{"object_ids"};
    /// Material ids, 0 for background, uint32 (H, W).
    SPPROPERTY()
    sp::reflect::SpArray<uint32_t> material_ids{"material_ids"};
    /// Linear base colour, float16 (H, W, 3).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> base_color{"base_color"};
    /// Roughness, float16 (H, W).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> roughness{"roughness"};
    /// Metalness, float16 (H, W).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> metallic{"metallic"};
    /// Material ambient occlusion, float16 (H, W).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> material_ao{"material_ao"};
    /// Radiance of a white Lambertian surface, float16 (H, W, 3).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> diffuse_illumination{"diffuse_illumination"};
    /// base_color * (1 - metallic) * diffuse_illumination, float16 (H, W, 3).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> diffuse_only{"diffuse_only"};
    /// hdr_color.rgb - diffuse_only, float16 (H, W, 3).
    SPPROPERTY()
    sp::reflect::SpArray<sp::reflect::Half> specular_residual{"specular_residual"};
};

/// Which EGL device renders this world, and what OpenGL reports about itself.
SPSTRUCT()
struct FRenderDeviceInfo {
    SP_GENERATED_BODY()

    /// "device" (an EGL device, e.g. a GPU) or "surfaceless" (Mesa's software platform).
    SPPROPERTY()
    std::string Kind;
    /// Index in the EGL device list, -1 for surfaceless.
    SPPROPERTY()
    int32_t DeviceIndex = -1;
    /// Number of EGL devices listed.
    SPPROPERTY()
    int32_t DeviceCount = 0;
    /// GL_VENDOR.
    SPPROPERTY()
    std::string Vendor;
    /// GL_RENDERER.
    SPPROPERTY()
    std::string Renderer;
    /// GL_VERSION.
    SPPROPERTY()
    std::string Version;
};

/// How often each render pass ran in this world since its renderer started (all cameras together), and
/// what the passes cost (see core/render/README.md, "Passes and timings").
SPSTRUCT()
struct FRenderStats {
    SP_GENERATED_BODY()

    /// Frames rendered (one per camera per world frame).
    SPPROPERTY()
    int64_t Frames = 0;
    /// Shadow maps rendered.
    SPPROPERTY()
    int64_t ShadowPasses = 0;
    /// Frames that reused the shadow maps unchanged (nothing that casts or lights moved).
    SPPROPERTY()
    int64_t ShadowReuses = 0;
    /// Surface passes (geometry rasterisation; shading too when colour is asked for).
    SPPROPERTY()
    int64_t SurfacePasses = 0;
    /// Attribute passes: a second rasterisation writing the targets past the surface pass's 8 (all 14
    /// modalities need one), at the fragments the surface pass kept.
    SPPROPERTY()
    int64_t AttributePasses = 0;
    /// Frames that shaded.
    SPPROPERTY()
    int64_t LightingPasses = 0;
    /// Frames that tone-mapped (fused into the pass that shaded).
    SPPROPERTY()
    int64_t TonemapPasses = 0;
    /// Images read back (one per modality per frame).
    SPPROPERTY()
    int64_t Readbacks = 0;
    /// Instances drawn by surface passes.
    SPPROPERTY()
    int64_t DrawnInstances = 0;
    /// Instances outside a camera's view, skipped.
    SPPROPERTY()
    int64_t CulledInstances = 0;
    /// Instances shaded without shadow-map lookups, since no shadow can reach them (a software
    /// rasteriser only: there the lookups are a fifth of a shaded pixel; images are the same either way).
    SPPROPERTY()
    int64_t UnshadowedInstances = 0;
    /// Instances shaded in scissored parts, with shadow-map lookups only where a shadow can fall (a floor
    /// under a few objects, on a software rasteriser).
    SPPROPERTY()
    int64_t SplitInstances = 0;
    /// Instances whose normals are turned to the camera by the rasteriser's facing rather than by screen
    /// derivatives: those whose mesh normals lean to their triangles' winding side under the instance's
    /// scale (the built-in shapes, most imported meshes; images are the same either way).
    SPPROPERTY()
    int64_t WindingFacedInstances = 0;
    /// Lights whose range reaches a view past the 16 a view shades: the farthest are left out (lights whose
    /// range misses the view are left out always, and not counted: they light nothing it sees).
    SPPROPERTY()
    int64_t LightsLeftOut = 0;
    /// Draw calls of surface passes: one per batch of visible instances sharing a mesh, material
    /// textures and program (instanced), so many copies of one object cost one call.
    SPPROPERTY()
    int64_t DrawCalls = 0;
    /// Meshes this world uploaded to the GPU. A built-in shape or mesh file that another world of the
    /// engine uploaded first is drawn from that upload and not counted again.
    SPPROPERTY()
    int64_t MeshUploads = 0;
    /// Textures this world uploaded to the GPU, counted as meshes are.
    SPPROPERTY()
    int64_t TextureUploads = 0;
    /// Milliseconds in shadow passes, by GL timer queries (the device's own clock).
    SPPROPERTY()
    double ShadowMs = 0.0;
    /// Milliseconds in surface passes, by GL timer queries.
    SPPROPERTY()
    double SurfaceMs = 0.0;
    /// Milliseconds in attribute passes, by GL timer queries.
    SPPROPERTY()
    double AttributeMs = 0.0;
    /// Milliseconds the CPU spent reading images back (waiting for the frame included).
    SPPROPERTY()
    double ReadbackMs = 0.0;
};

/// A camera that renders the modalities in Modalities at the end of every frame.
SPCLASS()
class UCameraSensorComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Image width in pixels.
    SPPROPERTY(Setter = SetWidth, meta = (ClampMin = 1, ClampMax = 16384))
    int32_t Width = 640;

    /// Image height in pixels.
    SPPROPERTY(Setter = SetHeight, meta = (ClampMin = 1, ClampMax = 16384))
    int32_t Height = 480;

    /// Horizontal field of view in degrees, in (0, 180); square pixels.
    SPPROPERTY(Setter = SetFOV)
    double FOV = 90.0;

    /// Near clipping distance in metres (> 0).
    SPPROPERTY(Setter = SetNearClip)
    double NearClip = 0.05;

    /// Far clipping distance in metres (> NearClip).
    SPPROPERTY(Setter = SetFarClip)
    double FarClip = 1000.0;

    /// Linear multiplier of HDR radiance before the tone curve (SetExposureValue and SetPhysicalExposure
    /// set it from photographic settings).
    SPPROPERTY(Setter = SetExposure)
    float Exposure = 1.0f;

    /// Whether final_color's exposure is Exposure as set (AEM_Manual, the default) or metered from the view
    /// (EAutoExposureMethod). GetAppliedExposure() tells the exposure a frame was shown at.
    SPPROPERTY()
    EAutoExposureMethod AutoExposureMethod = EAutoExposureMethod::AEM_Manual;

    /// Automatic exposure: f-stops to brighten (> 0) or darken (< 0) the metered exposure, in [-15, 15].
    SPPROPERTY(Setter = SetAutoExposureBias, meta = (ClampMin = -15, ClampMax = 15))
    float AutoExposureBias = 0.0f;

    /// Automatic exposure: the darkest scene, as EV100, the camera adapts to (darker ones show darker), in
    /// [-20, 40]; it must not exceed AutoExposureMaxBrightness when the camera renders.
    SPPROPERTY(Setter = SetAutoExposureMinBrightness, meta = (ClampMin = -20, ClampMax = 40))
    float AutoExposureMinBrightness = -10.0f;

    /// Automatic exposure: the brightest scene, as EV100, the camera adapts to, in [-20, 40].
    SPPROPERTY(Setter = SetAutoExposureMaxBrightness, meta = (ClampMin = -20, ClampMax = 40))
    float AutoExposureMaxBrightness = 20.0f;

    /// Automatic exposure: how fast the camera adapts to a scene turned brighter, in f-stops per second of
    /// world time (half the way in 1 / speed seconds), in (0, 100].
    SPPROPERTY(Setter = SetAutoExposureSpeedUp)
    float AutoExposureSpeedUp = 3.0f;

    /// Automatic exposure: how fast the camera adapts to a scene turned darker, in f-stops per second, in
    /// (0, 100].
    SPPROPERTY(Setter = SetAutoExposureSpeedDown)
    float AutoExposureSpeedDown = 1.0f;

    /// AEM_Histogram: the darkest percent of the pixels left out of the metering, in [0, 100) and below
    /// AutoExposureHighPercent when the camera renders.
    SPPROPERTY(Setter = SetAutoExposureLowPercent)
    float AutoExposureLowPercent = 10.0f;

    /// AEM_Histogram: the percentile above which the brightest pixels are left out, in (0, 100].
    SPPROPERTY(Setter = SetAutoExposureHighPercent)
    float AutoExposureHighPercent = 90.0f;

    /// The colour temperature in kelvin the camera is balanced for, in [2000, 25000]: light of this
    /// temperature renders neutral in final_color (hdr_color is unchanged). 6500 (daylight) leaves colours as
    /// they are; 3200 suits tungsten light (the image turns bluer), 10000 shade (warmer).
    SPPROPERTY(Setter = SetWhiteBalanceTemperature, meta = (ClampMin = 2000, ClampMax = 25000))
    double WhiteBalanceTemperature = 6500.0;

    /// Sensor width in millimetres (> 0), relating FOV to a lens's focal length: 36 is full frame.
    SPPROPERTY(Setter = SetSensorWidth)
    double SensorWidth = 36.0;

    /// Lens distortion applied to every modality (OpenCV's model with GetIntrinsicMatrix()'s K; see
    /// GetDistortionCoefficients): each pixel shows what the distorted ray through it sees, taken from a
    /// pinhole render wide enough to hold every ray, nearest pixel, so that all modalities stay consistent.
    /// Pixels past where the model folds over (strong barrel distortion far from the axis) show no ray and
    /// are zero in every modality. The remap is rebuilt when the lens, the size or the FOV changes.
    SPPROPERTY(Setter = SetLensDistortion)
    FLensDistortion LensDistortion;

    /// The principal point's offset from the image centre in pixels (X right, Y down): an off-centre lens, as
    /// a real camera's calibration gives it (cx, cy of GetIntrinsicMatrix() move by it).
    SPPROPERTY(Setter = SetPrincipalPointOffset)
    FVector2D PrincipalPointOffset;

    /// Depth of field of the path tracer: the lens's f-number (its focal length, GetFocalLength() on
    /// SensorWidth, over the aperture's diameter); 0 (the default) is a pinhole, everything sharp. The raster
    /// renderer, and the geometric modalities, are always sharp.
    SPPROPERTY(Setter = SetApertureFNumber)
    double ApertureFNumber = 0.0;

    /// The distance in metres, along the optical axis, that the path tracer's lens is focused at (> 0).
    SPPROPERTY(Setter = SetFocusDistance)
    double FocusDistance = 10.0;

    /// Natural vignetting of final_color, in [0, 1]: each pixel's exposure falls off as mix(1, cos^4 theta,
    /// VignetteIntensity), theta the angle of its ray to the optical axis (the cos^4 law of a lens); 0 (the
    /// default) is none. hdr_color, the scene's radiance, is not vignetted.
    SPPROPERTY(Setter = SetVignetteIntensity, meta = (ClampMin = 0, ClampMax = 1))
    float VignetteIntensity = 0.0f;

    /// The tone curve of final_color.
    SPPROPERTY()
    ECameraToneCurve ToneCurve = ECameraToneCurve::Aces;

    /// Whether shadow-casting lights render shadow maps for this camera.
    SPPROPERTY()
    bool bShadows = true;

    /// Shadow map size in texels, in [16, 8192], or 0 (the default) to size it to the world's cameras: the
    /// power of two at or above the longest side of its shadowed cameras, within [256, 4096]. The views of
    /// a frame share one map, and a small camera's map is small (texels cost a software rasteriser).
    SPPROPERTY(Setter = SetShadowResolution)
    int32_t ShadowResolution = 0;

    /// The modalities rendered each frame; only the passes they need run.
    SPPROPERTY()
    std::vector<ECameraModality> Modalities{ECameraModality::FinalColor};

    /// Frames between rendering and reading: 0 (same frame), 1 or 2 (double or triple buffered).
    SPPROPERTY(Setter = SetLatency)
    int32_t Latency = 0;

    /// The renderer of final_color, hdr_color and the intrinsic images (geometric and material modalities
    /// are always rasterised).
    SPPROPERTY()
    ECameraRenderer Renderer = ECameraRenderer::Raster;

    /// The rasteriser's indirect light (global illumination). A world's probes are lit in full on the first
    /// frame a camera asks for them; when the scene changes, the probes least recently lit are lit again, a
    /// budget per frame, so that a change reaches every probe within a bounded number of frames
    /// (core/render/README.md). Medium by default, as Unreal's cameras have global illumination on: about
    /// 1.6 ms more per 1080p frame of Table 3 on llvmpipe (BENCHMARKS.md); Off gives the sky light's uniform
    /// term alone.
    SPPROPERTY()
    EGlobalIlluminationQuality GlobalIlluminationQuality = EGlobalIlluminationQuality::Medium;

    /// Whether final_color has an alpha channel: (H, W, 4) RGBA with alpha 255 (the default), or false for
    /// (H, W, 3) RGB, the shape a model takes as it is (read_pixels() and read_pixels_stacked(), both
    /// transports; the alpha is dropped as the frame is read, one copy).
    SPPROPERTY()
    bool bFinalColorAlpha = true;

    /// Anti-aliasing of the rasterised final_color; FXAA by default. The path tracer's pixels average rays
    /// spread over the pixel, so its images need none and take none.
    SPPROPERTY()
    EAntiAliasingMethod AntiAliasingMethod = EAntiAliasingMethod::AAM_FXAA;

    /// Coverage samples a pixel with AAM_MSAA: 2, 4 or 8 (Unreal's r.MSAACount); a device offering fewer
    /// (llvmpipe: 4) draws its most.
    SPPROPERTY(Setter = SetMSAASampleCount)
    int32_t MSAASampleCount = 4;

    /// Spatial samples a pixel of the rasterised colour (Unreal's Movie Render Queue anti-aliasing setting):
    /// 1 (none), 2, 4, 8 or 16. final_color, hdr_color and the intrinsic images are drawn that many times,
    /// each time with every pixel sampling another point of its square, and averaged (final_color in linear
    /// light): supersampling, which filters shading, highlights, shadow edges and texture detail as well as
    /// silhouettes. Above 1 it stands in for AAM_MSAA's coverage samples (multisampling each moved pass would
    /// blur the pixel past its square); AAM_FXAA still filters the averaged image. The exact modalities stay
    /// one value a pixel, at its centre. A frame costs about that many times as much to shade
    /// (BENCHMARKS.md); the path tracer takes none (its SamplesPerPixel are spread over the pixel).
    SPPROPERTY(Setter = SetSpatialSampleCount)
    int32_t SpatialSampleCount = 1;

    /// Anisotropic filtering of the material textures a rasterised view reads (Unreal's r.MaxAnisotropy): up
    /// to this many texture samples along a pixel's footprint where a surface is seen at a grazing angle (a
    /// floor or a wall far along the view), where trilinear filtering blurs its texture. 1 filters
    /// trilinearly; 2 to 16 anisotropically; 0 (the default) takes the renderer's default: 8 samples in a
    /// GPU's sampler, where it is all but free, and on a software rasteriser 4 reads in the shader (base
    /// colour and roughness / metallic; a textured 1080p frame's surface pass costs llvmpipe 1.35 times as
    /// much with them, BENCHMARKS.md). The default scene against the path tracer: SSIM about 0.02 higher at
    /// every GlobalIlluminationQuality. The exact modalities are not filtered.
    SPPROPERTY(Setter = SetMaxAnisotropy, meta = (ClampMin = 0, ClampMax = 16))
    int32_t MaxAnisotropy = 0;

    /// Added to the mip level the material textures of a rasterised view are read at (Unreal's
    /// r.MipMapLODBias), in levels, [-2, 2]: below 0 sharper, above 0 softer; 0 by default. Trilinear
    /// filtering blurs a texture over about two pixels where the path tracer and a supersampled view show
    /// the mean over each pixel's footprint: -1 comes closer on natural textures (the default scene against
    /// the path tracer: SSIM about 0.02 higher; against a 17 x 17 supersampled view, closer with every
    /// anti-aliasing setting), but aliases more on high-contrast
    /// patterns a few pixels across (a checkerboard's squares), hence 0 unless the scene's textures are
    /// known (BENCHMARKS.md). With SpatialSampleCount N the samples read log2 sqrt(N) levels finer than
    /// this. Depth and ids are not filtered.
    SPPROPERTY(Setter = SetMipMapLODBias, meta = (ClampMin = -2, ClampMax = 2))
    float MipMapLODBias = 0.0f;

    /// Ambient occlusion of the rasterised indirect and sky light (Unreal's AmbientOcclusionIntensity):
    /// how much of the occlusion found in the view's depth is applied, in [0, 1]; 0 (the default) turns it
    /// off. Ground-truth ambient occlusion (GTAO, Jimenez et al. 2016) darkens what the irradiance probes are
    /// too coarse for: corners, the floor under furniture and at an object's foot (core/render/README.md,
    /// "Ambient occlusion"); the lights' own light keeps its shadow maps, and the path tracer finds occlusion
    /// by itself. Off by default because a software rasteriser pays for it: a 640 x 480 view about 6 ms more
    /// a frame, a 1080p one about 35 ms (llvmpipe, BENCHMARKS.md); on a GPU it costs little, and Unreal's
    /// 0.5 is a good value.
    SPPROPERTY(Setter = SetAmbientOcclusionIntensity, meta = (ClampMin = 0, ClampMax = 1))
    float AmbientOcclusionIntensity = 0.0f;

    /// How far from a point, in metres, the ambient occlusion looks for the surfaces that hide it (Unreal's
    /// AmbientOcclusionRadius, in centimetres there), in (0, 100].
    SPPROPERTY(Setter = SetAmbientOcclusionRadius)
    float AmbientOcclusionRadius = 0.5f;

    /// Path tracing: samples per pixel added each frame, in [1, 65536]; a still view keeps accumulating.
    SPPROPERTY(Setter = SetSamplesPerPixel, meta = (ClampMin = 1, ClampMax = 65536))
    int32_t SamplesPerPixel = 4;

    /// Path tracing: denoise final_color and hdr_color (an edge-avoiding à-trous wavelet filter guided by the
    /// first surfaces' albedo, normal, distance and object; the lights' direct light is kept as it is; see
    /// core/pathtrace/denoise.h). The intrinsic images (diffuse_illumination, diffuse_only,
    /// specular_residual) stay unfiltered, the unbiased reference. Unreal's name; off by default.
    SPPROPERTY()
    bool bPathTracingEnableDenoiser = false;

    /// Path tracing: indirect bounces after the first hit, in [0, 64] (0: direct light and sky only).
    SPPROPERTY(Setter = SetMaxBounces, meta = (ClampMin = 0, ClampMax = 64))
    int32_t MaxBounces = 4;

    /// Path tracing, firefly control (Unreal's name): the light a path brings back to the first surface from
    /// beyond it is scaled down so that no channel exceeds this radiance; the first surface's direct light
    /// is kept. 0 (the default) clamps nothing: the unbiased reference. Fewer bright speckles at few samples,
    /// a little energy lost from small bright sources. Finite, >= 0.
    SPPROPERTY(Setter = SetPathTracingMaxPathIntensity)
    float PathTracingMaxPathIntensity = 0.0f;

    /// Path tracing, path regularisation (Unreal's r.PathTracing.ApproximateCaustics): a surface met after a
    /// diffuse or rough bounce is shaded at least that rough, so light a polished metal reflects from a lamp
    /// or the sun onto a wall is found by the lamp's own samples instead of by chance: fewer speckles at few
    /// samples (a third less spread in core/pathtrace's test). What the camera sees directly and in mirrors
    /// stays sharp; caustics are blurred, a bias. Off by default, unlike Unreal: the unbiased reference.
    SPPROPERTY()
    bool bPathTracingApproximateCaustics = false;

    // Settings are checked when they are set, on either transport, so that a bad value is refused with
    // the property's name and range instead of failing every later frame.

    /// Sets Width in pixels, in [1, 16384].
    SPFUNCTION()
    void SetWidth(int32_t NewWidth);
    /// Sets Height in pixels, in [1, 16384].
    SPFUNCTION()
    void SetHeight(int32_t NewHeight);
    /// Sets the horizontal field of view in degrees, in (0, 180).
    SPFUNCTION()
    void SetFOV(double NewFOV);
    /// Sets NearClip in metres (> 0 and finite).
    SPFUNCTION()
    void SetNearClip(double NewNearClip);
    /// Sets FarClip in metres (> 0 and finite; it must exceed NearClip when the camera renders).
    SPFUNCTION()
    void SetFarClip(double NewFarClip);
    /// Sets Exposure (> 0 and finite).
    SPFUNCTION()
    void SetExposure(float NewExposure);
    /// Sets AutoExposureBias in f-stops, in [-15, 15].
    SPFUNCTION()
    void SetAutoExposureBias(float NewBias);
    /// Sets AutoExposureMinBrightness as EV100, in [-20, 40].
    SPFUNCTION()
    void SetAutoExposureMinBrightness(float NewMinBrightness);
    /// Sets AutoExposureMaxBrightness as EV100, in [-20, 40].
    SPFUNCTION()
    void SetAutoExposureMaxBrightness(float NewMaxBrightness);
    /// Sets AutoExposureSpeedUp in f-stops per second, in (0, 100].
    SPFUNCTION()
    void SetAutoExposureSpeedUp(float NewSpeed);
    /// Sets AutoExposureSpeedDown in f-stops per second, in (0, 100].
    SPFUNCTION()
    void SetAutoExposureSpeedDown(float NewSpeed);
    /// Sets AutoExposureLowPercent, in [0, 100).
    SPFUNCTION()
    void SetAutoExposureLowPercent(float NewPercent);
    /// Sets AutoExposureHighPercent, in (0, 100].
    SPFUNCTION()
    void SetAutoExposureHighPercent(float NewPercent);
    /// Makes the next frame's automatic exposure that of what it shows, with no adaptation from the frames
    /// before (Unreal's camera cut): for views that do not follow one another, such as a dataset's random
    /// poses.
    SPFUNCTION()
    void ResetAutoExposure();
    /// Returns the exposure the frame last read was shown at (final_color's multiplier of hdr_color before
    /// the tone curve): Exposure with AEM_Manual, the metered one otherwise; 0 before a frame was read.
    SPFUNCTION()
    float GetAppliedExposure() const { return appliedExposure_; }
    /// Sets SensorWidth in millimetres (> 0 and finite); FOV is kept.
    SPFUNCTION()
    void SetSensorWidth(double NewSensorWidth);
    /// Sets FOV from a lens's focal length in millimetres on SensorWidth: FOV = 2 atan(SensorWidth / (2 f)).
    SPFUNCTION()
    void SetFocalLength(double FocalLength);
    /// Returns the focal length in millimetres that FOV gives on SensorWidth.
    SPFUNCTION()
    double GetFocalLength() const;
    /// Sets Exposure from an exposure value at ISO 100 (EV100, as light meters give it): a scene of
    /// luminance L (cd/m^2) metered at EV100 = log2(L * 100 / 12.5) maps to 18 % grey; Exposure = 1 / (1.2 *
    /// 2^EV100) (the saturation-based sensitivity of ISO 12232).
    SPFUNCTION()
    void SetExposureValue(double EV100);
    /// Sets Exposure from an aperture (f-number), a shutter time in seconds and an ISO speed: EV100 =
    /// log2(FNumber^2 / ShutterSeconds * 100 / ISO).
    SPFUNCTION()
    void SetPhysicalExposure(double FNumber, double ShutterSeconds, double ISO);
    /// Sets LensDistortion (every coefficient finite; a lens too strong to invert over the image is refused
    /// when the camera renders).
    SPFUNCTION()
    void SetLensDistortion(const FLensDistortion& NewLensDistortion);
    /// Sets PrincipalPointOffset in pixels (finite).
    SPFUNCTION()
    void SetPrincipalPointOffset(const FVector2D& NewPrincipalPointOffset);
    /// Returns the distortion coefficients in OpenCV's order, (k1, k2, p1, p2, k3) as a (5,) array, for
    /// cv2.undistort(image, K, coefficients) and cv2.projectPoints.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetDistortionCoefficients() const;
    /// Returns where pinhole pixels (an (N, 2) array of u, v under GetIntrinsicMatrix()'s K, no distortion)
    /// land in this camera's images: OpenCV's distortion model applied to them.
    SPFUNCTION()
    sp::reflect::SpArray<double> DistortPixels(const sp::reflect::SpArray<double>& Points) const;
    /// Returns the pinhole pixels ((N, 2)) that this camera's image pixels Points ((N, 2)) show: the inverse
    /// of DistortPixels (cv2.undistortPoints(..., P=K) approximates it), solved to about 1e-10 pixels; NaN
    /// for a pixel no ray shows (past where a strong barrel distortion folds over; such pixels render empty).
    SPFUNCTION()
    sp::reflect::SpArray<double> UndistortPixels(const sp::reflect::SpArray<double>& Points) const;
    /// Sets ApertureFNumber: 0 (a pinhole) or >= 0.5.
    SPFUNCTION()
    void SetApertureFNumber(double NewApertureFNumber);
    /// Sets FocusDistance in metres (> 0 and finite).
    SPFUNCTION()
    void SetFocusDistance(double NewFocusDistance);
    /// Sets MSAASampleCount: 2, 4 or 8.
    SPFUNCTION()
    void SetMSAASampleCount(int32_t NewMSAASampleCount);
    /// Sets SpatialSampleCount: 1, 2, 4, 8 or 16.
    SPFUNCTION()
    void SetSpatialSampleCount(int32_t NewSpatialSampleCount);
    /// Sets MaxAnisotropy: 0 (the renderer's default), or 1 to 16.
    SPFUNCTION()
    void SetMaxAnisotropy(int32_t NewMaxAnisotropy);
    /// Sets MipMapLODBias, in [-2, 2].
    SPFUNCTION()
    void SetMipMapLODBias(float NewMipMapLODBias);
    /// Sets AmbientOcclusionIntensity, in [0, 1].
    SPFUNCTION()
    void SetAmbientOcclusionIntensity(float NewAmbientOcclusionIntensity);
    /// Sets AmbientOcclusionRadius in metres, in (0, 100].
    SPFUNCTION()
    void SetAmbientOcclusionRadius(float NewAmbientOcclusionRadius);

    /// Sets VignetteIntensity, in [0, 1].
    SPFUNCTION()
    void SetVignetteIntensity(float NewVignetteIntensity);
    /// Sets WhiteBalanceTemperature in kelvin, in [2000, 25000].
    SPFUNCTION()
    void SetWhiteBalanceTemperature(double NewWhiteBalanceTemperature);
    /// Returns the gains (3,) white balance multiplies linear red, green and blue by before the tone curve
    /// (1, 1, 1 at 6500 K; a grey keeps its luminance).
    SPFUNCTION()
    sp::reflect::SpArray<double> GetWhiteBalanceGains() const;
    /// Sets ShadowResolution in texels, in [16, 8192], or 0 to size it to the world's cameras.
    SPFUNCTION()
    void SetShadowResolution(int32_t NewShadowResolution);
    /// Sets Latency: 0, 1 or 2 frames.
    SPFUNCTION()
    void SetLatency(int32_t NewLatency);
    /// Sets SamplesPerPixel, in [1, 65536].
    SPFUNCTION()
    void SetSamplesPerPixel(int32_t NewSamplesPerPixel);
    /// Sets PathTracingMaxPathIntensity (finite, >= 0; 0 clamps nothing).
    SPFUNCTION()
    void SetPathTracingMaxPathIntensity(float NewIntensity);
    /// Sets MaxBounces, in [0, 64].
    SPFUNCTION()
    void SetMaxBounces(int32_t NewMaxBounces);

    /// Returns the intrinsic matrix K (3, 3) of the images in OpenCV's convention: pixel (u right, v down,
    /// the centre of pixel [i, j] at u = j, v = i) = K @ (x, y, z) / z for a point (x, y, z) in the OpenCV
    /// camera frame (x right, y down, z forward); fx = fy = (Width / 2) / tan(FOV / 2), cx = (Width - 1) / 2
    /// + PrincipalPointOffset.X, cy = (Height - 1) / 2 + PrincipalPointOffset.Y. With LensDistortion the
    /// distortion applies between the normalised point and K, as in OpenCV (DistortPixels).
    SPFUNCTION()
    sp::reflect::SpArray<double> GetIntrinsicMatrix() const;

    /// Returns the world-to-camera transform (4, 4) into the OpenCV camera frame (x right, y down, z
    /// forward, metres) from the component's current world transform: with GetIntrinsicMatrix(), a world
    /// point's pixel is K @ (T @ [p, 1])[:3] divided by its z. Both describe the camera as it is now: the
    /// frame read in the same end_frame at Latency 0, Latency frames earlier otherwise.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetWorldToCamera() const;

    /// Returns the samples per pixel behind the path-traced images of the frame last read (they restart
    /// from SamplesPerPixel when anything in the scene, the camera or MaxBounces changes), or 0 when the
    /// last read frame was not path traced.
    SPFUNCTION()
    int64_t GetAccumulatedSamples() const { return accumulatedSamples_; }

    /// Returns the images of the frame due (see the class notes on latency); an empty dict while priming or
    /// before the camera's first frame. In begin_frame, the frame rendered at the end of the last one.
    SPFUNCTION()
    FCameraPixels read_pixels();

    /// Renders this camera now, between frames, showing the world as it stands (nothing ticks): read_pixels()
    /// returns it next (with Latency N, after N more). What the inspector's viewer shows of a paused world.
    SPFUNCTION()
    void RenderNow();

    /// Returns the images of several cameras' due frames (cameras of any worlds of one engine) in one call:
    /// each modality as one array with a leading camera axis, (len(Cameras), H, W[, C]), each camera's images
    /// read straight into its slice. The cameras must show frames of one size and the same modalities; an
    /// empty dict while any of them is priming.
    SPFUNCTION()
    static FCameraPixels read_pixels_stacked(const std::vector<UCameraSensorComponent*>& Cameras);

    /// Returns the world frame shown by the last read_pixels() result, or -1 when it was empty.
    SPFUNCTION()
    int64_t GetPixelsFrame() const { return pixelsFrame_; }

    /// Sets Modalities from snake_case names ("final_color", "depth", ...); an unknown name is an error.
    SPFUNCTION()
    void SetModalityNames(const std::vector<std::string>& Names);

    /// Returns the snake_case names of Modalities, in the order read_pixels() uses as dict keys.
    SPFUNCTION()
    std::vector<std::string> GetModalityNames() const;

    /// Looks up an object id of object_ids: the actor, the component and the material slot and name it
    /// belongs to (a spline's debug line: its actor, Component None, material "DebugLine"; drawn roads: the
    /// AZoneGraphData, Component None, slot 0 road, 1 sidewalk, 2 markings); returns False
    /// (and None, -1, "") for 0, an unknown id or a destroyed component.
    SPFUNCTION()
    bool GetObjectIdInfo(int64_t ObjectId, AActor*& Actor, UPrimitiveComponent*& Component,
                         int32_t& MaterialSlot, std::string& MaterialName) const;

    /// Returns the object id of one material slot of Component, or 0 when it has not been rendered yet.
    SPFUNCTION()
    int64_t GetObjectId(UPrimitiveComponent* Component, int32_t MaterialSlot = 0) const;

    /// Returns the material id that material_ids holds for the material called Name, or 0 when unused.
    SPFUNCTION()
    int64_t GetMaterialId(const std::string& Name) const;

    /// Returns which EGL device renders this camera's world (starting the renderer if needed).
    SPFUNCTION()
    FRenderDeviceInfo get_render_device_info();

    /// Returns how often each render pass ran in this camera's world, and its timings.
    SPFUNCTION()
    FRenderStats GetRenderStats() const;

    void BeginPlay() override;

    // The lens of the images: K (with the principal point offset) and the distortion coefficients.
    sp::render::LensModel lensModel() const;

    // Set by the RenderSubsystem when read_pixels() reads a frame.
    void setPixelsFrame(int64_t frame) { pixelsFrame_ = frame; }
    void setAccumulatedSamples(int64_t samples) { accumulatedSamples_ = samples; }
    void setAppliedExposure(float exposure) { appliedExposure_ = exposure; }
    // Set by a render job for an engine frame whose output frame is already written: the world does not
    // render this camera in that frame.
    void setRenderSuspended(bool suspended) { renderSuspended_ = suspended; }
    bool renderSuspended() const { return renderSuspended_; }

  private:
    int64_t pixelsFrame_ = -1;
    int64_t accumulatedSamples_ = 0;
    float appliedExposure_ = 0.0f;
    bool renderSuspended_ = false;
};
