#include "core/sensors/render_subsystem.h"

#include <algorithm>

#include "core/base/error.h"
#include "core/render/camera.h"
#include "core/render/gl_context.h"
#include "core/render/render_target.h"
#include "core/render/renderer.h"
#include "core/sensors/render_scene.h"
#include "core/world/world.h"

namespace sp::sensors {
namespace {

static_assert(sp::render::kModalityCount == 14, "ECameraModality mirrors sp::render::Modality");

sp::render::ModalitySet toModalitySet(const std::vector<ECameraModality>& modalities) {
    sp::render::ModalitySet set;
    for (ECameraModality modality : modalities)
        set.add(static_cast<sp::render::Modality>(modality));
    return set;
}

// Checks the camera's settings, naming the camera and the property (the renderer's own checks name
// its fields, which the Python user never sees).
sp::render::CameraParams cameraParams(const UCameraSensorComponent& camera) {
    const std::string who = "UCameraSensorComponent " + camera.GetDebugName() + ": ";
    SP_CHECK(camera.Width > 0 && camera.Width <= 16384, sp::InvalidArgument, who,
             "Width must be in [1, 16384], got ", camera.Width);
    SP_CHECK(camera.Height > 0 && camera.Height <= 16384, sp::InvalidArgument, who,
             "Height must be in [1, 16384], got ", camera.Height);
    SP_CHECK(camera.FOV > 0.0 && camera.FOV < 180.0, sp::InvalidArgument, who,
             "FOV must be in (0, 180) degrees, got ", camera.FOV);
    SP_CHECK(camera.NearClip > 0.0, sp::InvalidArgument, who, "NearClip must be > 0, got ", camera.NearClip);
    SP_CHECK(camera.FarClip > camera.NearClip, sp::InvalidArgument, who, "FarClip must be > NearClip (",
             camera.NearClip, "), got ", camera.FarClip);
    SP_CHECK(camera.ShadowResolution >= 16 && camera.ShadowResolution <= 8192, sp::InvalidArgument, who,
             "ShadowResolution must be in [16, 8192], got ", camera.ShadowResolution);
    SP_CHECK(camera.Latency >= 0 && camera.Latency <= sp::render::RenderTarget::kMaxLatency,
             sp::InvalidArgument, who, "Latency must be 0, 1 or 2, got ", camera.Latency);
    sp::render::CameraParams params;
    params.width = camera.Width;
    params.height = camera.Height;
    params.hfovDeg = camera.FOV;
    params.nearClip = camera.NearClip;
    params.farClip = camera.FarClip;
    params.exposure = camera.Exposure;
    params.toneMap = static_cast<sp::render::ToneMap>(camera.ToneCurve);
    params.shadows = camera.bShadows;
    params.shadowResolution = camera.ShadowResolution;
    return params;
}

// Allocates the SpArray of one modality at the given size and returns the view the readback writes to.
template <typename T>
sp::render::OutputView allocate(sp::reflect::SpArray<T>& array, sp::render::Modality modality, int width,
                                int height) {
    const int channels = sp::render::modalityInfo(modality).channels;
    std::vector<int64_t> shape{height, width};
    if (channels > 1)
        shape.push_back(channels);
    array.resize(shape);
    return {modality, array.data(), sp::render::modalityByteSize(modality, width, height)};
}

sp::render::OutputView allocate(FCameraPixels& pixels, sp::render::Modality modality, int width, int height) {
    using M = sp::render::Modality;
    switch (modality) {
    case M::FinalColor:
        return allocate(pixels.final_color, modality, width, height);
    case M::HdrColor:
        return allocate(pixels.hdr_color, modality, width, height);
    case M::Depth:
        return allocate(pixels.depth, modality, width, height);
    case M::Position:
        return allocate(pixels.position, modality, width, height);
    case M::Normal:
        return allocate(pixels.normal, modality, width, height);
    case M::ObjectIds:
        return allocate(pixels.object_ids, modality, width, height);
    case M::MaterialIds:
        return allocate(pixels.material_ids, modality, width, height);
    case M::BaseColor:
        return allocate(pixels.base_color, modality, width, height);
    case M::Roughness:
        return allocate(pixels.roughness, modality, width, height);
    case M::Metallic:
        return allocate(pixels.metallic, modality, width, height);
    case M::MaterialAo:
        return allocate(pixels.material_ao, modality, width, height);
    case M::DiffuseIllumination:
        return allocate(pixels.diffuse_illumination, modality, width, height);
    case M::DiffuseOnly:
        return allocate(pixels.diffuse_only, modality, width, height);
    case M::SpecularResidual:
        return allocate(pixels.specular_residual, modality, width, height);
    }
    SP_THROW(sp::InvalidArgument, "RenderSubsystem::readPixels(): unknown modality ", int(modality));
}

} // namespace

// What was submitted, so that the due frame can be read straight into arrays of the right size.
struct RenderSubsystem::PendingFrame {
    std::uint64_t submit = 0;
    std::int64_t worldFrame = 0;
    int width = 0;
    int height = 0;
    sp::render::ModalitySet modalities;
};

struct RenderSubsystem::CameraState {
    std::unique_ptr<sp::render::RenderTarget> target;
    std::deque<PendingFrame> pending;
    // Whether read_pixels ran since the last submit, and the frame it read (read again by later calls).
    // The arrays themselves are never kept: each call fills fresh ones, so that memory handed out (a
    // numpy array, or an RPC client's reply buffer) is not held by the camera after the call.
    bool readSinceSubmit = false;
    std::optional<PendingFrame> lastRead;
    std::int64_t pixelsFrame = -1;
};

RenderSubsystem::RenderSubsystem(UWorld& world) : world_(world) {}

RenderSubsystem::~RenderSubsystem() {
    if (!context_)
        return;
    context_->makeCurrent(); // GL objects are deleted below, bottom-up: targets, scene caches, renderer
    cameras_.clear();
    if (scene_)
        renderer_->releaseScene(scene_->scene());
    renderer_.reset();
    context_.reset();
}

void RenderSubsystem::ensureRenderer() {
    if (!context_) {
        context_ = std::make_unique<sp::render::GlContext>(); // logs the EGL device it chose, once
        renderer_ = std::make_unique<sp::render::Renderer>(*context_);
        scene_ = std::make_unique<RenderScene>();
    }
    context_->makeCurrent();
}

void RenderSubsystem::Tick(double /*deltaSeconds*/) {
    std::vector<UCameraSensorComponent*> cameras;
    for (AActor* actor : world_.find_actors())
        for (const auto& component : actor->GetComponentList())
            if (auto* camera = dynamic_cast<UCameraSensorComponent*>(component.get()))
                cameras.push_back(camera);

    // Render targets of destroyed cameras go (with the context current, as they hold GL objects).
    if (context_)
        context_->makeCurrent();
    for (auto it = cameras_.begin(); it != cameras_.end();) {
        const bool alive = std::any_of(cameras.begin(), cameras.end(), [&](const UCameraSensorComponent* c) {
            return c->GetHandle() == it->first;
        });
        it = alive ? std::next(it) : cameras_.erase(it);
    }
    if (cameras.empty())
        return;

    ensureRenderer();
    scene_->sync(world_);
    for (UCameraSensorComponent* camera : cameras)
        submit(*camera);
}

RenderSubsystem::CameraState& RenderSubsystem::cameraState(UCameraSensorComponent& camera) {
    auto& state = cameras_[camera.GetHandle()];
    if (!state)
        state = std::make_unique<CameraState>();
    return *state;
}

void RenderSubsystem::submit(UCameraSensorComponent& camera) {
    sp::render::Camera renderCamera;
    renderCamera.params = cameraParams(camera);
    renderCamera.pose = camera.GetComponentTransform().toIsometry();
    const sp::render::ModalitySet modalities = toModalitySet(camera.Modalities);

    CameraState& state = cameraState(camera);
    state.readSinceSubmit = false;
    state.lastRead.reset();
    if (modalities.empty()) { // nothing to render; older frames are dropped with the target
        state.target.reset();
        state.pending.clear();
        return;
    }
    if (!state.target || state.target->latency() != camera.Latency) { // a new latency restarts the ring
        state.target = std::make_unique<sp::render::RenderTarget>(*renderer_, modalities, camera.Latency);
        state.pending.clear();
    } else if (state.target->modalities() != modalities) {
        state.target->setModalities(modalities);
    }
    const std::uint64_t number = state.target->submit(scene_->scene(), renderCamera);
    // The world's frame counter advances after its subsystems tick, so this frame is count + 1.
    state.pending.push_back({number, world_.get_frame_count() + 1, camera.Width, camera.Height, modalities});
    while (state.pending.size() > std::size_t(camera.Latency) + 1)
        state.pending.pop_front();
}

FCameraPixels RenderSubsystem::readPixels(UCameraSensorComponent& camera) {
    auto it = cameras_.find(camera.GetHandle());
    if (it == cameras_.end() || !it->second->target) {
        camera.setPixelsFrame(-1);
        return {};
    }
    CameraState& state = *it->second;
    const auto fill = [&](FCameraPixels& pixels, const PendingFrame& frame) {
        std::vector<sp::render::OutputView> views;
        for (sp::render::Modality modality : frame.modalities.list())
            views.push_back(allocate(pixels, modality, frame.width, frame.height));
        return views;
    };
    FCameraPixels pixels;
    context_->makeCurrent();
    if (!state.readSinceSubmit) {
        state.readSinceSubmit = true;
        state.pixelsFrame = -1;
        const std::uint64_t submitted = state.target->submittedFrames();
        const std::uint64_t latency = std::uint64_t(state.target->latency());
        auto due = std::find_if(state.pending.begin(), state.pending.end(), [&](const PendingFrame& f) {
            return submitted > latency && f.submit == submitted - latency;
        });
        if (due != state.pending.end()) {
            if (state.target->read(fill(pixels, *due))) {
                state.pixelsFrame = due->worldFrame;
                state.lastRead = *due;
            } else {
                pixels = {};
            }
            state.pending.erase(state.pending.begin(), std::next(due));
        }
    } else if (state.lastRead && !state.target->readAgain(fill(pixels, *state.lastRead))) {
        pixels = {};
    }
    camera.setPixelsFrame(state.pixelsFrame);
    return pixels;
}

std::optional<RenderSubsystem::ObjectIdInfo> RenderSubsystem::objectIdInfo(std::uint32_t id) const {
    if (!scene_)
        return std::nullopt;
    auto info = scene_->objectIdInfo(id);
    if (!info)
        return std::nullopt;
    return ObjectIdInfo{info->component, info->slot, info->materialName};
}

std::uint32_t RenderSubsystem::objectId(sp::reflect::ObjectHandle component, int slot) const {
    return scene_ ? scene_->objectId(component, slot) : 0;
}

std::uint32_t RenderSubsystem::materialId(const std::string& name) const {
    return scene_ ? scene_->materialId(name) : 0;
}

FRenderDeviceInfo RenderSubsystem::deviceInfo() {
    ensureRenderer();
    const sp::render::ContextReport& report = context_->report();
    FRenderDeviceInfo info;
    info.Kind = report.kind;
    info.DeviceIndex = report.deviceIndex;
    info.DeviceCount = report.deviceCount;
    info.Vendor = report.vendor;
    info.Renderer = report.renderer;
    info.Version = report.version;
    return info;
}

FRenderStats RenderSubsystem::stats() const {
    FRenderStats result;
    if (!renderer_)
        return result;
    // stats() collects timer queries of this context; another world may own the current one.
    context_->makeCurrent();
    const sp::render::RenderStats& stats = renderer_->stats();
    result.Frames = int64_t(stats.frames);
    result.ShadowPasses = int64_t(stats.shadowPasses);
    result.ShadowReuses = int64_t(stats.shadowReuses);
    result.SurfacePasses = int64_t(stats.surfacePasses);
    result.AttributePasses = int64_t(stats.attributePasses);
    result.LightingPasses = int64_t(stats.lightingPasses);
    result.TonemapPasses = int64_t(stats.tonemapPasses);
    result.Readbacks = int64_t(stats.readbacks);
    result.DrawnInstances = int64_t(stats.drawnInstances);
    result.CulledInstances = int64_t(stats.culledInstances);
    const auto time = [&](sp::render::Pass pass) { return stats.passTimes[std::size_t(pass)]; };
    result.ShadowMs = time(sp::render::Pass::Shadow).gpuMs;
    result.SurfaceMs = time(sp::render::Pass::Surface).gpuMs;
    result.AttributeMs = time(sp::render::Pass::Attribute).gpuMs;
    result.ReadbackMs = time(sp::render::Pass::Readback).cpuMs;
    return result;
}

} // namespace sp::sensors
