#pragma once
// GLSL 4.50 sources of the render passes. The surface programs are composed per variant
// from shared chunks (material evaluation, shading, tone curve), with one output per target the variant
// writes, so that a pass never computes or stores what no requested modality needs.
//
// Variants are also specialised for the scene's lights (unrolled, one block per light with its type,
// shadow layer and range fixed) and for the textures a material has. A GPU skips a branch that no pixel
// takes; a software rasteriser (Mesa's llvmpipe) runs both sides of every branch under a mask, so a
// loop over lights or an `if (hasTexture)` costs as if every light and texture were always there.

#include <cstddef>
#include <string>
#include <vector>

#include "core/render/camera.h"
#include "core/render/light.h"
#include "core/render/modality.h"

namespace sp::render::shaders {

inline constexpr int kMaxLights = 16;     // must match MAX_LIGHTS in kFrameBlock
inline constexpr int kMaxShadowMaps = 16; // must match MAX_SHADOWS in kFrameBlock
// Of those, the maps of directional, spot and rect lights, whose coordinates the vertex shader interpolates
// (a varying each): they hold the first layers. A point light's six cube faces follow, looked up per pixel.
inline constexpr int kMaxProjectedShadowMaps = 4;

// The image unit the shading reads shadow maps from (binding 0 in kShadingChunk).
inline constexpr int kShadowMapImageUnit = 0;
// The image unit and storage-buffer binding of the id-channel copy (idChannelCompute()).
inline constexpr int kIdsImageUnit = 1;
inline constexpr int kPackedIdsBinding = 0;
inline constexpr int kFrameBlockBinding = 0;

// Per-frame constants of one view, shared by every program through one uniform buffer (std140).
struct FrameBlock {
    float cameraPosition[4]; // xyz; w: the layer of the scene's first shadow map (ShadowLayers)
    float ambient[4];        // xyz: uniform sky radiance
    float background[4];     // xyz: hdr_color of background pixels
    int counts[4]; // x = light count (informative: the programs are specialised), y = the view's layer,
                   // z = the shader's anisotropic taps (Renderer::shaderTextureTaps(); 1: the sampler's),
                   // w = the view's spatial samples
    float lightRadiance[16][4]; // xyz = colour * intensity
    // Reciprocals rather than the values the shading would divide by (see accumulate() in shaders.cpp).
    float lightPosition[16][4];             // xyz, w = 1 / range (0 = unbounded)
    float lightDirection[16][4];            // xyz unit direction light travels
    float lightCone[16][4];                 // x = cos(outer), y = 1 / max(cos(inner) - cos(outer), 1e-4)
    float shadowMatrix[kMaxShadowMaps][16]; // world -> light clip, column-major
    float shadowParams[kMaxShadowMaps][4];  // x = world texel size (per metre of distance when perspective),
                                            // y = resolution
    float backgroundFinal[4];  // rgba: final_color of background pixels (tone-mapped on the CPU side)
    float exposure[4];         // xyz: exposure times the white balance gains
    float vignette[4];         // x = intensity, y = focal length in pixels, zw = the image centre in pixels
    float irradianceVolume[4]; // xyz: world position of the volume's probe (0, 0, 0); w: 1 / spacing
    // The environment map's diffuse term (EnvironmentMap::diffuseCoefficients() times its scale), xyz each.
    float skyDiffuse[9][4];
    float environment[4]; // xyz: the map's scale; w: the prefiltered chain's last level
};

// Where the shading blends the irradiance probes: not at all, per pixel (sixteen image loads a pixel: cheap
// on a GPU, most of a 1080p frame on llvmpipe), or per vertex, interpolated, on meshes subdivided until their
// vertices are no further apart than the probes (Renderer::refineLevel()).
enum class IrradianceBlend { None, PerPixel, PerVertex };

// One light of a shading variant.
struct LightSlot {
    LightType type = LightType::Directional;
    int shadowLayer = -1; // layer of the shadow map array (a point light's first of six), -1 for none
    bool ranged = false;  // point or spot light with a finite AttenuationRadius

