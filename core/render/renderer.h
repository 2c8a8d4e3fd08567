#pragma once
// The GL renderer: owns the shader programs and, per scene it renders, the GPU copies of the scene's
// meshes and textures, its shadow maps and its statistics; runs the passes a RenderTarget asks for (see
// PassSet in modality.h): shadow maps (reused while lights and casters do not move, so the views of one frame
// share them), then one surface pass that shades, tone-maps and writes up to 8 targets, and for larger sets
// an attribute pass that writes the rest at the fragments the surface pass kept. Instances outside the view
// are culled and the rest drawn front to back, so hidden fragments fail the early depth test. One Renderer
// per GlContext, shared by any number of scenes (an engine's worlds share one: one context, one set of
// compiled programs); destroy it (and its RenderTargets) before the context.

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "core/render/camera.h"
#include "core/render/derived_images.h"
#include "core/render/gl_context.h"
#include "core/render/modality.h"
#include "core/render/pass_timers.h"
#include "core/render/scene.h"
#include "core/render/shaders.h"
#include "core/render/shadow_reach.h"

namespace sp::render {

class Framebuffers;
class FramebufferAtlas;
class GpuSceneCache;
struct GpuTexture;
class InstanceBuffer;
struct InstanceRecord;
struct SharedUploads;
class ScreenOcclusion;
class ShaderProgram;
class ShadowLayers;
class ShadowMaps;
struct ShadowInfo;

// How often each pass ran (tests use it to check that only the needed passes run), and what it cost.
struct RenderStats {
    std::uint64_t frames = 0;
    std::uint64_t shadowPasses = 0;    // one per shadow map rendered
    std::uint64_t shadowReuses = 0;    // frames whose shadow maps were reused unchanged
    std::uint64_t surfacePasses = 0;   // surface passes (shading or not)
    std::uint64_t attributePasses = 0; // attribute passes (targets past the surface pass's 8)
    std::uint64_t lightingPasses = 0;  // frames that shaded
    std::uint64_t tonemapPasses = 0;   // frames that tone-mapped (fused into the shading)
    std::uint64_t readbacks = 0;       // one per modality read back
    std::uint64_t meshUploads = 0;
    std::uint64_t textureUploads = 0;
    std::uint64_t drawnInstances = 0;        // instances drawn by surface passes
    std::uint64_t drawCalls = 0;             // instanced draw calls of surface and attribute passes
    std::uint64_t culledInstances = 0;       // instances outside the view, not drawn
    std::uint64_t unshadowedInstances = 0;   // shaded without shadow lookups: no shadow reaches them
    std::uint64_t splitInstances = 0;        // shaded in parts: lookups only where a shadow can fall
    std::uint64_t windingFacedInstances = 0; // normals turned by the rasteriser's facing (kFacingFromWinding)
    std::uint64_t lightsLeftOut = 0;         // lights reaching a view past the 16 it shades (the farthest)
    std::uint64_t irradianceUploads = 0;     // irradiance volumes uploaded (a new one, or new probe values)
    std::uint64_t environmentUploads = 0;    // environment maps uploaded (a new map)
    std::uint64_t occlusionPasses = 0;       // screen-space ambient occlusion computed (screen_occlusion.h)
    std::uint64_t constantSlotPasses = 0; // surface passes whose fragments read constants from flat varyings
    std::array<PassTime, kPassCount> passTimes{}; // by Pass
};

class Renderer {
  public:
    // Makes `context` current and compiles the programs; throws sp::InvalidState when a shader fails.
    explicit Renderer(const GlContext& context);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const ContextReport& contextReport() const { return context_.report(); }
    // What the renderer did for one scene (by Scene::uid()) since it first rendered it or since
    // resetStats(), and the sum over every scene.
    RenderStats stats(std::uint64_t sceneUid) const;
    RenderStats stats() const;
    void resetStats();
    // Frees what the renderer holds for a scene: its meshes' and textures' GPU copies, its shadow maps and
    // statistics (call when a Scene is destroyed).
    void releaseScene(const Scene& scene);

