#include "core/render/renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/render/framebuffer_atlas.h"
#include "core/render/framebuffers.h"
#include "core/render/gpu_scene_cache.h"
#include "core/render/image_buffer.h"
#include "core/render/instances.h"
#include "core/render/parallel_copy.h"
#include "core/render/screen_occlusion.h"
#include "core/render/shader_program.h"
#include "core/render/shaders.h"
#include "core/render/shadow_layers.h"
#include "core/render/shadow_maps.h"
#include "core/render/tone.h"

namespace sp::render {
namespace {

// final_color of a background pixel, RGBA.
std::array<float, 4> backgroundFinal(const Environment& environment, const CameraParams& params) {
    return {toneMapChannel(environment.background.x(), 0, params),
            toneMapChannel(environment.background.y(), 1, params),
            toneMapChannel(environment.background.z(), 2, params), 1.0f};
}

void copy3(float (&out)[4], const Eigen::Vector3f& v, float w) {
    out[0] = v.x();
    out[1] = v.y();
    out[2] = v.z();
    out[3] = w;
}

// Whether a surface pass writing `targets` leaves its shading to the compute pass: where it was planned
// (Renderer::planComputeLighting()) and the irradiance is not blended at the vertices, which a compute pass
// has none of (then every fragment shades, as without it).
bool lightsInCompute(TargetMask targets, const shaders::ShadingLayout& lights) {
    return (targets & targetBit(Target::GBuffer)) != 0 &&
           lights.irradiance != shaders::IrradianceBlend::PerVertex;
}
// The targets the compute lighting pass stores (Renderer::planComputeLighting()).
constexpr TargetMask kComputeLit = targetBit(Target::FinalColor) | targetBit(Target::Hdr);

// An on/off setting: `variable`'s value, `on` or `off`, or `byDefault` when it is not set; anything else
// throws sp::InvalidArgument naming the variable and the value.
bool switchFromEnvironment(const char* variable, const char* on, const char* off, bool byDefault) {
    const char* env = std::getenv(variable);
    if (env == nullptr)
        return byDefault;
    const std::string value = env;
    SP_CHECK(value == on || value == off, InvalidArgument, "Renderer::Renderer(): ", variable, " must be '",
             on, "' or '", off, "', got '", value, "'");
    return value == on;
}

} // namespace

struct Renderer::Draw {
    const Instance* instance;
    MeshId mesh; // the level of detail drawn
    std::size_t slot;
    unsigned features;                                // shaders::MaterialFeature bits: which program draws it
    double distance;                                  // from the eye to the instance's bounding sphere
    bool holdsEye;                                    // the bounding sphere holds the eye (a floor, a room)
    std::array<std::optional<TextureId>, 3> textures; // base colour, roughness-metallic, normal
    ShadowReach::Kind reach = ShadowReach::Kind::Whole; // which shaded programs draw it, and where
    std::size_t part = 0;                               // Part: its rectangles, in Renderer::parts_; else 0
    // Draws of one batch are drawn by one instanced call: same program, mesh, submesh and textures (and
    // whether they hold the eye, so that floors still go last); a draw in parts is a batch of its own.
    // Numbered in visibleDraws().
    std::size_t batch = 0;
    int refine = 0; // subdivisions of the mesh drawn (per-vertex indirect light: Renderer::refineLevel())
    // How far the level drawn may lie inside the full mesh the shadow maps hold, in metres
    // (MeshLod::surfaceError): its shadow lookups are offset that much more, or it would shadow itself.
    float shadowSlack = 0.0f;
};

Renderer::Renderer(const GlContext& context)
    : context_(context), packIdsOnGpu_(!context.report().software), shadowReach_(context.report().software) {
    context_.makeCurrent();
    // The GPU paths, on by default where the context is a GPU's (see their setters).
    const bool hardware = !context.report().software;
    stagedReadback_ = switchFromEnvironment("SPEAR_READBACK", "staged", "direct", hardware);
    readbackThreads_ = defaultCopyThreads();
    computeLighting_ = switchFromEnvironment("SPEAR_LIGHTING", "compute", "forward", hardware);
    vertexIrradiance_ = switchFromEnvironment("SPEAR_IRRADIANCE_BLEND", "vertex", "pixel", !hardware);
    GLint vertexImages = 0;
    glGetIntegerv(GL_MAX_VERTEX_IMAGE_UNIFORMS, &vertexImages);
    vertexProbeImages_ = vertexImages > 0;
    derivesOnCpu_ = switchFromEnvironment("SPEAR_DERIVED_MODALITIES", "cpu", "rendered", !hardware);
    compactTargets_ = switchFromEnvironment("SPEAR_TARGET_FORMATS", "compact", "float", !hardware);
    GLint samples = 1, colorSamples = 1, depthSamples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &samples);
    glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &colorSamples);
    glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &depthSamples);
    maxSamples_ = std::max(1, std::min({samples, colorSamples, depthSamples}));
    if (context.report().software) {
        // What the surface programs' own varyings leave of the smaller of the two limits (see
        // shaders::ShadingLayout::constantSlots), in vec4s: 8 per-vertex and per-instance varyings and up to
        // one light-space position per projected shadow map; one more is kept back for gl_Position, which
        // some drivers count among the outputs.
        GLint vertexOutputs = 0, fragmentInputs = 0;
        glGetIntegerv(GL_MAX_VERTEX_OUTPUT_COMPONENTS, &vertexOutputs);
        glGetIntegerv(GL_MAX_FRAGMENT_INPUT_COMPONENTS, &fragmentInputs);
        constantSlots_ = std::max(0, std::min(vertexOutputs, fragmentInputs) / 4 - 8 -
                                         shaders::kMaxProjectedShadowMaps - 1);
    }
    // Where the driver can choose the layer in the vertex shader, the shadow maps of every scene are drawn in
    // one layered framebuffer (shadow_layers.h) and small views share layered ones (framebuffer_atlas.h).
    const bool layered = epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array");
    setLayeredShadowMaps(layered);
    instances_ = std::make_unique<InstanceBuffer>();
    sharedUploads_ = std::make_unique<SharedUploads>();
    glCreateBuffers(1, &frameBlock_);
    glNamedBufferData(frameBlock_, sizeof(shaders::FrameBlock), nullptr, GL_DYNAMIC_DRAW);
    glCreateVertexArrays(1, &emptyVao_);
    anisotropySupported_ = epoxy_gl_version() >= 46 ||
                           epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
                           epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic");
    shaderAnisotropy_ =
        switchFromEnvironment("SPEAR_ANISOTROPY", "shader", "sampler", !hardware || !anisotropySupported_);
    setAnisotropicFiltering(switchFromEnvironment("SPEAR_TEXTURE_FILTER", "anisotropic", "trilinear", true));
    atlas_ = std::make_unique<FramebufferAtlas>(layered);
    // Readbacks of 3-channel and 16-bit images have rows that are not multiples of 4 bytes.
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

bool Renderer::layeredShadowMaps() const {
    return shadowLayers_->layered();
}

void Renderer::setLayeredShadowMaps(bool on) {
    context_.makeCurrent();
    scenes_.clear(); // their maps live in the layers
    active_ = nullptr;
    shadowLayers_ = std::make_unique<ShadowLayers>(on);
    shadow_ = std::make_unique<ShaderProgram>("shadow", shaders::shadowVertex(on).c_str(),
                                              shaders::kShadowFragment);
}

ShaderProgram& Renderer::idChannelProgram(bool layered) {
    std::unique_ptr<ShaderProgram>& program = idChannel_[layered ? 1 : 0];
    if (!program)
        program = std::make_unique<ShaderProgram>("id channel", shaders::idChannelCompute(layered).c_str());
    return *program;
}

Renderer::~Renderer() {
    context_.makeCurrent();
    scenes_.clear();
    glDeleteBuffers(1, &frameBlock_);
    glDeleteVertexArrays(1, &emptyVao_);
    glDeleteSamplers(1, &textureSampler_);
}

void Renderer::setShaderAnisotropy(bool on) {
    SP_CHECK(on || anisotropySupported_ || !anisotropicFiltering_, InvalidArgument,
             "Renderer::setShaderAnisotropy(): this context's sampler has no anisotropic filtering "
             "(GL 4.6 or GL_ARB_texture_filter_anisotropic) to take over from the shader");
    shaderAnisotropy_ = on;
    setAnisotropicFiltering(anisotropicFiltering_); // the sampler's default follows
}