    bool operator==(const LightSlot&) const = default;
};
// The lights a shading variant is compiled for, in the scene's light order (FrameBlock's indices).
struct ShadingLayout {
    std::vector<LightSlot> lights;
    bool floatShadowMaps = false; // the shadow maps are GL_R32F, not GL_R16 (ShadowMaps::format())
    bool vignette = false;        // final_color is vignetted (FrameBlock::vignette)
    // final_color's tone curve, compiled in: chosen at run time, a SIMD rasteriser evaluated every curve.
    ToneMap toneMap = ToneMap::Aces;
    // Flat varyings (vec4s) the vertex shader may fill with the FrameBlock values the fragment shader reads:
    // camera position, ambient, exposure, vignette, shadow-map sizes and as many lights as fit (the rest
    // are read from FrameBlock); 0 reads them all from FrameBlock. Mesa's llvmpipe loads a uniform-buffer
    // value in a fragment shader as a gather, one scalar load per pixel of its 8-pixel vectors, even at a
    // constant offset, while a flat varying is set up once per triangle: the Table 3 workload's 1080p frame
    // took 23% less time. GPUs read uniform buffers at no cost, so hardware contexts keep them
    // (Renderer::constantSlots()).
    int constantSlots = 0;
    // Whether the shading blends the scene's irradiance volume (irradiance_volume.h) where it otherwise adds
    // the uniform ambient term, and where (Renderer::vertexIrradiance()).
    IrradianceBlend irradiance = IrradianceBlend::None;
    // Per vertex: the vertex shader loads the probes as an image (cheaper than a texel fetch on llvmpipe,
    // whose sampler path is general), where the driver allows images in vertex shaders (GL 4.5 need not).
    bool vertexProbeImages = false;
    // The sky term comes from the scene's environment map (environment_map.h): diffuse from its spherical
    // harmonics, specular from its prefiltered chain; the background from the map (drawBackground()). The
    // irradiance volume, where blended, still gives both terms: its probes saw the map.
    bool environmentMap = false;
    // Screen-space ambient occlusion (screen_occlusion.h): 0 none, else the view pixels a side of one of its
    // texels (ScreenOcclusion::scaleFor()); the indirect and sky light are scaled by it, read from
    // kScreenOcclusionUnit.
    int screenOcclusionScale = 0;
    // A short text naming the layout, for program caches ("D0.S1r.P").
    std::string key() const;
};

// What a surface program is compiled for beside its targets and lights: the textures a material samples,
// each one present compiled in (see the header comment), and how its normals are turned to the camera.
enum MaterialFeature : unsigned {
    kBaseColorTexture = 1,
    kRoughnessMetallicTexture = 2,
    kNormalTexture = 4,
    kTextureFeatures = 7,
    // The draw's normals lie on their triangles' winding side (windingTurnsNormals() in mesh_data.h): the
    // rasteriser's facing turns them, instead of a geometric normal from screen derivatives of the position
    // (on llvmpipe 5% of a 1080p final_color frame). Not with a normal texture, whose frame needs them
    // anyway.
    kFacingFromWinding = 8,
    // The textures are projected on the object's scaled box axes (Material::textureSize, box_uv.h).
    kBoxUv = 16,
};

// The shadow pass's vertex shader: instanced, the light projection in InstanceRecord's modelViewProjection;
// `layered`, it also sends each primitive to layer uLayer (ARB_shader_viewport_layer_array; see
// ShadowLayers).
std::string shadowVertex(bool layered);
extern const char* const kShadowFragment;

// Copies channel uChannel (0: object ids, 1: material ids) of the uSize pixels of the ids target from uOrigin
// into a tightly packed uint buffer, in glReadPixels' row order; 16 x 16 work groups.
// `layered`: of layer uLayer of an array (a page of shared framebuffers: see FramebufferAtlas).
std::string idChannelCompute(bool layered);
inline constexpr int kIdChannelGroupSize = 16;

// The surface and attribute passes: rasterise every visible instance and write `targets` (a mask of
// Target bits, in Target order at locations 0, 1, ...); when `forward`, shade each fragment as well (the
// HDR, intrinsic and final colour targets).
// `layered`: into the view's layer (FrameBlock's uCounts.y) of layered framebuffers (FramebufferAtlas).
// `boxUv`: with the object's scaled position and normal for kBoxUv materials.
std::string surfaceVertex(bool forward, const ShadingLayout& lights, bool layered = false,
                          bool boxUv = false);
// `compact`: into compact targets (PassSet::compactTargets).
std::string surfaceFragment(TargetMask targets, bool forward, unsigned materialFeatures,
                            const ShadingLayout& lights, bool compact = false);

// The background of a vignetted final_color: a full-screen triangle on the far plane writing the tone-mapped,
// vignetted background colour at draw buffer `location`, drawn after the surfaces where none was.
// `layered`: into the view's layer (FrameBlock's uCounts.y) of layered framebuffers.
std::string backgroundVertex(bool layered);
std::string backgroundFragment(int location, ToneMap toneMap);
// The background of a scene with an environment map: the map seen along each pixel's ray (uClipToOffset as
// in computeLighting(), uSize, uBackgroundLod: the background texture's level) into hdr_color and
// specular_residual (all of a background pixel is residual) and, tone-mapped, final_color, at their locations
// among `targets`; drawn after the surfaces where none was.
std::string environmentBackgroundFragment(TargetMask targets, ToneMap toneMap, bool compact);
// The resolve of multisampled shaded targets (PassSet::samples > 1): the average of each pixel's `samples`
// samples of each of `targets` (read from texture units kResolveTextureUnit + i, in Target order) into the
// same location; final_color's samples are averaged in linear light, as a camera's pixel (and a supersampled
// view) averages light, and encoded again. With `layers` above 1, the samples are the layers of 2D array
// textures instead (PassSet::spatialSamples), and `samples` is ignored.
inline constexpr int kResolveTextureUnit = 16;
std::string resolveFragment(TargetMask targets, int samples, int layers = 1);
// Writes uClear[i] into the i-th of `targets` (in Target order; zero into the ids target): a clear of one
// view's layer of shared framebuffers, drawn with backgroundVertex(true) (see Renderer::clearTargets).
std::string clearFragment(TargetMask targets, bool compact = false);

// The compute lighting pass (PassSet::computeLighting()): for each pixel whose G-buffer names a draw (not the
// background, not a pixel its fragment shaded), the world position from the depth buffer, the normal and
// the draw's material from the G-buffer and its InstanceRecord, shaded as the forward pass shades (shadow
// coordinates per pixel) into `targets` (FinalColor and/or Hdr) as images. Work groups of
// kComputeLightingGroupSize squared.
// `materials`: textured draws wrote Target::GBufferMaterial, read where a record's ids.w has bit 0.
std::string computeLighting(TargetMask targets, const ShadingLayout& lights, bool materials);
inline constexpr int kComputeLightingGroupSize = 8;
// The draws of a view the G-buffer can name (10 bits, all ones reserved): later ones are shaded in their
// fragments.
inline constexpr std::size_t kGBufferRecords = 1023;
// Its bindings: the records (storage buffer), the depth texture, the G-buffer and the output images.
inline constexpr int kRecordsBinding = 1;
inline constexpr int kDepthTextureUnit = 3;
inline constexpr int kGBufferImageUnit = 2;
inline constexpr int kFinalColorImageUnit = 3;
inline constexpr int kHdrImageUnit = 4;
inline constexpr int kGBufferMaterialImageUnit = 6;
// The image unit of the irradiance probes (IrradianceVolume::packed()), read by every shading program.
inline constexpr int kIrradianceImageUnit = 5;
// The texture unit a vertex shader fetches them from (per-vertex blending).
inline constexpr int kIrradianceTextureUnit = 6;
// The texture units of the environment map: its prefiltered chain (the specular term) and the full map (the
// background).
inline constexpr int kEnvironmentSpecularUnit = 7;
inline constexpr int kEnvironmentBackgroundUnit = 8;
// The image unit of the view's screen-space ambient occlusion (ShadingLayout::screenOcclusionScale).
inline constexpr int kScreenOcclusionUnit = 7;

// The passes of ScreenOcclusion (screen_occlusion.h), drawn with backgroundVertex(false): the occlusion of
// each texel from the depth pass's texture (unit 0; uCamera: focal length in texels, radius in metres, the
// largest radius in texels), and its 4 x 4 depth-aware blur (the depth at unit 0, the occlusion at unit 1,
// uIntensity).
std::string screenOcclusionFragment();
std::string screenOcclusionBlurFragment();

} // namespace sp::render::shaders