    // One view of a batch: the passes to run for `camera` in `scene`, into `framebuffers` (allocated for
    // them at the camera's size), or with a layer, into that layer of layered ones.
    struct View {
        const Scene* scene = nullptr;
        const Camera* camera = nullptr;
        PassSet passes;
        Framebuffers* framebuffers = nullptr;
        int layer = -1;
        // When its surface pass writes Target::Record: given the materials of the draws it names.
        std::vector<DrawMaterial>* materials = nullptr;
    };
    // Runs the passes of each view into its framebuffers (used by RenderTarget; see render_target.h for the
    // public way): first the shadow maps of every scene the views see (a scene's views share its maps, which
    // cover what all of them see), then the views in order. A software rasteriser runs the work queued
    // between two changes of the bound framebuffer as one job for its threads; with the maps in shared
    // layers (shadow_layers.h) and small views in shared framebuffers (framebuffer_atlas.h), a batch of many
    // small worlds costs a few jobs rather than two per world. Views of one scene that ask for different
    // shadow-map resolutions split the batch where the second one comes.
    void render(std::span<const View> views);
    // The shared framebuffers small views are drawn in (RenderTarget takes its tiles there).
    FramebufferAtlas& atlas() { return *atlas_; }
    // Bracket one modality's readback of a frame of scene `sceneUid` (RenderTarget): counted and timed in
    // that scene's statistics (not at all once the scene is released).
    void beginReadback(std::uint64_t sceneUid);
    void endReadback(std::uint64_t sceneUid);
    // The compute program that copies one channel of the ids target (RenderTarget's id readback), of a
    // layer of layered framebuffers or not.
    ShaderProgram& idChannelProgram(bool layered);
    // Whether RenderTarget reads object and material ids through that compute copy rather than
    // glReadPixels of one channel: by default on hardware, where the driver's one-channel integer read is
    // slow; a CPU rasteriser converts on the CPU either way, and the dispatch only adds to it.
    bool packIdsOnGpu() const { return packIdsOnGpu_; }
    void setPackIdsOnGpu(bool on) { packIdsOnGpu_ = on; }
    // Whether a latency-0 view with framebuffers of its own queues its readback into pixel-buffer objects
    // when it is submitted, as a longer ring does, rather than reading the framebuffers when it is read: by
    // default on hardware, where the GPU then copies the image out while it draws the next view and the
    // read copies it from there on several threads; a CPU rasteriser would only copy it twice.
    // SPEAR_READBACK=staged|direct overrides the default. Settable, so that tests read both ways; the bytes
    // are the same.
    bool stagedReadback() const { return stagedReadback_; }
    void setStagedReadback(bool on) { stagedReadback_ = on; }
    // Whether RenderTarget computes the modalities that other modalities define on the CPU when a set
    // needs more targets than one pass writes (planModalities()): by default on a software rasteriser,
    // which pays for every target it writes. SPEAR_DERIVED_MODALITIES=cpu|rendered overrides the default.
    // Settable, so that tests compare both ways.
    bool derivesOnCpu() const { return derivesOnCpu_; }
    void setDerivesOnCpu(bool on) { derivesOnCpu_ = on; }
    // Whether views render into compact targets (PassSet::compactTargets: float16 targets as RGBA16UI holding
    // float16 bits, the normal as two octahedral coordinates): by default on a software rasteriser, whose
    // fragment stores cost least for 32-bit and integer channels (all 14 modalities at 1080p on llvmpipe:
    // core/render/README.md). The images read are the same, up to a float16 rounding and the normal's
    // decoding (a few units in the last place of float32). Views computed in compute lighting keep float
    // targets. SPEAR_TARGET_FORMATS=compact|float overrides the default. Settable, so that tests compare
    // both.
    bool compactTargets() const { return compactTargets_; }
    void setCompactTargets(bool on) { compactTargets_ = on; }
    // The threads a read splits its copy out of a pixel-buffer object across (parallelCopy()); by default
    // defaultCopyThreads().
    int readbackThreads() const { return readbackThreads_; }
    void setReadbackThreads(int threads) { readbackThreads_ = std::max(1, threads); }
    // Whether a view that shades only colour (final_color, hdr_color, with any unshaded targets) and has
    // framebuffers of its own is shaded by a compute pass over a G-buffer (Target::GBuffer: normal and
    // draw, 4 bytes a pixel; Target::GBufferMaterial: a textured material's factors, 8 more where one is
    // drawn) rather than in its fragments: by default on hardware, where fragment shaders run on the few
    // units a data-centre GPU keeps for graphics and compute shaders on all of them (spear_shading_probe: the
    // same shading 25-150 times cheaper on an H100). On llvmpipe the compute pass costs more than the
    // fragments it spares. With the irradiance blended at the vertices (vertexIrradiance()), the fragments
    // shade.
    // SPEAR_LIGHTING=compute|forward overrides the default. Settable, so that tests render both ways;
    // images agree within the tolerance of per-pixel shadow coordinates and an 11-bit normal.
    bool computeLighting() const { return computeLighting_; }
    void setComputeLighting(bool on) { computeLighting_ = on; }
    // Where the shading blends a scene's irradiance volume (shaders::IrradianceBlend): at the vertices of
    // meshes subdivided to the probe spacing (a software rasteriser: a 1080p frame's per-pixel blend cost
    // llvmpipe 86 ms, spear_render_bench --gi), or per pixel (a GPU). SPEAR_IRRADIANCE_BLEND=vertex|pixel
    // overrides the default.
    bool vertexIrradiance() const { return vertexIrradiance_; }
    // Whether material textures are filtered anisotropically (samples spread along a pixel's footprint) or
    // trilinearly: on by default. SPEAR_TEXTURE_FILTER=anisotropic|trilinear overrides the default; throws
    // sp::InvalidArgument turning it on where neither the sampler nor the shader can. A view's
    // CameraParams::maxAnisotropy, when not 0, takes the place of this default for that view.
    bool anisotropicFiltering() const { return anisotropicFiltering_; }
    void setAnisotropicFiltering(bool on);
    static constexpr float kMaxAnisotropy = 8.0f; // UE's r.MaxAnisotropy default: the sampler's
    // Where the anisotropic filtering happens: in the sampler (a GPU's, where it is all but free) or in the
    // surface shader, kShaderAnisotropy trilinear reads of base colour and roughness / metallic along the
    // footprint (a software rasteriser: llvmpipe's own anisotropic sampler more than doubled a 1080p frame of
    // the textured default scene; the shader's costs it 1.4x, for the same SSIM against the path tracer,
    // BENCHMARKS.md). Also the shader where the context's sampler has none. SPEAR_ANISOTROPY=shader|sampler
    // overrides the default.
    bool shaderAnisotropy() const { return shaderAnisotropy_; }
    void setShaderAnisotropy(bool on);
    static constexpr int kShaderAnisotropy = 4; // as 8 on the default scene (SSIM 0.922 both), for less
    // The shader's reads a view's texture takes along the footprint: 1 where the sampler filters.
    int shaderTextureTaps(const Camera& camera) const;
    // A view's anisotropic samples or reads: its CameraParams::maxAnisotropy, else the renderer's default
    // (kMaxAnisotropy in the sampler, kShaderAnisotropy in the shader; 1 with anisotropic filtering off).
    int viewAnisotropy(const Camera& camera) const;
    void setVertexIrradiance(bool on) { vertexIrradiance_ = on; }
    // How many times a mesh whose longest edge is `edge` metres in the world (scale included), with
    // `triangles` triangles, is subdivided for per-vertex indirect light on probes `spacing` apart: until its
    // edges are no longer than the spacing, at most kMaxRefine times and 65,536 triangles.
    static int refineLevel(double edge, double spacing, std::size_t triangles);
    static constexpr int kMaxRefine = 6;
    // Adds the G-buffer and the compute pass to `passes` where computeLighting() applies (see above).
    void planComputeLighting(PassSet& passes) const;
    // The flat varyings the surface programs may spend on the per-view constants their fragments read
    // (shaders::ShadingLayout::constantSlots): what the driver's varying limits leave on a software
    // rasteriser, 0 on a GPU. Settable, so that tests render both ways; images are the same bit for bit.
    int constantSlots() const { return constantSlots_; }
    void setConstantSlots(int slots) { constantSlots_ = std::max(0, slots); }
    // A view spends them only where it has at least kPixelsPerConstantTriangle pixels for each triangle it
    // draws (viewConstantSlots()): a flat varying is paid for per triangle and saves per pixel, so a view of
    // finely tessellated meshes reads its constants from the uniform buffer (on llvmpipe, 64 spheres of
    // 1,024 triangles each at 640x480: 29-32 against 19-28 ms a frame; of 16,384 at 1080p: 188-194 against
    // 167-175 ms), while Table 3's 256x256 view of 64 objects (27 pixels a triangle) keeps them (2.5-2.7
    // against 2.7-3.2 ms without). Off, a view spends them whatever it draws, so that tests render both ways.
    bool adaptiveConstantSlots() const { return adaptiveConstantSlots_; }
    void setAdaptiveConstantSlots(bool on) { adaptiveConstantSlots_ = on; }
    static constexpr std::uint64_t kPixelsPerConstantTriangle = 16;
    // The constant slots of a view of `pixels` pixels drawing `triangles` triangles: constantSlots() or 0.
    int viewConstantSlots(std::uint64_t triangles, std::uint64_t pixels) const {
        return !adaptiveConstantSlots_ || pixels >= kPixelsPerConstantTriangle * triangles ? constantSlots_
                                                                                           : 0;
    }
    // Whether the surface pass shades what no shadow can reach without shadow-map lookups, and a large
    // instance a shadow falls on in part in scissored parts (see shadow_reach.h): by default on a software
    // rasteriser, where the lookups are a fifth of a shaded pixel; a GPU would only pay for more draws.
    // Settable, so that tests render both ways; images are the same bit for bit.
    bool shadowReach() const { return shadowReach_; }
    void setShadowReach(bool on) { shadowReach_ = on; }
    // Whether draws whose normals lie on their triangles' winding side turn them to the camera by the
    // rasteriser's facing rather than by screen derivatives (shaders::kFacingFromWinding): on by default.
    // Settable, so that tests render both ways; images are the same but where a triangle is seen edge-on.
    bool facingFromWinding() const { return facingFromWinding_; }
    void setFacingFromWinding(bool on) { facingFromWinding_ = on; }
    // Whether the shadow maps of all scenes are drawn in one layered framebuffer (see shadow_layers.h): by
    // default wherever the driver offers ARB_shader_viewport_layer_array. Settable, so that tests render
    // both ways (images are the same bit for bit); setting it drops what the renderer holds for its scenes.
    bool layeredShadowMaps() const;
    void setLayeredShadowMaps(bool on);
    // The most coverage samples a pixel multisampled targets can have here (GL_MAX_SAMPLES and the colour and
    // depth texture limits; 4 on llvmpipe); a camera asking for more gets these.
    int maxSamples() const { return maxSamples_; }