int Renderer::viewAnisotropy(const Camera& camera) const {
    if (camera.params.maxAnisotropy > 0)
        return camera.params.maxAnisotropy;
    if (!anisotropicFiltering_)
        return 1;
    return shaderAnisotropy_ ? kShaderAnisotropy : int(kMaxAnisotropy);
}

int Renderer::shaderTextureTaps(const Camera& camera) const {
    return shaderAnisotropy_ ? viewAnisotropy(camera) : 1;
}

void Renderer::setAnisotropicFiltering(bool on) {
    SP_CHECK(!on || anisotropySupported_ || shaderAnisotropy_, InvalidArgument,
             "Renderer::setAnisotropicFiltering(): this context has no anisotropic filtering "
             "(GL 4.6 or GL_ARB_texture_filter_anisotropic)");
    context_.makeCurrent();
    if (textureSampler_ == 0) {
        glCreateSamplers(1, &textureSampler_);
        glSamplerParameteri(textureSampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glSamplerParameteri(textureSampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glSamplerParameteri(textureSampler_, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glSamplerParameteri(textureSampler_, GL_TEXTURE_WRAP_T, GL_REPEAT);
    }
    if (anisotropySupported_)
        glSamplerParameterf(textureSampler_, GL_TEXTURE_MAX_ANISOTROPY,
                            on && !shaderAnisotropy_ ? kMaxAnisotropy : 1.0f);
    anisotropicFiltering_ = on;
}

Renderer::SceneState::SceneState(SharedUploads& shared, ShadowLayers& layers, std::uint64_t sceneUid)
    : cache(std::make_unique<GpuSceneCache>(shared)),
      shadowMaps(std::make_unique<ShadowMaps>(layers, sceneUid)) {}
Renderer::SceneState::~SceneState() = default;

namespace {

void add(RenderStats& total, const RenderStats& s) {
    total.frames += s.frames;
    total.shadowPasses += s.shadowPasses;
    total.shadowReuses += s.shadowReuses;
    total.surfacePasses += s.surfacePasses;
    total.attributePasses += s.attributePasses;
    total.lightingPasses += s.lightingPasses;
    total.tonemapPasses += s.tonemapPasses;
    total.readbacks += s.readbacks;
    total.meshUploads += s.meshUploads;
    total.textureUploads += s.textureUploads;
    total.drawnInstances += s.drawnInstances;
    total.drawCalls += s.drawCalls;
    total.culledInstances += s.culledInstances;
    total.unshadowedInstances += s.unshadowedInstances;
    total.splitInstances += s.splitInstances;
    total.windingFacedInstances += s.windingFacedInstances;
    total.lightsLeftOut += s.lightsLeftOut;
    total.irradianceUploads += s.irradianceUploads;
    total.environmentUploads += s.environmentUploads;
    total.constantSlotPasses += s.constantSlotPasses;
    total.occlusionPasses += s.occlusionPasses;
    for (std::size_t p = 0; p < kPassCount; ++p) {
        total.passTimes[p].gpuMs += s.passTimes[p].gpuMs;
        total.passTimes[p].cpuMs += s.passTimes[p].cpuMs;
        total.passTimes[p].samples += s.passTimes[p].samples;
    }
}

} // namespace

RenderStats Renderer::stats(std::uint64_t sceneUid) const {
    SceneState* state = findState(sceneUid);
    if (state == nullptr)
        return {};
    state->timers.collect();
    state->stats.passTimes = state->timers.totals();
    return state->stats;
}
RenderStats Renderer::stats() const {
    RenderStats total;
    for (const auto& [uid, state] : scenes_)
        add(total, stats(uid));
    return total;
}
void Renderer::resetStats() {
    for (auto& [uid, state] : scenes_) {
        state->timers.collect();
        state->timers.reset();
        state->stats = RenderStats();
    }
}
void Renderer::releaseScene(const Scene& scene) {
    const auto it = scenes_.find(scene.uid());
    if (it == scenes_.end())
        return;
    if (active_ == it->second.get())
        active_ = nullptr;
    scenes_.erase(it);
    sharedUploads_->prune();
}

Renderer::SceneState& Renderer::stateFor(const Scene& scene) {
    auto& state = scenes_[scene.uid()];
    if (!state)
        state = std::make_unique<SceneState>(*sharedUploads_, *shadowLayers_, scene.uid());
    return *state;
}
Renderer::SceneState* Renderer::findState(std::uint64_t sceneUid) const {
    const auto it = scenes_.find(sceneUid);
    return it == scenes_.end() ? nullptr : it->second.get();
}

void Renderer::beginReadback(std::uint64_t sceneUid) {
    if (SceneState* state = findState(sceneUid)) {
        ++state->stats.readbacks;
        state->timers.begin(Pass::Readback);
    }
}
void Renderer::endReadback(std::uint64_t sceneUid) {
    if (SceneState* state = findState(sceneUid))
        state->timers.end();
}

ShaderProgram& Renderer::surfaceProgram(TargetMask targets, bool forward, unsigned materialFeatures,
                                        const shaders::ShadingLayout& lights) {
    const bool layered = viewLayer_ >= 0;
    const std::string key = std::string(forward ? "forward/" : "surface/") + std::to_string(targets) + "/" +
                            std::to_string(materialFeatures) + "/" +
                            (forward ? lights.key() : "c" + std::to_string(lights.constantSlots)) +
                            (layered ? "/layered" : "") + (viewCompact_ ? "/compact" : "");
    auto& program = programs_[key];
    if (!program)
        program = std::make_unique<ShaderProgram>(
            key,
            shaders::surfaceVertex(forward, lights, layered, (materialFeatures & shaders::kBoxUv) != 0)
                .c_str(),
            shaders::surfaceFragment(targets, forward, materialFeatures, lights, viewCompact_).c_str());
    return *program;
}

void Renderer::render(std::span<const View> views) {
    // The timers of earlier frames that finished; not those of this batch, which are not submitted yet: a
    // software rasteriser answers whether such a query is done by running what is queued.
    for (const View& view : views)
        if (SceneState* state = findState(view.scene->uid()))
            state->timers.collect();
    // Segments of views whose scenes each want one shadow-map resolution: their maps are drawn first, then
    // the views (a scene's maps exist at one resolution at a time).
    std::size_t first = 0;
    while (first < views.size()) {
        std::map<std::uint64_t, int> resolutions; // by scene uid
        std::size_t last = first;
        for (; last < views.size(); ++last) {
            const View& view = views[last];
            view.camera->params.validate("Renderer::render");
            if (!view.passes.shadow)
                continue;
            const auto [it, added] =
                resolutions.try_emplace(view.scene->uid(), view.camera->params.shadowResolution);
            if (!added && it->second != view.camera->params.shadowResolution)
                break;
        }
        const std::span<const View> segment = views.subspan(first, last - first);
        updateShadowMaps(segment);
        const std::set<const Framebuffers*> cleared = clearPages(segment);
        for (const View& view : segment) {
            pageCleared_ = cleared.contains(view.framebuffers);
            renderView(view);
        }
        pageCleared_ = false;
        first = last;
    }
}

std::set<const Framebuffers*> Renderer::clearPages(std::span<const View> views) {
    // A page of shared framebuffers all of whose views are drawn now, to one background, is cleared whole:
    // a clear of every layer costs a software rasteriser little, a drawn clear per layer as much as
    // shading it (see clearTargets()). Another page's views clear their own layers.
    std::map<const Framebuffers*, std::vector<const View*>> pages;
    for (const View& view : views)
        if (view.layer >= 0 && view.passes.surface)
            pages[view.framebuffers].push_back(&view);
    std::set<const Framebuffers*> cleared;
    for (const auto& [fb, list] : pages) {
        if (list.size() != atlas_->heldLayers(*fb))
            continue;
        const View& front = *list.front();
        const TargetMask targets = front.passes.surfaceTargets;
        const std::vector<std::array<float, 4>> values = clearValues(*front.scene, *front.camera, targets);
        if (!std::all_of(list.begin(), list.end(), [&](const View* view) {
                return clearValues(*view->scene, *view->camera, targets) == values;
            }))
            continue;
        glBindFramebuffer(GL_FRAMEBUFFER, fb->surfaceFbo);
        glViewport(0, 0, fb->width, fb->height);
        glDepthMask(GL_TRUE);
        clearBound(targets, values, true, front.passes.compactTargets);
        cleared.insert(fb);
    }
    return cleared;
}

void Renderer::updateShadowMaps(std::span<const View> views) {
    glDisable(GL_CULL_FACE); // two-sided: imported meshes have unreliable winding
    glDisable(GL_BLEND);
    // Each scene once, its directional maps covering what its shadowed views see (see shadow_maps.h).
    std::vector<std::size_t> firsts; // the first shadowed view of each scene, in order
    std::map<std::uint64_t, Sphere> seen;
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View& view = views[i];
        if (!view.passes.shadow)
            continue;
        Sphere sphere;
        view.scene->bounds(sphere.centre, sphere.radius, view.camera->frustumPlanes());
        const auto [it, added] = seen.try_emplace(view.scene->uid(), sphere);
        if (added)
            firsts.push_back(i);
        else
            it->second = united(it->second, sphere);
    }
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View& view = views[i];
        if (!view.passes.shadow)
            continue;
        SceneState& state = stateFor(*view.scene);
        if (!std::binary_search(firsts.begin(), firsts.end(), i)) { // the scene's first view drew them
            state.stats.shadowReuses += state.shadowMaps->infos().empty() ? 0 : 1;
            continue;
        }
        const std::uint64_t meshUploads = state.cache->meshUploads();
        state.timers.begin(Pass::Shadow);
        const std::size_t rendered =
            state.shadowMaps->render(*view.scene, view.camera->params.shadowResolution, *state.cache,
                                     *shadow_, &seen[view.scene->uid()]);
        state.timers.end();
        state.stats.shadowPasses += rendered;
        state.stats.shadowReuses += rendered == 0 && !state.shadowMaps->infos().empty() ? 1 : 0;
        state.stats.meshUploads += state.cache->meshUploads() - meshUploads;
    }
}

void Renderer::renderView(const View& view) {
    const Scene& scene = *view.scene;
    const Camera& camera = *view.camera;
    const PassSet& passes = view.passes;
    Framebuffers& fb = *view.framebuffers;
    active_ = &stateFor(scene);
    GpuSceneCache& cache = *active_->cache;
    const std::uint64_t meshUploads = cache.meshUploads(), textureUploads = cache.textureUploads();
    viewLayer_ = view.layer;
    viewSpatialSamples_ = passes.spatialSamples;
    viewCompact_ = passes.compactTargets;
    viewMaterials_ = view.materials;
    SP_CHECK(camera.params.width == fb.width && camera.params.height == fb.height &&
                 (view.layer < 0 ? fb.layers == 0 : view.layer < fb.layers),
             InvalidArgument, "Renderer::render(): a ", camera.params.width, "x", camera.params.height,
             " view in layer ", view.layer, " of ", fb.width, "x", fb.height, " framebuffers of ", fb.layers,
             " layers");
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    // The view's own texture filtering (CameraParams::maxAnisotropy), else the renderer's: in the sampler, or
    // in the shader (shaderTextureTaps(), through the frame block), the sampler then trilinear. A context
    // without the sampler's filters trilinearly whatever a view asks of it (said once).
    const float anisotropy = shaderAnisotropy_ ? 1.0f : float(viewAnisotropy(camera));
    if (anisotropySupported_)
        glSamplerParameterf(textureSampler_, GL_TEXTURE_MAX_ANISOTROPY, anisotropy);
    else if (anisotropy > 1.0f && !anisotropyRefusalLogged_) {
        anisotropyRefusalLogged_ = true;
        SP_LOG("render: a view asked for anisotropic texture filtering, which this OpenGL context does not ",
               "offer (GL 4.6 or GL_ARB_texture_filter_anisotropic): trilinear");
    }
    glSamplerParameterf(textureSampler_, GL_TEXTURE_LOD_BIAS, camera.params.mipBias);

    // With spatial samples (PassSet::spatialSamples), the shaded targets are drawn once a sample, the pixels
    // moved to its point, into framebuffers of their own, and averaged into these; the exact targets after,
    // unmoved.
    const bool sampled = passes.spatialSamples > 1;

    std::vector<ShadowInfo> shadowInfos;
    if (passes.shadow)
        shadowInfos = active_->shadowMaps->infos();
    // The shading programs are specialised for the lights the view shades (see shaders.h): type, range,
    // shadow layer.
    shaders::ShadingLayout lights;
    lights.constantSlots = constantSlots_;
    viewRefineSpacing_ = 0.0;
    std::vector<ViewLight> shaded;
    if (passes.lighting) {
        shaded = viewLights(scene, camera);
        for (const ViewLight& light : shaded) {
            shaders::LightSlot slot;
            slot.type = light.light->type;
            slot.ranged = light.light->ranged();
            for (const ShadowInfo& info : shadowInfos)
                if (info.lightOrdinal == light.ordinal && slot.shadowLayer < 0)
                    slot.shadowLayer = info.layer; // a point light's first face
            lights.lights.push_back(slot);
        }
        lights.floatShadowMaps = !shadowInfos.empty() && active_->shadowMaps->format() == GL_R32F;
        lights.vignette = camera.params.vignetteIntensity > 0.0f;
        lights.toneMap = camera.params.toneMap;
        if (camera.params.globalIllumination && bindIrradianceVolume(scene)) {
            lights.irradiance =
                vertexIrradiance_ ? shaders::IrradianceBlend::PerVertex : shaders::IrradianceBlend::PerPixel;
            lights.vertexProbeImages = vertexProbeImages_;
            if (vertexIrradiance_)
                viewRefineSpacing_ = scene.irradianceVolume()->spacing;
        }
        lights.environmentMap = bindEnvironment(scene);
        if (camera.params.ambientOcclusionIntensity > 0.0f && (passes.surfaceTargets & kShadedTargets) != 0)
            lights.screenOcclusionScale = ScreenOcclusion::scaleFor(fb.width, fb.height);
        uploadFrameBlock(scene, camera, shadowInfos, shaded);
    }
    if (passes.surface) {
        // Where no shadow can fall, the shading programs skip the lookups (see shadow_reach.h); not with
        // spatial samples, whose pixels are not where the rectangles were found. (The frustum culls for the
        // pixels unmoved: a sample sees at most half a pixel past the image's edge, through its outer
        // pixels.)
        std::optional<ShadowReceivers> receivers;
        if (shadowReach_ && passes.lighting && !shadowInfos.empty() && !sampled)
            receivers.emplace(scene, camera, fb.width, fb.height, shadowInfos);
        const std::vector<Draw> draws = visibleDraws(scene, camera, receivers ? &*receivers : nullptr);
        // The triangles drawn are counted only where there are slots to spend (not on a GPU).
        std::uint64_t triangles = 0;
        if (constantSlots_ > 0 && adaptiveConstantSlots_)
            for (const Draw& draw : draws)
                triangles += (scene.mesh(draw.mesh).submeshes[draw.slot].indexCount / 3) << (2 * draw.refine);
        viewConstantSlots_ = viewConstantSlots(triangles, std::uint64_t(fb.width) * std::uint64_t(fb.height));
        lights.constantSlots = viewConstantSlots_;
        active_->stats.constantSlotPasses += viewConstantSlots_ > 0 ? 1 : 0;
        if (lights.screenOcclusionScale > 0) {
            screenOcclusionPass(scene, camera, draws, lights, cache);
            uploadFrameBlock(scene, camera, shadowInfos, shaded);
        }
        if (sampled) {
            // Each sample stands for 1/N of the pixel: meshes are drawn at the level of detail of a pixel
            // sqrt(N) times smaller, as a view that many times larger draws them (the attribute pass draws
            // the camera's own levels, as without spatial samples).
            const std::uint64_t culled = active_->stats.culledInstances; // counted once a view
            const std::vector<Draw> finer =
                visibleDraws(scene, camera, nullptr, std::sqrt(double(passes.spatialSamples)));
            active_->stats.culledInstances = culled;
            const PassSet samplePasses = spatialSampleSurface(passes);
            const std::span<const Eigen::Vector2d> pattern = spatialSamplePattern(passes.spatialSamples);
            Camera moved = camera;
            // Textures likewise are read log2 sqrt(N) levels finer: else the average of N samples of the
            // pixel's own level blurs the texture twice.
            glSamplerParameterf(textureSampler_, GL_TEXTURE_LOD_BIAS,
                                camera.params.mipBias -
                                    float(0.5 * std::log2(double(passes.spatialSamples))));
            for (int sample = 0; sample < passes.spatialSamples; ++sample) {
                moved.subpixelOffset = pattern[std::size_t(sample)];
                surfacePass(scene, moved, samplePasses, lights, finer, cache, *fb.spatialSampled());
                fb.copySample(sample);
            }
            glSamplerParameterf(textureSampler_, GL_TEXTURE_LOD_BIAS, camera.params.mipBias);
            resolveSamples(passes, fb);
        } else {
            surfacePass(scene, camera, passes, lights, draws, cache, fb);
        }
        if (passes.attributeTargets != 0)
            attributePass(scene, camera, passes, draws, cache, fb);
    }
    active_->stats.lightingPasses += passes.lighting ? 1 : 0;
    active_->stats.tonemapPasses += passes.tonemap ? 1 : 0;
    active_->stats.meshUploads += cache.meshUploads() - meshUploads;
    active_->stats.textureUploads += cache.textureUploads() - textureUploads;
    ++active_->stats.frames;
}

std::vector<Renderer::ViewLight> Renderer::viewLights(const Scene& scene, const Camera& camera) {
    // A light of finite range whose sphere of influence misses the view frustum lights no point the view
    // sees (its windowed falloff is exactly 0 past the range), so it is left out: a house of many rooms
    // shades, in each view, the lights of the rooms it sees.
    const std::array<Eigen::Vector4d, 6> planes = camera.frustumPlanes();
    const Eigen::Vector3d eye = camera.pose.translation();
    std::vector<ViewLight> reaching;
    int ordinal = -1;
    scene.forEachLight([&](LightId, const Light& light) {
        ++ordinal;
        // A margin over the range, for the float arithmetic of the shading.
        const double reach = 1.001 * double(light.range) + 1e-3;
        if (light.ranged() && !Scene::reachesInside(planes, light.position, reach))
            return;
        const double distance = light.ranged() ? std::max(0.0, (light.position - eye).norm() - reach) : -1.0;
        reaching.push_back({&light, ordinal, distance});
    });
    if (reaching.size() <= std::size_t(shaders::kMaxLights))
        return reaching;
    // More than a program shades: the nearest (the unbounded first), in the scene's order.
    const std::size_t reached = reaching.size();
    std::stable_sort(reaching.begin(), reaching.end(),
                     [](const ViewLight& a, const ViewLight& b) { return a.distance < b.distance; });
    reaching.resize(std::size_t(shaders::kMaxLights));
    std::sort(reaching.begin(), reaching.end(),
              [](const ViewLight& a, const ViewLight& b) { return a.ordinal < b.ordinal; });
    active_->stats.lightsLeftOut += reached - reaching.size();
    if (!warnedLightsLeftOut_) {
        warnedLightsLeftOut_ = true;
        SP_LOG("Renderer: a view reaches ", reached, " lights; it shades the ", shaders::kMaxLights,
               " nearest (RenderStats::lightsLeftOut counts the rest)");
    }
    return reaching;
}

bool Renderer::bindIrradianceVolume(const Scene& scene) {
    const IrradianceVolume* volume = scene.irradianceVolume().get();
    if (volume == nullptr)
        return false;
    SceneState& state = *active_;
    if (!state.irradiance || state.irradianceSource != volume ||
        state.irradianceRevision != volume->revision) {
        const std::vector<std::uint32_t> texels = volume->packed();
        const Eigen::Vector3i size(2 * volume->counts.x(), volume->counts.y(), volume->counts.z());
        // A new texture when the size changed (immutable storage), else the texels replaced in place.
        GLint width = 0, height = 0, depth = 0;
        if (state.irradiance) {
            glGetTextureLevelParameteriv(state.irradiance->name, 0, GL_TEXTURE_WIDTH, &width);
            glGetTextureLevelParameteriv(state.irradiance->name, 0, GL_TEXTURE_HEIGHT, &height);
            glGetTextureLevelParameteriv(state.irradiance->name, 0, GL_TEXTURE_DEPTH, &depth);
        }
        if (!state.irradiance || Eigen::Vector3i(width, height, depth) != size) {
            state.irradiance = std::make_unique<GpuTexture>();
            glCreateTextures(GL_TEXTURE_3D, 1, &state.irradiance->name);
            glTextureStorage3D(state.irradiance->name, 1, GL_RGBA32UI, size.x(), size.y(), size.z());
            // Integer texels are fetched, never filtered (a vertex shader's texelFetch needs a complete
            // texture).
            glTextureParameteri(state.irradiance->name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(state.irradiance->name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        glTextureSubImage3D(state.irradiance->name, 0, 0, 0, 0, size.x(), size.y(), size.z(), GL_RGBA_INTEGER,
                            GL_UNSIGNED_INT, texels.data());
        state.irradianceSource = volume;
        state.irradianceRevision = volume->revision;
        ++state.stats.irradianceUploads;
    }
    glBindImageTexture(shaders::kIrradianceImageUnit, state.irradiance->name, 0, GL_TRUE, 0, GL_READ_ONLY,
                       GL_RGBA32UI);
    glBindTextureUnit(shaders::kIrradianceTextureUnit, state.irradiance->name);
    return true;
}

bool Renderer::bindEnvironment(const Scene& scene) {
    const EnvironmentMap* map = scene.environment().map.get();
    if (map == nullptr)
        return false;
    SceneState& state = *active_;
    if (state.environmentUid != map->uid()) {
        // Half floats hold a sky's and a photograph's range (to 65504) at a quarter of a float's bandwidth.
        auto upload = [](GpuTexture& texture, const std::vector<const RadianceImage*>& levels, int storage) {
            glCreateTextures(GL_TEXTURE_2D, 1, &texture.name);
            glTextureStorage2D(texture.name, storage, GL_RGBA16F, levels[0]->width, levels[0]->height);
            std::vector<float> texels;
            for (std::size_t level = 0; level < levels.size(); ++level) {
                const RadianceImage& image = *levels[level];
                texels.resize(image.texels.size() * 4);
                for (std::size_t i = 0; i < image.texels.size(); ++i) {
                    const Eigen::Vector3f c = image.texels[i].cwiseMin(65000.0f);
                    texels[4 * i] = c.x(), texels[4 * i + 1] = c.y(), texels[4 * i + 2] = c.z();
                    texels[4 * i + 3] = 1.0f;
                }
                glTextureSubImage2D(texture.name, GLint(level), 0, 0, image.width, image.height, GL_RGBA,
                                    GL_FLOAT, texels.data());
            }
            // Around the horizon the map wraps; at the poles it stops.
            glTextureParameteri(texture.name, GL_TEXTURE_WRAP_S, GL_REPEAT);
            glTextureParameteri(texture.name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            glTextureParameteri(texture.name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
            glTextureParameteri(texture.name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        };
        std::vector<const RadianceImage*> chain;
        for (const RadianceImage& level : map->specularLevels())
            chain.push_back(&level);
        state.environmentSpecular = std::make_unique<GpuTexture>();
        upload(*state.environmentSpecular, chain, int(chain.size()));
        // The full map with mipmaps, so that a wide map seen by a small image is averaged, not sampled.
        state.environmentBackground = std::make_unique<GpuTexture>();
        upload(*state.environmentBackground, {&map->full()},
               int(std::floor(std::log2(double(map->full().width)))) + 1);
        glGenerateTextureMipmap(state.environmentBackground->name);
        state.environmentUid = map->uid();
        state.environmentBackgroundWidth = map->full().width;
        ++state.stats.environmentUploads;
    }
    glBindTextureUnit(shaders::kEnvironmentSpecularUnit, state.environmentSpecular->name);
    glBindTextureUnit(shaders::kEnvironmentBackgroundUnit, state.environmentBackground->name);
    return true;
}

void Renderer::uploadFrameBlock(const Scene& scene, const Camera& camera,
                                const std::vector<ShadowInfo>& shadows,
                                const std::vector<ViewLight>& lights) {
    shaders::FrameBlock block;
    std::memset(&block, 0, sizeof block);
    copy3(block.cameraPosition, camera.pose.translation().cast<float>(),
          shadows.empty() ? 0.0f : float(active_->shadowMaps->firstLayer()));
    copy3(block.ambient, scene.environment().ambient, 0.0f);
    if (const IrradianceVolume* volume = scene.irradianceVolume().get();
        volume && camera.params.globalIllumination)
        copy3(block.irradianceVolume, volume->origin.cast<float>(), float(1.0 / volume->spacing));
    copy3(block.background, scene.environment().background, 1.0f);
    if (const EnvironmentMap* map = scene.environment().map.get()) {
        for (std::size_t i = 0; i < 9; ++i)
            copy3(block.skyDiffuse[i],
                  map->diffuseCoefficients()[i].cwiseProduct(scene.environment().mapScale), 0.0f);
        copy3(block.environment, scene.environment().mapScale, float(EnvironmentMap::kSpecularLevels - 1));
    }
    copy3(block.exposure, camera.params.exposure * camera.params.whiteBalance, 0.0f);
    block.vignette[0] = camera.params.vignetteIntensity;
    block.vignette[1] = float(camera.focalLengthPixels());
    block.vignette[2] = 0.5f * float(camera.params.width);
    block.vignette[3] = 0.5f * float(camera.params.height);
    const std::array<float, 4> final = backgroundFinal(scene.environment(), camera.params);
    std::copy(final.begin(), final.end(), block.backgroundFinal);
    for (const ShadowInfo& info : shadows) {
        std::memcpy(block.shadowMatrix[info.layer], info.worldToClip.data(), sizeof(float) * 16);
        block.shadowParams[info.layer][0] = info.texel;
        block.shadowParams[info.layer][1] = float(camera.params.shadowResolution);
    }
    int count = 0;
    for (const ViewLight& shaded : lights) {
        const Light& light = *shaded.light;
        copy3(block.lightRadiance[count], light.color * light.intensity, 0.0f);
        copy3(block.lightPosition[count], light.position.cast<float>(),
              light.range > 0.0f ? 1.0f / light.range : 0.0f);
        copy3(block.lightDirection[count], light.direction.normalized().cast<float>(), 0.0f);
        const float cosInner = std::cos(light.innerConeDeg * float(M_PI) / 180.0f);
        const float cosOuter = std::cos(light.outerConeDeg * float(M_PI) / 180.0f);
        block.lightCone[count][0] = cosOuter;
        block.lightCone[count][1] = 1.0f / std::max(cosInner - cosOuter, 1e-4f);
        if (light.type == LightType::Rect) {
            // Radiance and the half extents, the second turned so that their cross product is the direction
            // the panel shines (see rectLight() in shaders.cpp).
            copy3(block.lightRadiance[count], light.color * light.rectRadiance(), 0.0f);
            const Eigen::Vector3d halfRight = light.right * (0.5 * light.width);
            Eigen::Vector3d halfUp = light.up * (0.5 * light.height);
            if (halfRight.cross(halfUp).dot(light.direction) < 0.0)
                halfUp = -halfUp;
            copy3(block.lightDirection[count], halfRight.cast<float>(), 0.0f);
            copy3(block.lightCone[count], halfUp.cast<float>(), 0.0f);
        }
        ++count;
    }
    block.counts[0] = count;
    block.counts[1] = std::max(viewLayer_, 0); // the layer a layered program draws into
    block.counts[2] = shaderTextureTaps(camera);
    block.counts[3] = std::max(viewSpatialSamples_, 1); // each sample's footprint: 1 / sqrt(N) of the pixel's
    glNamedBufferData(frameBlock_, sizeof block, &block, GL_DYNAMIC_DRAW);
    glBindBufferBase(GL_UNIFORM_BUFFER, shaders::kFrameBlockBinding, frameBlock_);
}

void Renderer::screenOcclusionPass(const Scene& scene, const Camera& camera, const std::vector<Draw>& draws,
                                   const shaders::ShadingLayout& lights, GpuSceneCache& cache) {
    std::unique_ptr<ScreenOcclusion>& occlusion =
        screenOcclusion_[{camera.params.width, camera.params.height}];
    if (!occlusion)
        occlusion = std::make_unique<ScreenOcclusion>(camera.params.width, camera.params.height);
    // The same view at the occlusion's resolution, at the pixels' centres, into plain framebuffers of its own
    // (whatever the view's layer and target encoding).
    Camera small = camera;
    small.params.width = occlusion->width();
    small.params.height = occlusion->height();
    small.subpixelOffset = Eigen::Vector2d::Zero();
    const int layer = viewLayer_;
    const bool compact = viewCompact_;
    viewLayer_ = -1;
    viewCompact_ = false;
    const std::uint64_t drawCalls = active_->stats.drawCalls; // those of surface and attribute passes
    active_->timers.begin(Pass::Occlusion);
    glBindFramebuffer(GL_FRAMEBUFFER, occlusion->depthFbo());
    glViewport(0, 0, occlusion->width(), occlusion->height());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const float background[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float far = 1.0f;
    glClearBufferfv(GL_COLOR, 0, background);
    glClearBufferfv(GL_DEPTH, 0, &far);
    uploadFrameBlock(scene, small, {}, {});
    drawAll(scene, small, draws, targetBit(Target::Depth), false, lights, cache);
    const auto program = [&](const char* name, std::string (*fragment)()) -> ShaderProgram& {
        std::unique_ptr<ShaderProgram>& p = programs_[name];
        if (!p)
            p = std::make_unique<ShaderProgram>(name, shaders::backgroundVertex(false).c_str(),
                                                fragment().c_str());
        return *p;
    };
    occlusion->compute(program("screen occlusion", shaders::screenOcclusionFragment),
                       program("screen occlusion blur", shaders::screenOcclusionBlurFragment),
                       float(small.focalLengthPixels()), camera.params.ambientOcclusionRadius,
                       camera.params.ambientOcclusionIntensity);
    active_->timers.end();
    active_->stats.drawCalls = drawCalls;
    ++active_->stats.occlusionPasses;
    viewLayer_ = layer;
    viewCompact_ = compact;
    glBindImageTexture(shaders::kScreenOcclusionUnit, occlusion->texture(), 0, GL_FALSE, 0, GL_READ_ONLY,
                       GL_R8);
}

void Renderer::surfacePass(const Scene& scene, const Camera& camera, const PassSet& passes,
                           const shaders::ShadingLayout& lights, const std::vector<Draw>& draws,
                           GpuSceneCache& cache, Framebuffers& fb) {
    const bool multisampled = passes.samples > 1;
    beginPass(Pass::Surface, multisampled ? fb.multisampleFbo : fb.surfaceFbo, fb, GL_LESS, true);
    if (!passes.lighting) // the material chunk still reads the camera position (and the layer) from it
        uploadFrameBlock(scene, camera, {}, {});
    if (!pageCleared_) // else cleared with its page (clearPages())
        clearTargets(scene, camera, passes.surfaceTargets, true);
    if (passes.lighting && passes.shadow && active_->shadowMaps->texture() != 0)
        glBindImageTexture(shaders::kShadowMapImageUnit, active_->shadowMaps->texture(), 0, GL_TRUE, 0,
                           GL_READ_ONLY, active_->shadowMaps->format());
    drawAll(scene, camera, draws, passes.surfaceTargets, passes.lighting, lights, cache);
    if (lightsInCompute(passes.surfaceTargets, lights))
        lightInCompute(camera, passes, lights, fb);
    else if (lights.environmentMap)
        drawEnvironmentBackground(camera, fb, passes.surfaceTargets, lights.toneMap);
    else if (lights.vignette && (passes.surfaceTargets & targetBit(Target::FinalColor)) != 0)
        drawVignettedBackground(passes.surfaceTargets, lights.toneMap);
    if (multisampled)
        resolveSamples(passes, fb);
    active_->timers.end();
    ++active_->stats.surfacePasses;
}

void Renderer::resolveSamples(const PassSet& passes, const Framebuffers& fb) {
    const int layers = passes.spatialSamples;
    auto& program =
        programs_["resolve/" + std::to_string(passes.surfaceTargets) + "/" +
                  (layers > 1 ? "layers " + std::to_string(layers) : std::to_string(passes.samples))];
    if (!program)
        program = std::make_unique<ShaderProgram>(
            "resolve", shaders::backgroundVertex(false).c_str(),
            shaders::resolveFragment(passes.surfaceTargets, passes.samples, layers).c_str());
    program->use();
    int unit = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t)
        if ((passes.surfaceTargets & (TargetMask(1) << t)) != 0) {
            const Target target = static_cast<Target>(t);
            glBindTextureUnit(GLuint(shaders::kResolveTextureUnit + unit++),
                              layers > 1 ? fb.sampleLayers(target) : fb.multisampleTexture(target));
        }
    glBindFramebuffer(GL_FRAMEBUFFER, fb.surfaceFbo);
    glViewport(0, 0, fb.width, fb.height);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
}

void Renderer::drawVignettedBackground(TargetMask targets, ToneMap toneMap) {
    // The cleared background of final_color is one colour; vignetted, it varies by pixel, so it is drawn
    // where the surfaces left the far plane, into final_color alone.
    int location = 0, count = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t)
        if ((targets & (TargetMask(1) << t)) != 0) {
            if (static_cast<Target>(t) == Target::FinalColor)
                location = count;
            ++count;
        }
    const bool layered = viewLayer_ >= 0;
    auto& program = programs_["background/" + std::to_string(location) + "/" +
                              std::to_string(static_cast<int>(toneMap)) + (layered ? "/layered" : "")];
    if (!program)
        program = std::make_unique<ShaderProgram>("background", shaders::backgroundVertex(layered).c_str(),
                                                  shaders::backgroundFragment(location, toneMap).c_str());
    program->use();
    drawOnFarPlane(targets, targetBit(Target::FinalColor));
}

void Renderer::drawOnFarPlane(TargetMask targets, TargetMask written) {
    maskTargets(targets, targets & ~written);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    maskTargets(targets, 0);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
}

namespace {

// Clip space to the world position relative to the camera, composed in double precision: the inverse of the
// projection (flipped as drawn) times the camera's rotation.
Eigen::Matrix4f clipToOffset(const Camera& camera) {
    Eigen::Matrix4d view = camera.viewMatrix();
    view.block<3, 1>(0, 3).setZero();
    return (camera.projectionMatrix(true) * view).inverse().cast<float>();
}

// The level of the background texture whose texels are about a pixel wide at the image's centre.
float backgroundLod(const Camera& camera, int mapWidth) {
    const double texelsPerRadian = double(mapWidth) / (2.0 * 3.14159265358979);
    return float(std::max(0.0, std::log2(texelsPerRadian / camera.focalLengthPixels())));
}

} // namespace

void Renderer::drawEnvironmentBackground(const Camera& camera, const Framebuffers& fb, TargetMask targets,
                                         ToneMap toneMap) {
    constexpr TargetMask kBackgroundTargets =
        targetBit(Target::Hdr) | targetBit(Target::SpecularResidual) | targetBit(Target::FinalColor);
    if ((targets & kBackgroundTargets) == 0)
        return;
    const bool layered = viewLayer_ >= 0;
    auto& program = programs_["environment background/" + std::to_string(targets) + "/" +
                              std::to_string(static_cast<int>(toneMap)) + (viewCompact_ ? "/compact" : "") +
                              (layered ? "/layered" : "")];
    if (!program)
        program = std::make_unique<ShaderProgram>(
            "environment background", shaders::backgroundVertex(layered).c_str(),
            shaders::environmentBackgroundFragment(targets, toneMap, viewCompact_).c_str());
    program->use();
    program->set("uClipToOffset", clipToOffset(camera));
    glProgramUniform2i(program->id(), program->location("uSize"), fb.width, fb.height);
    glProgramUniform1f(program->id(), program->location("uBackgroundLod"),
                       backgroundLod(camera, active_->environmentBackgroundWidth));
    drawOnFarPlane(targets, targets & kBackgroundTargets);
}

void Renderer::attributePass(const Scene& scene, const Camera& camera, const PassSet& passes,
                             const std::vector<Draw>& draws, GpuSceneCache& cache, Framebuffers& fb) {
    shaders::ShadingLayout constantsOnly; // no shading: the camera position alone
    constantsOnly.constantSlots = viewConstantSlots_;
    if (passes.samples > 1 || passes.spatialSamples > 1) {
        // The surface pass drew multisampled or moved: the exact targets are drawn as a surface pass that
        // shades nothing draws them, with a single-sampled depth buffer of their own.
        beginPass(Pass::Attribute, fb.attributeFbo, fb, GL_LESS, true);
        clearTargets(scene, camera, passes.attributeTargets, true);
        drawAll(scene, camera, draws, passes.attributeTargets, false, constantsOnly, cache);
        active_->timers.end();
        ++active_->stats.attributePasses;
        return;
    }
    // The surface pass's depth, kept: a fragment passes only where it is the one the surface pass left. Where
    // surfaces tie (coincident instances), every tied fragment passes and the last drawn stays, while the
    // surface pass (GL_LESS) kept the first drawn: drawn in reverse order, the last here is the first there.
    beginPass(Pass::Attribute, fb.attributeFbo, fb, GL_LEQUAL, false);
    clearTargets(scene, camera, passes.attributeTargets, false);
    const std::vector<Draw> reversed(draws.rbegin(), draws.rend());
    drawAll(scene, camera, reversed, passes.attributeTargets, false, constantsOnly, cache);
    glDepthMask(GL_TRUE);
    active_->timers.end();
    ++active_->stats.attributePasses;
}

void Renderer::beginPass(Pass pass, unsigned fbo, const Framebuffers& fb, unsigned depthFunc,
                         bool depthWrite) {
    active_->timers.begin(pass);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, fb.width, fb.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depthFunc);
    glDepthMask(depthWrite ? GL_TRUE : GL_FALSE);
}

std::vector<std::array<float, 4>> Renderer::clearValues(const Scene& scene, const Camera& camera,
                                                        TargetMask targets) {
    // What a background pixel of each modality reads.
    const Eigen::Vector3f background = scene.environment().background;
    std::vector<std::array<float, 4>> values; // by location
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((targets & (TargetMask(1) << t)) == 0)
            continue;
        const auto target = static_cast<Target>(t);
        float value[4] = {0, 0, 0, 0};
        if (target == Target::Hdr || target == Target::SpecularResidual) { // the background is all residual
            copy3(value, background, 1.0f);
        } else if (target == Target::FinalColor) {
            const std::array<float, 4> final = backgroundFinal(scene.environment(), camera.params);
            std::copy(final.begin(), final.end(), value);
        }
        values.push_back({value[0], value[1], value[2], value[3]});
    }
    return values;
}

void Renderer::clearBound(TargetMask targets, const std::vector<std::array<float, 4>>& values, bool depth,
                          bool compact) {
    int location = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((targets & (TargetMask(1) << t)) == 0)
            continue;
        const GLuint zero[4] = {0, 0, 0, 0};
        const auto target = static_cast<Target>(t);
        const std::array<float, 4>& value = values[std::size_t(location)];
        if (target == Target::Ids || target == Target::Record) {
            glClearBufferuiv(GL_COLOR, location, zero);
        } else if (compact && (kHalfTargets & targetBit(target)) != 0) {
            const GLuint bits[4] = {floatToHalf(value[0]), floatToHalf(value[1]), floatToHalf(value[2]),
                                    floatToHalf(value[3])};
            glClearBufferuiv(GL_COLOR, location, bits);
        } else if (compact && target == Target::Normal) {
            const GLfloat none[4] = {kNoOctahedralNormal, kNoOctahedralNormal, 0, 0};
            glClearBufferfv(GL_COLOR, location, none);
        } else if (target != Target::GBuffer && target != Target::GBufferMaterial) {
            // (The G-buffer is read only where the depth buffer holds a surface: not cleared.)
            glClearBufferfv(GL_COLOR, location, value.data());
        }
        ++location;
    }
    if (depth)
        glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

void Renderer::clearTargets(const Scene& scene, const Camera& camera, TargetMask targets, bool depth) {
    const std::vector<std::array<float, 4>> values = clearValues(scene, camera, targets);
    if (viewLayer_ < 0) {
        clearBound(targets, values, depth, viewCompact_);
        return;
    }
    if (values.empty() && !depth)
        return;
    // A clear of layered framebuffers clears every layer: the view's layer is drawn instead, by a triangle
    // covering it on the far plane (depth 1, as a clear leaves it).
    auto& program = programs_["clear/" + std::to_string(targets) + (viewCompact_ ? "/compact" : "")];
    if (!program)
        program = std::make_unique<ShaderProgram>("clear", shaders::backgroundVertex(true).c_str(),
                                                  shaders::clearFragment(targets, viewCompact_).c_str());
    program->use();
    if (!values.empty())
        glProgramUniform4fv(program->id(), program->location("uClear"), GLsizei(values.size()),
                            values.front().data());
    GLint depthFunc = GL_LESS;
    GLboolean depthWrite = GL_TRUE;
    glGetIntegerv(GL_DEPTH_FUNC, &depthFunc);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthWrite);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(depth ? GL_TRUE : GL_FALSE);
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDepthFunc(GLenum(depthFunc));
    glDepthMask(depthWrite);
}

int Renderer::refineLevel(double edge, double spacing, std::size_t triangles) {
    int level = 0;
    while (level < kMaxRefine && edge > 2.0 * spacing && triangles * 4 <= 65536) {
        edge *= 0.5;
        triangles *= 4;
        ++level;
    }
    return level;
}

std::vector<Renderer::Draw> Renderer::visibleDraws(const Scene& scene, const Camera& camera,
                                                   const ShadowReceivers* receivers, double detail) {
    const std::array<Eigen::Vector4d, 6> planes = camera.frustumPlanes();
    const Eigen::Vector3d eye = camera.pose.translation();
    const double focal = camera.focalLengthPixels() * detail;

    // Cull against the view frustum (bounding spheres); then draw each program's submeshes front to back.
    std::vector<Draw> draws;
    std::size_t drawn = 0;
    parts_.clear();
    scene.forEachInstance([&](InstanceId, const Instance& instance) {
        if (!instance.visible)
            return;
        Eigen::Vector3d centre;
        double radius = 0.0;
        scene.boundingSphere(instance, centre, radius);
        if (!Scene::reachesInside(planes, centre, radius)) {
            ++active_->stats.culledInstances;
            return;
        }
        ++drawn;
        // Front to back, so hidden fragments fail the early depth test; an instance whose bounds hold the
        // eye (a floor, a room's walls) goes last: it is behind most of what is in front of the camera.
        const double centreDistance = (centre - eye).norm();
        const double distance = centreDistance > radius ? centreDistance - radius
                                                        : std::numeric_limits<double>::max() / 2 - radius;
        const double nearest = std::max(centreDistance - radius, camera.params.nearClip);
        const MeshLod lod = scene.chooseLod(instance.mesh, radius * focal / nearest);
        const MeshId mesh = lod.mesh;
        const bool facing = facingFromWinding_ &&
                            windingTurnsNormals(scene.meshWindingSpread(mesh), instance.transform.linear());
        ShadowReach reach;
        if (receivers != nullptr)
            reach = receivers->reach(scene, instance);
        const ShadowReach::Kind kind = reach.kind; // read before its rectangles move to parts_
        active_->stats.unshadowedInstances += kind == ShadowReach::Kind::None ? 1 : 0;
        active_->stats.splitInstances += kind == ShadowReach::Kind::Part ? 1 : 0;
        std::size_t part = 0;
        if (kind == ShadowReach::Kind::Part) {
            part = parts_.size();
            parts_.push_back(std::move(reach));
        }
        int refine = 0;
        if (viewRefineSpacing_ > 0.0) {
            const Eigen::Matrix3d linear = instance.transform.linear();
            const double scale = linear.colwise().norm().maxCoeff();
            refine = refineLevel(double(scene.meshLongestEdge(mesh)) * scale, viewRefineSpacing_,
                                 scene.mesh(mesh).indices.size() / 3);
        }
        bool windingFaced = false;
        for (std::size_t slot = 0; slot < instance.materials.size(); ++slot) {
            const Material& material = scene.material(instance.materials[slot]);
            const unsigned features =
                (material.baseColorTexture ? shaders::kBaseColorTexture : 0u) |
                (material.roughnessMetallicTexture ? shaders::kRoughnessMetallicTexture : 0u) |
                (material.normalTexture ? shaders::kNormalTexture
                 : facing               ? shaders::kFacingFromWinding
                                        : 0u) |
                (material.boxUv() ? shaders::kBoxUv : 0u);
            windingFaced = windingFaced || (features & shaders::kFacingFromWinding) != 0;
            draws.push_back(
                {&instance,
                 mesh,
                 slot,
                 features,
                 distance,
                 centreDistance <= radius,
                 {material.baseColorTexture, material.roughnessMetallicTexture, material.normalTexture},
                 kind,
                 part});
            draws.back().refine = refine;
            draws.back().shadowSlack = float(lod.surfaceError * radius);
        }
        active_->stats.windingFacedInstances += windingFaced ? 1 : 0;
    });
    // Front to back, whatever their programs; then each draw joins the batch of the nearest draw it batches
    // with, so a batch is drawn where its nearest member was (still roughly front to back), its members front
    // to back. (Grouping by program first drew an untextured floor before every textured object on it, and
    // shaded its hidden fragments: on llvmpipe, 64 textured boxes at 1080p took 36.0-38.5 ms a frame, now
    // 28.7-31.5 ms.)
    std::sort(draws.begin(), draws.end(), [](const Draw& a, const Draw& b) {
        return a.distance != b.distance ? a.distance < b.distance : a.features < b.features;
    });
    // Batches numbered in order of their nearest draw, through a map of what a batch shares (a scene of many
    // distinct meshes has many batches).
    using BatchKey = std::tuple<unsigned, MeshId, std::size_t, bool, std::array<std::optional<TextureId>, 3>,
                                ShadowReach::Kind, std::size_t, int>;
    std::map<BatchKey, std::size_t> batches;
    for (Draw& draw : draws)
        draw.batch = batches
                         .try_emplace({draw.features, draw.mesh, draw.slot, draw.holdsEye, draw.textures,
                                       draw.reach, draw.part, draw.refine},
                                      batches.size())
                         .first->second;
    std::stable_sort(draws.begin(), draws.end(),
                     [](const Draw& a, const Draw& b) { return a.batch < b.batch; });
    active_->stats.drawnInstances += drawn;
    return draws;
}

void Renderer::drawAll(const Scene& scene, const Camera& camera, const std::vector<Draw>& draws,
                       TargetMask targets, bool shade, const shaders::ShadingLayout& lights,
                       GpuSceneCache& cache) {
    // The projection is flipped vertically so that GL's bottom row holds image row 0 and glReadPixels
    // returns the top image row first; depth and ids are unaffected.
    const Eigen::Matrix4d worldToCamera = camera.pose.inverse(Eigen::Isometry).matrix();
    const Eigen::Matrix4d viewProjection = camera.projectionMatrix(true) * camera.viewMatrix();
    records_.resize(draws.size());
    for (std::size_t i = 0; i < draws.size(); ++i) {
        const Draw& draw = draws[i];
        const Instance& instance = *draw.instance;
        const Eigen::Matrix4d model = instance.transform.matrix();
        InstanceRecord& record = records_[i];
        record.setModelViewProjection(viewProjection * model);
        record.setModel(model, worldToCamera * model);
        const MaterialId materialId = instance.materials[draw.slot];
        const Material& material = scene.material(materialId);
        std::copy(material.baseColor.data(), material.baseColor.data() + 4, record.baseColor);
        record.material[0] = material.roughness;
        record.material[1] = material.metallic;
        record.material[2] = material.ambientOcclusion;
        record.material[3] = material.textureSize > 0.0f ? 1.0f / material.textureSize : 0.0f;
        std::copy(material.emissive.data(), material.emissive.data() + 3, record.emissive);
        record.emissive[3] = draw.shadowSlack;
        record.ids[0] = instance.objectIds[draw.slot];
        record.ids[1] = scene.materialIdValue(materialId);
        record.ids[2] = std::uint32_t(i); // the G-buffer's name for the draw (compute lighting)
        // Bit 0: the material is textured, so its pixels' factors are in Target::GBufferMaterial.
        record.ids[3] = (draw.features & shaders::kTextureFeatures) != 0 ? 1u : 0u;
    }
    instances_->upload(records_);
    // What Target::Record's pixels name: each draw's ids and untextured material factors, rounded as the
    // float16 targets round them.
    if (viewMaterials_ != nullptr && (targets & targetBit(Target::Record)) != 0) {
        viewMaterials_->resize(draws.size());
        for (std::size_t i = 0; i < draws.size(); ++i) {
            const InstanceRecord& record = records_[i];
            DrawMaterial& m = (*viewMaterials_)[i];
            m.objectId = record.ids[0];
            m.materialId = record.ids[1];
            for (int c = 0; c < 3; ++c)
                m.baseColor[c] = floatToHalf(record.baseColor[c]);
            m.roughness = floatToHalf(record.material[0]);
            m.metallic = floatToHalf(record.material[1]);
            m.ambientOcclusion = floatToHalf(record.material[2]);
        }
    }

    // What the shaded programs draw where no shadow falls: the same lights, no shadow-map lookups.
    shaders::ShadingLayout unshadowed = lights;
    for (shaders::LightSlot& light : unshadowed.lights)
        light.shadowLayer = -1;
    unshadowed.floatShadowMaps = false;

    // One instanced draw call per batch (consecutive draws of one batch: see visibleDraws()), or for a
    // batch in parts one per rectangle, scissored.
    // The program is looked up (its key composed) only when the features or the lookups change.
    std::optional<std::tuple<unsigned, bool, bool>> current;
    // With compute lighting, a material writes the G-buffer (a textured one its factors at the pixel in the
    // material target as well) and leaves the shaded targets to the compute pass (masked here, so that
    // nothing is stored for them); a batch past the records the G-buffer can name, or a textured one when the
    // pass had no room for the material target, is shaded here. A target a draw does not write is masked too:
    // an unassigned output is undefined, and storing it costs as much as a real one.
    const bool computeLighting = lightsInCompute(targets, lights);
    const bool materialTarget = (targets & targetBit(Target::GBufferMaterial)) != 0;
    TargetMask masked = 0;
    const auto use = [&](unsigned features, bool lookups, bool named) {
        const bool textured = (features & shaders::kTextureFeatures) != 0;
        const bool deferred = computeLighting && named && (!textured || materialTarget);
        if (current == std::tuple(features, lookups, deferred))
            return;
        surfaceProgram(targets, shade && !deferred, features, lookups ? lights : unshadowed).use();
        current = std::tuple(features, lookups, deferred);
        const TargetMask mask = (deferred ? targets & kComputeLit : 0) |
                                (deferred && textured ? 0 : targets & targetBit(Target::GBufferMaterial));
        if (mask != masked) {
            maskTargets(targets, mask);
            masked = mask;
        }
    };
    for (std::size_t first = 0, last = 0; first < draws.size(); first = last) {
        const Draw& draw = draws[first];
        for (last = first + 1; last < draws.size() && draws[last].batch == draw.batch;)
            ++last;
        const GpuMesh& mesh =
            draw.refine > 0 ? cache.refined(scene, draw.mesh, draw.refine) : cache.mesh(scene, draw.mesh);
        instances_->bind(mesh.vao);
        glBindVertexArray(mesh.vao);
        for (int t = 0; t < 3; ++t)
            if (draw.textures[std::size_t(t)]) {
                glBindTextureUnit(GLuint(t), cache.texture(scene, *draw.textures[std::size_t(t)]));
                glBindSampler(GLuint(t), textureSampler_);
            }
        const Submesh& sub = mesh.submeshes[draw.slot];
        const auto drawBatch = [&] {
            glDrawElementsInstancedBaseInstance(
                GL_TRIANGLES, GLsizei(sub.indexCount), GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(std::uintptr_t(sub.firstIndex) * 4), GLsizei(last - first),
                GLuint(first));
            ++active_->stats.drawCalls;
        };
        if (!shade || draw.reach != ShadowReach::Kind::Part) {
            use(draw.features, draw.reach != ShadowReach::Kind::None, last <= shaders::kGBufferRecords);
            drawBatch();
            continue;
        }
        // Each pixel of the instance lies in one rectangle of the two lists, so it is shaded once.
        glEnable(GL_SCISSOR_TEST);
        const ShadowReach& reach = parts_[draw.part];
        for (const bool lookups : {false, true}) {
            use(draw.features, lookups, last <= shaders::kGBufferRecords);
            for (const PixelRect& rect : lookups ? reach.shadowed : reach.unshadowed) {
                glScissor(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0);
                drawBatch();
            }
        }
        glDisable(GL_SCISSOR_TEST);
    }
    if (masked != 0)
        maskTargets(targets, 0);
    glBindVertexArray(0);
}

void Renderer::maskTargets(TargetMask targets, TargetMask masked) {
    int location = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((targets & (TargetMask(1) << t)) == 0)
            continue;
        const GLboolean write = (masked & (TargetMask(1) << t)) != 0 ? GL_FALSE : GL_TRUE;
        glColorMaski(GLuint(location++), write, write, write, write);
    }
}

void Renderer::planComputeLighting(PassSet& passes) const {
    passes.surfaceTargets &= ~(targetBit(Target::GBuffer) | targetBit(Target::GBufferMaterial));
    // One surface pass that shades only colour (the intrinsic images keep the forward pass's exact
    // float16 rounding) and has a draw buffer left for the G-buffer.
    // Its image stores write float formats: not into compact targets.
    if (!computeLighting_ || passes.compactTargets || !passes.lighting || passes.attributeTargets != 0 ||
        passes.samples > 1 || passes.spatialSamples > 1 ||
        (passes.surfaceTargets & kShadedTargets & ~kComputeLit) != 0 ||
        std::popcount(passes.surfaceTargets) + 1 > kMaxDrawTargets)
        return;
    passes.surfaceTargets |= targetBit(Target::GBuffer);
    // Textured materials too, where a draw buffer is left for their factors (else their fragments shade).
    if (std::popcount(passes.surfaceTargets) + 1 <= kMaxDrawTargets)
        passes.surfaceTargets |= targetBit(Target::GBufferMaterial);
}

void Renderer::lightInCompute(const Camera& camera, const PassSet& passes,
                              const shaders::ShadingLayout& lights, const Framebuffers& fb) {
    const TargetMask stored = passes.surfaceTargets & kComputeLit;
    const bool materials = (passes.surfaceTargets & targetBit(Target::GBufferMaterial)) != 0;
    auto& program =
        programs_["lighting/" + std::to_string(stored) + (materials ? "/m/" : "/") + lights.key()];
    if (!program)
        program = std::make_unique<ShaderProgram>(
            "compute lighting", shaders::computeLighting(stored, lights, materials).c_str());
    program->use();
    program->set("uClipToOffset", clipToOffset(camera));
    if (lights.environmentMap)
        glProgramUniform1f(program->id(), program->location("uBackgroundLod"),
                           backgroundLod(camera, active_->environmentBackgroundWidth));
    glProgramUniform2i(program->id(), program->location("uSize"), fb.width, fb.height);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shaders::kRecordsBinding, instances_->buffer());
    glBindTextureUnit(shaders::kDepthTextureUnit, fb.depthTexture());
    glBindImageTexture(shaders::kGBufferImageUnit, fb.texture(Target::GBuffer), 0, GL_FALSE, 0, GL_READ_ONLY,
                       GL_R32UI);
    if (materials)
        glBindImageTexture(shaders::kGBufferMaterialImageUnit, fb.texture(Target::GBufferMaterial), 0,
                           GL_FALSE, 0, GL_READ_ONLY, GL_RG32UI);
    if ((stored & targetBit(Target::FinalColor)) != 0)
        glBindImageTexture(shaders::kFinalColorImageUnit, fb.texture(Target::FinalColor), 0, GL_FALSE, 0,
                           GL_WRITE_ONLY, GL_RGBA8);
    if ((stored & targetBit(Target::Hdr)) != 0)
        glBindImageTexture(shaders::kHdrImageUnit, fb.texture(Target::Hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                           GL_RGBA16F);
    const int group = shaders::kComputeLightingGroupSize;
    glDispatchCompute(GLuint((fb.width + group - 1) / group), GLuint((fb.height + group - 1) / group), 1);
    // Image stores are incoherent: the readback (glReadPixels, a texture copy) and the next frame's draws
    // into these targets must see them.
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shaders::kRecordsBinding, 0);
}

} // namespace sp::render