  private:
    struct Draw; // one submesh of a visible instance
    // What the renderer keeps for one scene.
    struct SceneState {
        SceneState(SharedUploads& shared, ShadowLayers& layers, std::uint64_t sceneUid);
        ~SceneState();
        std::unique_ptr<GpuSceneCache> cache;
        std::unique_ptr<ShadowMaps> shadowMaps;
        // The scene's irradiance volume as uploaded (a 3D texture), and which one and revision it holds.
        std::unique_ptr<GpuTexture> irradiance;
        const IrradianceVolume* irradianceSource = nullptr;
        std::uint64_t irradianceRevision = 0;
        // The scene's environment map as uploaded (its prefiltered chain and its full map, for the
        // background) and which map that is (EnvironmentMap::uid()).
        std::unique_ptr<GpuTexture> environmentSpecular, environmentBackground;
        std::uint64_t environmentUid = 0;
        int environmentBackgroundWidth = 0;
        RenderStats stats;
        PassTimers timers; // stats() collects finished timer queries
    };

    SceneState& stateFor(const Scene& scene);
    // The shadow maps of the scenes of `views` (all of them compatible: see render()), each brought up to
    // date once, for what its shadowed views see.
    void updateShadowMaps(std::span<const View> views);
    // The passes of one view after the shadow maps.
    void renderView(const View& view);
    // The scene's state, or null when the renderer holds none for it.
    SceneState* findState(std::uint64_t sceneUid) const;
    // A surface or attribute program; for layered framebuffers when the view being drawn has a layer.
    ShaderProgram& surfaceProgram(TargetMask targets, bool forward, unsigned materialFeatures,
                                  const shaders::ShadingLayout& lights);
    // A light a view shades: the scene's light, its position in the scene's order (ShadowInfo::lightOrdinal)
    // and how far the view is from where it reaches (-1 for an unbounded light).
    struct ViewLight {
        const Light* light = nullptr;
        int ordinal = -1;
        double distance = 0.0;
    };
    // The lights that reach the view's frustum, in the scene's order, at most shaders::kMaxLights (the
    // nearest, counted in RenderStats::lightsLeftOut past that).
    std::vector<ViewLight> viewLights(const Scene& scene, const Camera& camera);
    // Uploads the scene's irradiance volume when it changed and binds it for the shading programs; false when
    // the scene has none.
    bool bindIrradianceVolume(const Scene& scene);
    // Uploads the scene's environment map when it is a new one and binds it for the shading and background
    // programs; false when the scene has none.
    bool bindEnvironment(const Scene& scene);
    void uploadFrameBlock(const Scene& scene, const Camera& camera, const std::vector<ShadowInfo>& shadows,
                          const std::vector<ViewLight>& lights);
    // The submeshes of the instances in view, grouped by program and front to back within a group; with
    // `receivers`, each knows where shadows reach it (the parts of those drawn in parts go to parts_). The
    // levels of detail are chosen for pixels `detail` times smaller than the camera's (spatial samples).
    std::vector<Draw> visibleDraws(const Scene& scene, const Camera& camera, const ShadowReceivers* receivers,
                                   double detail = 1.0);
    // The view's screen-space ambient occlusion (screen_occlusion.h): its depth drawn alone, the occlusion
    // and its blur, bound to shaders::kScreenOcclusionUnit for the surface pass. Replaces the FrameBlock.
    void screenOcclusionPass(const Scene& scene, const Camera& camera, const std::vector<Draw>& draws,
                             const shaders::ShadingLayout& lights, GpuSceneCache& cache);
    void surfacePass(const Scene& scene, const Camera& camera, const PassSet& passes,
                     const shaders::ShadingLayout& lights, const std::vector<Draw>& draws,
                     GpuSceneCache& cache, Framebuffers& fb);
    void attributePass(const Scene& scene, const Camera& camera, const PassSet& passes,
                       const std::vector<Draw>& draws, GpuSceneCache& cache, Framebuffers& fb);
    // Averages the multisampled copies of the shaded targets into them (PassSet::samples > 1), or their
    // spatial samples (PassSet::spatialSamples > 1: the layers of Framebuffers::sampleLayers()):
    // final_color in linear light, the others as they are.
    void resolveSamples(const PassSet& passes, const Framebuffers& fb);
    // Starts timing `pass` and binds `fbo` at the framebuffers' size with the given depth test and writes.
    void beginPass(Pass pass, unsigned fbo, const Framebuffers& fb, unsigned depthFunc, bool depthWrite);
    // Clears the view's pixels of the bound framebuffer's `targets` to what a background pixel of each
    // modality reads, and with `depth`, its depth to the far plane.
    void clearTargets(const Scene& scene, const Camera& camera, TargetMask targets, bool depth);
    // What clearTargets() writes, by draw-buffer location.
    static std::vector<std::array<float, 4>> clearValues(const Scene& scene, const Camera& camera,
                                                         TargetMask targets);
    // Clears all of the bound framebuffer's `targets` to `values` (and its depth with `depth`).
    // `compact`: they are compact targets (PassSet::compactTargets), given the encoded values.
    static void clearBound(TargetMask targets, const std::vector<std::array<float, 4>>& values, bool depth,
                           bool compact);
    // Clears the surface targets of the pages of shared framebuffers that `views` redraw whole; returns them.
    std::set<const Framebuffers*> clearPages(std::span<const View> views);
    // Sets the colour write masks of `targets`' draw buffers: off for those in `masked`, on for the others.
    static void maskTargets(TargetMask targets, TargetMask masked);
    // The compute lighting pass of a view whose surface pass wrote the G-buffer (PassSet::computeLighting()).
    void lightInCompute(const Camera& camera, const PassSet& passes, const shaders::ShadingLayout& lights,
                        const Framebuffers& fb);
    void drawAll(const Scene& scene, const Camera& camera, const std::vector<Draw>& draws, TargetMask targets,
                 bool shade, const shaders::ShadingLayout& lights, GpuSceneCache& cache);
    // Writes the vignetted background into final_color (one of `targets`) where no surface was drawn.
    void drawVignettedBackground(TargetMask targets, ToneMap toneMap);
    // Draws a triangle covering the view on the far plane with the bound program, into the draw buffers of
    // `written` (among `targets`, the bound framebuffer's) and only where no surface was drawn.
    void drawOnFarPlane(TargetMask targets, TargetMask written);
    // Writes the environment map seen along each pixel's ray into hdr_color, specular_residual and
    // final_color (those of `targets`) where no surface was drawn.
    void drawEnvironmentBackground(const Camera& camera, const Framebuffers& fb, TargetMask targets,
                                   ToneMap toneMap);

    const GlContext& context_;
    std::map<std::string, std::unique_ptr<ShaderProgram>> programs_; // by variant key
    // The screen-space ambient occlusion's textures, by view size (views are drawn one after the other).
    std::map<std::pair<int, int>, std::unique_ptr<ScreenOcclusion>> screenOcclusion_;
    std::unique_ptr<ShaderProgram> shadow_;
    std::unique_ptr<ShaderProgram> idChannel_[2]; // by layered; made at the first id readback
    bool packIdsOnGpu_ = true;
    int maxSamples_ = 1;
    bool stagedReadback_ = false;
    bool computeLighting_ = false;
    bool vertexIrradiance_ = false;
    bool vertexProbeImages_ = false; // the driver allows image loads in vertex shaders
    double viewRefineSpacing_ = 0.0; // the probe spacing the view's meshes are subdivided to; 0: none
    bool derivesOnCpu_ = false;
    bool compactTargets_ = false;
    int readbackThreads_ = 1;
    int constantSlots_ = 0;
    bool adaptiveConstantSlots_ = true;
    int viewConstantSlots_ = 0; // of the view render() is drawing (viewConstantSlots())
    bool shadowReach_ = false;
    bool facingFromWinding_ = true;
    bool warnedLightsLeftOut_ = false;
    std::unique_ptr<SharedUploads> sharedUploads_; // meshes and textures the scenes add under shared keys
    std::unique_ptr<ShadowLayers> shadowLayers_;   // the scenes' shadow maps (before scenes_: they use it)
    std::map<std::uint64_t, std::unique_ptr<SceneState>> scenes_; // by Scene::uid()
    SceneState* active_ = nullptr;                                // the scene render() is drawing
    int viewLayer_ = -1;         // the layer of the view render() is drawing (-1: framebuffers of its own)
    int viewSpatialSamples_ = 1; // the view's spatial samples (PassSet::spatialSamples), for the frame block
    bool viewCompact_ = false;   // its targets are compact (PassSet::compactTargets)
    std::vector<DrawMaterial>* viewMaterials_ = nullptr; // its View::materials
    bool pageCleared_ = false; // its surface targets were cleared with its page (clearPages())
    std::unique_ptr<FramebufferAtlas> atlas_;
    std::unique_ptr<InstanceBuffer> instances_; // the surface passes' instance records
    std::vector<InstanceRecord> records_;       // scratch for them
    std::vector<ShadowReach> parts_; // the rectangles of the draws in parts, of the last visibleDraws()
    unsigned frameBlock_ = 0;
    unsigned emptyVao_ = 0; // bound for draws whose vertices come from gl_VertexID alone
    // The material textures' sampler (anisotropicFiltering()), bound with them for every draw: their only
    // filtering and wrapping (texture units 0-2 hold nothing else).
    unsigned textureSampler_ = 0;
    bool anisotropySupported_ = false;
    bool anisotropicFiltering_ = false;
    bool shaderAnisotropy_ = false;
    bool anisotropyRefusalLogged_ = false;
};

} // namespace sp::render
