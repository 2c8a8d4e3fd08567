#include "core/sensors/render_subsystem.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <map>
#include <type_traits>
#include <utility>

#include "core/base/error.h"
#include "core/pathtrace/denoise.h"
#include "core/pathtrace/irradiance_probes.h"
#include "core/pathtrace/path_tracer.h"
#include "core/render/auto_exposure.h"
#include "core/render/camera.h"
#include "core/render/gl_context.h"
#include "core/render/lens.h"
#include "core/render/luminance.h"
#include "core/render/render_target.h"
#include "core/render/renderer.h"
#include "core/render/tone.h"
#include "core/sensors/camera_exposure.h"
#include "core/sensors/render_scene.h"
#include "core/world/world.h"

namespace sp::sensors {
namespace {

// ECameraModality and FCameraPixels, which the generator reads as plain declarations, mirror the renderer's
// one list of modalities (SP_RENDER_MODALITIES): each entry's enumerator has its value and each has a field
// of its name and element type, or the build fails naming it. (That neither has more than the list is checked
// from the registry: tests/core/sensors/camera_modalities_test.cpp.)
template <sp::render::DType> struct ElementOf;
template <> struct ElementOf<sp::render::DType::UInt8> { using type = uint8_t; };
template <> struct ElementOf<sp::render::DType::UInt32> { using type = uint32_t; };
template <> struct ElementOf<sp::render::DType::Float16> { using type = sp::reflect::Half; };
template <> struct ElementOf<sp::render::DType::Float32> { using type = float; };
#define SP_CHECK_CAMERA_MODALITY(enumerator, name, dtype, channels)                                          \
    static_assert(static_cast<int>(ECameraModality::enumerator) ==                                           \
                      static_cast<int>(sp::render::Modality::enumerator),                                    \
                  "ECameraModality::" #enumerator " is not sp::render::Modality::" #enumerator);             \
    static_assert(std::is_same_v<decltype(FCameraPixels::name),                                              \
                                 sp::reflect::SpArray<ElementOf<sp::render::DType::dtype>::type>>,           \
                  "FCameraPixels::" #name " is not an array of " #dtype);
SP_RENDER_MODALITIES(SP_CHECK_CAMERA_MODALITY)
#undef SP_CHECK_CAMERA_MODALITY

sp::render::ModalitySet toModalitySet(const std::vector<ECameraModality>& modalities) {
    sp::render::ModalitySet set;
    for (ECameraModality modality : modalities)
        set.add(static_cast<sp::render::Modality>(modality));
    return set;
}

// Checks the camera's settings, naming the camera and the property (the renderer's own checks name
// its fields, which the Python user never sees).
// `sizedResolution` stands for ShadowResolution 0 (see RenderSubsystem::Tick).
sp::render::CameraParams cameraParams(const UCameraSensorComponent& camera, int sizedResolution) {
    const std::string who = camera.GetDebugName() + ": ";
    SP_CHECK(camera.Width > 0 && camera.Width <= 16384, sp::InvalidArgument, who,
             "Width must be in [1, 16384], got ", camera.Width);
    SP_CHECK(camera.Height > 0 && camera.Height <= 16384, sp::InvalidArgument, who,
             "Height must be in [1, 16384], got ", camera.Height);
    SP_CHECK(camera.FOV > 0.0 && camera.FOV < 180.0, sp::InvalidArgument, who,
             "FOV must be in (0, 180) degrees, got ", camera.FOV);
    SP_CHECK(camera.NearClip > 0.0, sp::InvalidArgument, who, "NearClip must be > 0, got ", camera.NearClip);
    SP_CHECK(camera.FarClip > camera.NearClip, sp::InvalidArgument, who, "FarClip must be > NearClip (",
             camera.NearClip, "), got ", camera.FarClip);
    SP_CHECK(camera.ShadowResolution == 0 ||
                 (camera.ShadowResolution >= 16 && camera.ShadowResolution <= 8192),
             sp::InvalidArgument, who, "ShadowResolution must be 0 or in [16, 8192], got ",
             camera.ShadowResolution);
    SP_CHECK(camera.WhiteBalanceTemperature >= 2000.0 && camera.WhiteBalanceTemperature <= 25000.0,
             sp::InvalidArgument, who, "WhiteBalanceTemperature must be in [2000, 25000] kelvin, got ",
             camera.WhiteBalanceTemperature);
    SP_CHECK(camera.Latency >= 0 && camera.Latency <= sp::render::RenderTarget::kMaxLatency,
             sp::InvalidArgument, who, "Latency must be 0, 1 or 2, got ", camera.Latency);
    sp::render::CameraParams params;
    params.width = camera.Width;
    params.height = camera.Height;
    params.hfovDeg = camera.FOV;
    params.nearClip = camera.NearClip;
    params.farClip = camera.FarClip;
    params.exposure = camera.Exposure;
    params.whiteBalance = sp::render::whiteBalanceGains(camera.WhiteBalanceTemperature);
    // A thin lens of the camera's focal length (on its sensor) at its f-number: radius f / (2 N), in metres.
    params.apertureRadius =
        camera.ApertureFNumber > 0.0 ? 0.5e-3 * camera.GetFocalLength() / camera.ApertureFNumber : 0.0;
    params.focusDistance = camera.FocusDistance;
    params.vignetteIntensity = camera.VignetteIntensity;
    params.toneMap = static_cast<sp::render::ToneMap>(camera.ToneCurve);
    params.shadows = camera.bShadows;
    params.shadowResolution = camera.ShadowResolution != 0 ? camera.ShadowResolution : sizedResolution;
    params.globalIllumination = camera.GlobalIlluminationQuality != EGlobalIlluminationQuality::Off;
    // (The path tracer's pixels average rays spread over them: none.)
    params.antiAliasing = sp::render::AntiAliasing::None;
    if (camera.Renderer == ECameraRenderer::Raster &&
        camera.AntiAliasingMethod != EAntiAliasingMethod::AAM_None)
        params.antiAliasing = camera.AntiAliasingMethod == EAntiAliasingMethod::AAM_FXAA
                                  ? sp::render::AntiAliasing::Fxaa
                                  : sp::render::AntiAliasing::Msaa;
    params.msaaSamples = camera.MSAASampleCount;
    if (camera.Renderer == ECameraRenderer::Raster) {
        params.spatialSamples = camera.SpatialSampleCount;
        params.maxAnisotropy = camera.MaxAnisotropy;
        params.mipBias = camera.MipMapLODBias;
        params.ambientOcclusionIntensity = camera.AmbientOcclusionIntensity;
    }
    params.ambientOcclusionRadius = camera.AmbientOcclusionRadius;
    return params;
}

// How far from the cameras that ask for indirect light (m) the probes' grid reaches.
constexpr double kIndirectLightReach = 50.0;

// The probes of each quality (EGlobalIlluminationQuality's documentation; core/render/README.md): spacing,
// probes along an axis at most, rays per probe, bounces, probes lit per frame after a change.
sp::pathtrace::ProbeSettings probeSettings(EGlobalIlluminationQuality quality) {
    switch (quality) {
    case EGlobalIlluminationQuality::Off:
    case EGlobalIlluminationQuality::Low:
        return {1.0, 16, 128, 2, 32};
    case EGlobalIlluminationQuality::Medium:
        return {0.5, 24, 256, 3, 32};
    case EGlobalIlluminationQuality::High:
        return {0.35, 32, 512, 4, 64};
    case EGlobalIlluminationQuality::Epic:
        return {0.25, 48, 1024, 4, 128};
    }
    throw sp::InvalidArgument("probeSettings(): EGlobalIlluminationQuality " + std::to_string(int(quality)) +
                              " is not a quality");
}

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names)
        text += (text.empty() ? "" : ", ") + name;
    return text;
}

// Allocates the SpArray of one modality for `count` images of the given size, (count, H, W[, C]), or one
// image, (H, W[, C]), when count is 0; returns the view of the first image (the next ones follow it). The
// storage is not zeroed: a read writes every byte of it, and arrays of a read that fails are dropped.
template <typename T>
sp::render::OutputView allocate(sp::reflect::SpArray<T>& array, sp::render::Modality modality, int width,
                                int height, int count) {
    const int channels = sp::render::modalityInfo(modality).channels;
    std::vector<int64_t> shape{height, width};
    if (channels > 1)
        shape.push_back(channels);
    if (count > 0)
        shape.insert(shape.begin(), count);
    array.resizeForOverwrite(shape);
    return {modality, array.data(), sp::render::modalityByteSize(modality, width, height)};
}

// final_color without its alpha channel (UCameraSensorComponent::bFinalColorAlpha): (..., 4) -> (..., 3).
void dropAlpha(sp::reflect::SpArray<std::uint8_t>& rgba) {
    std::vector<int64_t> shape = rgba.getShape();
    if (shape.empty() || shape.back() != 4)
        return; // not read (the camera does not render final_color)
    shape.back() = 3;
    sp::reflect::SpArray<std::uint8_t> rgb;
    rgb.resizeForOverwrite(shape);
    const std::uint8_t* from = rgba.data();
    std::uint8_t* to = rgb.data();
    const auto pixels = std::size_t(rgb.getSize()) / 3;
    for (std::size_t p = 0; p < pixels; ++p, from += 4, to += 3) {
        to[0] = from[0];
        to[1] = from[1];
        to[2] = from[2];
    }
    rgba = std::move(rgb);
}

sp::render::OutputView allocate(FCameraPixels& pixels, sp::render::Modality modality, int width, int height,
                                int count) {
    switch (modality) { // each modality's field of FCameraPixels, from the one list
#define SP_ALLOCATE_MODALITY(enumerator, name, dtype, channels)                                              \
    case sp::render::Modality::enumerator:                                                                   \
        return allocate(pixels.name, modality, width, height, count);
        SP_RENDER_MODALITIES(SP_ALLOCATE_MODALITY)
#undef SP_ALLOCATE_MODALITY
    }
    SP_THROW(sp::InvalidArgument, "RenderSubsystem::readPixels(): unknown modality ", int(modality));
}

} // namespace

// What a path-traced camera takes from the path tracer; its other modalities are rasterised.
constexpr std::array kTracedModalities{sp::render::Modality::FinalColor, sp::render::Modality::HdrColor,
                                       sp::render::Modality::DiffuseIllumination,
                                       sp::render::Modality::DiffuseOnly,
                                       sp::render::Modality::SpecularResidual};

// A path-traced camera's images of one frame, made when it was submitted (RenderSubsystem::trace): the
// requested ones of kTracedModalities, each as the modality's dtype and shape.
struct TracedImages {
    std::map<sp::render::Modality, std::vector<std::byte>> images;
    std::uint64_t samples = 0; // per pixel, accumulated
};

// What was submitted, so that the due frame can be read straight into arrays of the right size.
struct RenderSubsystem::PendingFrame {
    std::uint64_t submit = 0;
    std::int64_t worldFrame = 0;
    int width = 0;
    int height = 0;
    sp::render::ModalitySet modalities;
    sp::render::CameraParams params;            // as rendered: its exposure, and the lens source's size
    std::shared_ptr<const TracedImages> traced; // replaces rasterised images when set
    // Set for a lens camera: the frame was rendered as the remap's pinhole source (sourceWidth x
    // sourceHeight) and is read through it into width x height images.
    std::shared_ptr<const sp::render::LensRemap> lens;
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
    sp::pathtrace::Accumulation accumulation; // the path tracer's running image
    // The lens remap of the camera's current lens and size (rebuilt when either changes).
    std::shared_ptr<const sp::render::LensRemap> lens;
    sp::render::LensModel lensModel;
    CameraExposure exposure;
    // A cut's metering view (meterView()): a small hdr_color render of what the camera is about to show.
    std::unique_ptr<sp::render::RenderTarget> meterTarget;
};

RenderSubsystem::RenderSubsystem(UWorld& world) : world_(world), scene_(std::make_unique<RenderScene>()) {}

void RenderSubsystem::OnActorBeginPlay(AActor& actor) {
    scene_->track(actor);
}

void RenderSubsystem::OnActorEndPlay(AActor& actor) {
    scene_->untrack(actor);
}

void RenderSubsystem::OnComponentBeginPlay(UActorComponent& component) {
    if (auto* camera = dynamic_cast<UCameraSensorComponent*>(&component))
        cameraComponents_.add(camera);
    scene_->track(component);
}

void RenderSubsystem::OnComponentEndPlay(UActorComponent& component) {
    if (const auto* camera = dynamic_cast<const UCameraSensorComponent*>(&component))
        cameraComponents_.remove(camera);
    scene_->untrack(component);
}

struct RenderSubsystem::Gl {
    Gl()
        : context(std::make_unique<sp::render::GlContext>()),
          renderer(std::make_unique<sp::render::Renderer>(*context)) {}
    ~Gl() {
        context->makeCurrent();
        renderer.reset();
    }
    Gl(const Gl&) = delete;
    Gl& operator=(const Gl&) = delete;

    // A camera's render of this frame, queued by its world's tick.
    struct Queued {
        const RenderSubsystem* owner = nullptr;
        sp::render::RenderTarget* target = nullptr;
        const sp::render::Scene* scene = nullptr;
        sp::render::Camera camera;
        std::uint64_t frame = 0; // the frame number its world recorded
    };
    // Renders what the worlds queued, as one batch (sp::render::RenderTarget::submitAll): once every world
    // ticked (OnWorldsTicked), or earlier when something needs a queued frame or a world ticks again.
    void runQueued() {
        if (queued.empty())
            return;
        const std::vector<Queued> batch = std::exchange(queued, {});
        std::vector<sp::render::RenderTarget::Submission> submissions;
        submissions.reserve(batch.size());
        for (const Queued& q : batch)
            submissions.push_back({q.target, q.scene, &q.camera});
        context->makeCurrent();
        const std::vector<std::uint64_t> numbers = sp::render::RenderTarget::submitAll(submissions);
        for (std::size_t i = 0; i < batch.size(); ++i)
            SP_CHECK(numbers[i] == batch[i].frame, sp::InvalidState, "RenderSubsystem: frame ", numbers[i],
                     " of a camera was recorded as frame ", batch[i].frame);
    }

    std::unique_ptr<sp::render::GlContext> context; // logs the EGL device it chose, once per engine
    std::unique_ptr<sp::render::Renderer> renderer;
    std::vector<Queued> queued;
};

RenderSubsystem::~RenderSubsystem() {
    if (!gl_)
        return;
    std::erase_if(gl_->queued, [&](const Gl::Queued& q) { return q.owner == this; });
    gl_->context->makeCurrent(); // this world's GL objects go: its targets, then its scene's state
    cameras_.clear();
    if (scene_)
        gl_->renderer->releaseScene(scene_->scene());
}

void RenderSubsystem::ensureRenderer() {
    if (!gl_) {
        auto make = [] { return std::static_pointer_cast<void>(std::make_shared<Gl>()); };
        sp::world::WorldHost* host = world_.GetHost();
        gl_ = std::static_pointer_cast<Gl>(
            host != nullptr ? host->shared("sp::sensors::RenderSubsystem::Gl", make) : make());
    }
    gl_->context->makeCurrent();
}

namespace {
// ShadowResolution 0's map size for cameras whose longest side is `longest`: the next power of two, in [256,
// 4096].
int sizedShadowResolution(int longest) {
    return std::clamp(int(std::bit_ceil(unsigned(std::max(longest, 1)))), 256, 4096);
}
} // namespace

void RenderSubsystem::Tick(double /*deltaSeconds*/) {
    std::vector<UCameraSensorComponent*> cameras; // a snapshot: the frame's cameras, in play order
    for (const auto& [sequence, camera] : cameraComponents_.items())
        cameras.push_back(camera);

    // Render targets of destroyed cameras go (with the context current, as they hold GL objects), after this
    // world's renders of an earlier frame are done, if they are still queued (a world without a host whose
    // last frame failed after its tick). What other worlds queued this frame waits for OnWorldsTicked.
    if (gl_) {
        if (std::any_of(gl_->queued.begin(), gl_->queued.end(),
                        [&](const Gl::Queued& q) { return q.owner == this; }))
            gl_->runQueued();
        gl_->context->makeCurrent();
    }
    for (auto it = cameras_.begin(); it != cameras_.end();) {
        const bool alive = std::any_of(cameras.begin(), cameras.end(), [&](const UCameraSensorComponent* c) {
            return c->GetHandle() == it->first;
        });
        it = alive ? std::next(it) : cameras_.erase(it);
    }
    if (cameras.empty())
        return;

    ensureRenderer();
    scene_->sync();
    updateIndirectLight(cameras);
    // ShadowResolution 0: one size for the frame's shadowed cameras, from the longest side among them, so
    // that they share the maps (a size per camera would draw them again for each) and a 128-pixel camera
    // does not redraw a 1024-texel map's worth around every moving object (16 worlds of Table 3's pushed
    // cube, bench_vector.py: 128 texels gave 1.4x the steps per second of 1024, 4096 a fifth).
    int longest = 0;
    for (const UCameraSensorComponent* camera : cameras)
        if (!camera->renderSuspended() && camera->bShadows)
            longest = std::max({longest, camera->Width, camera->Height});
    const int sized = sizedShadowResolution(longest);
    for (UCameraSensorComponent* camera : cameras)
        if (!camera->renderSuspended())
            submit(*camera, sized, world_.get_frame_count() + 1); // the counter advances after the tick
}

void RenderSubsystem::renderNow(UCameraSensorComponent& camera) {
    if (gl_)
        gl_->runQueued(); // what a frame queued goes first, in order
    ensureRenderer();
    gl_->context->makeCurrent();
    scene_->sync();
    updateIndirectLight({&camera});
    submit(camera, sizedShadowResolution(std::max(camera.Width, camera.Height)), world_.get_frame_count());
    gl_->runQueued();
}

void RenderSubsystem::updateIndirectLight(const std::vector<UCameraSensorComponent*>& cameras) {
    // The highest quality any rasterised camera that shades asks for; Off when none does.
    EGlobalIlluminationQuality quality = EGlobalIlluminationQuality::Off;
    // The probes cover what reaches within kIndirectLightReach of those cameras: what lies wholly further out
    // adds little light to what they see, and a thing falling away there must not stretch the grid.
    Eigen::AlignedBox3d around;
    for (const UCameraSensorComponent* camera : cameras)
        if (!camera->renderSuspended() && camera->Renderer == ECameraRenderer::Raster &&
            camera->GlobalIlluminationQuality != EGlobalIlluminationQuality::Off &&
            toModalitySet(camera->Modalities).requiredPasses(camera->bShadows).lighting) {
            quality = std::max(quality, camera->GlobalIlluminationQuality);
            around.extend(camera->GetComponentTransform().toIsometry().translation());
        }
    if (quality == EGlobalIlluminationQuality::Off) {
        scene_->setIrradianceVolume(nullptr);
        probes_.reset();
        return;
    }
    if (!tracer_)
        tracer_ = std::make_unique<sp::pathtrace::PathTracer>();
    if (!probes_)
        probes_ = std::make_unique<sp::pathtrace::IrradianceProbes>();
    around.min().array() -= kIndirectLightReach;
    around.max().array() += kIndirectLightReach;
    scene_->setIrradianceVolume(probes_->update(scene_->scene(), *tracer_, probeSettings(quality), around));
}

RenderSubsystem::CameraState& RenderSubsystem::cameraState(UCameraSensorComponent& camera) {
    auto& state = cameras_[camera.GetHandle()];
    if (!state)
        state = std::make_unique<CameraState>();
    return *state;
}

void RenderSubsystem::submit(UCameraSensorComponent& camera, int sizedShadowResolution, int64_t shownFrame) {
    sp::render::Camera renderCamera;
    renderCamera.params = cameraParams(camera, sizedShadowResolution);
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
    // A lens camera renders the pinhole image its remap samples (centred, wide enough for every ray).
    const sp::render::LensModel lens = camera.lensModel();
    const bool pinhole = lens.undistorted() && camera.PrincipalPointOffset == FVector2D{};
    if (pinhole) {
        state.lens.reset();
    } else {
        const bool same = state.lens && state.lens->width() == camera.Width &&
                          state.lens->height() == camera.Height && state.lensModel == lens;
        if (!same) {
            const std::string context = camera.GetDebugName();
            state.lens =
                std::make_shared<sp::render::LensRemap>(lens, camera.Width, camera.Height, context.c_str());
            state.lensModel = lens;
        }
        renderCamera.params.width = state.lens->sourceWidth();
        renderCamera.params.height = state.lens->sourceHeight();
        renderCamera.params.hfovDeg = state.lens->sourceHfovDeg();
    }
    if (!state.target || state.target->latency() != camera.Latency) { // a new latency restarts the ring
        state.target = std::make_unique<sp::render::RenderTarget>(*gl_->renderer, modalities, camera.Latency);
        state.pending.clear();
    } else if (state.target->modalities() != modalities) {
        state.target->setModalities(modalities);
    }
    const bool traces = camera.Renderer == ECameraRenderer::PathTraced &&
                        std::any_of(kTracedModalities.begin(), kTracedModalities.end(),
                                    [&](sp::render::Modality m) { return modalities.contains(m); });
    // A path-traced camera meters its own image (trace()); a rasterised one adapts to its last read frame.
    if (!traces && modalities.contains(sp::render::Modality::FinalColor))
        renderCamera.params.exposure = state.exposure.exposureFor(
            camera, world_.get_time_seconds(), [&](const sp::render::MeteringSettings& settings) {
                return meterView(camera, renderCamera, state, settings);
            });
    // Rendered with every world's cameras once all worlds ticked (OnWorldsTicked).
    const std::uint64_t number = state.target->submittedFrames() + 1;
    gl_->queued.push_back({this, state.target.get(), &scene_->scene(), renderCamera, number});
    std::shared_ptr<const TracedImages> traced;
    if (traces)
        traced = trace(camera, renderCamera, modalities, state);
    state.pending.push_back({number, shownFrame, camera.Width, camera.Height, modalities, renderCamera.params,
                             std::move(traced), state.lens});
    while (state.pending.size() > std::size_t(camera.Latency) + 1)
        state.pending.pop_front();
}

double RenderSubsystem::meterView(const UCameraSensorComponent& camera,
                                  const sp::render::Camera& renderCamera, CameraState& state,
                                  const sp::render::MeteringSettings& settings) {
    // At most 128 pixels wide: the metering samples no more (auto_exposure.h), and the render costs little.
    sp::render::Camera view = renderCamera;
    if (view.params.width > 128) {
        view.params.height = std::max(1, int(std::lround(128.0 * view.params.height / view.params.width)));
        view.params.width = 128;
    }
    view.params.antiAliasing = sp::render::AntiAliasing::None;
    view.params.spatialSamples = 1;
    const sp::render::ModalitySet hdr{sp::render::Modality::HdrColor};
    if (!state.meterTarget)
        state.meterTarget = std::make_unique<sp::render::RenderTarget>(*gl_->renderer, hdr, 0);
    std::vector<std::uint16_t> pixels(std::size_t(view.params.width) * std::size_t(view.params.height) * 4);
    const sp::render::OutputView output{sp::render::Modality::HdrColor, pixels.data(),
                                        pixels.size() * sizeof(std::uint16_t)};
    const sp::render::RenderTarget::Submission submission{state.meterTarget.get(), &scene_->scene(), &view};
    sp::render::RenderTarget::submitAll({&submission, 1});
    SP_CHECK(state.meterTarget->read({&output, 1}).has_value(), sp::InvalidState,
             "RenderSubsystem::meterView(): the metering view of ", camera.GetDebugName(),
             " was not rendered");
    return sp::render::meterHdrHalf(pixels.data(), view.params.width, view.params.height, settings);
}

void RenderSubsystem::resetAutoExposure(UCameraSensorComponent& camera) {
    cameraState(camera).exposure.reset();
}

std::shared_ptr<const TracedImages> RenderSubsystem::trace(UCameraSensorComponent& camera,
                                                           sp::render::Camera& renderCamera,
                                                           const sp::render::ModalitySet& modalities,
                                                           CameraState& state) {
    if (!tracer_)
        tracer_ = std::make_unique<sp::pathtrace::PathTracer>();
    tracer_->render(scene_->scene(), renderCamera,
                    {camera.SamplesPerPixel, camera.MaxBounces, camera.PathTracingMaxPathIntensity,
                     camera.bPathTracingApproximateCaustics},
                    state.accumulation);
    const sp::pathtrace::Accumulation& image = state.accumulation;
    // final_color and hdr_color denoised when asked for; the intrinsic images stay unfiltered.
    std::vector<float> denoised;
    if (camera.bPathTracingEnableDenoiser && (modalities.contains(sp::render::Modality::FinalColor) ||
                                              modalities.contains(sp::render::Modality::HdrColor)))
        denoised = sp::pathtrace::denoise(image);
    // Channel c of pixel (x, y) of the image final_color and hdr_color show.
    const auto shownAt = [&](int x, int y, int c) {
        return denoised.empty() ? image.mean(x, y, c)
                                : denoised[(std::size_t(y) * image.width + x) * 3 + std::size_t(c)];
    };
    if (modalities.contains(sp::render::Modality::FinalColor)) {
        // Automatic exposure meters the image it tone-maps (denoised when it is).
        std::optional<double> ev;
        if (camera.AutoExposureMethod != EAutoExposureMethod::AEM_Manual) {
            ev = sp::render::meterLuminance(
                image.width, image.height,
                [&](int x, int y) {
                    return sp::render::luminance<double>(shownAt(x, y, 0), shownAt(x, y, 1),
                                                         shownAt(x, y, 2));
                },
                meteringSettings(camera));
            state.exposure.metered(*ev);
        }
        renderCamera.params.exposure = state.exposure.exposureFor(
            camera, world_.get_time_seconds(), [&](const sp::render::MeteringSettings&) { return *ev; });
    }
    auto traced = std::make_shared<TracedImages>();
    traced->samples = image.samples;
    // The pixel's vignetting (1 without), as the surface shader applies it to final_color.
    const sp::render::Vignette vignette(renderCamera.params);
    for (sp::render::Modality modality : kTracedModalities) {
        if (!modalities.contains(modality))
            continue;
        std::vector<std::byte>& bytes = traced->images[modality];
        bytes.resize(sp::render::modalityByteSize(modality, image.width, image.height));
        const int channels = sp::render::modalityInfo(modality).channels;
        auto* half = reinterpret_cast<std::uint16_t*>(bytes.data());
        auto* final = reinterpret_cast<std::uint8_t*>(bytes.data());
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const std::size_t pixel = (std::size_t(y) * image.width + x) * std::size_t(channels);
                for (int c = 0; c < 3; ++c) {
                    const float raw = image.mean(x, y, c);
                    const float hdr = shownAt(x, y, c);
                    switch (modality) {
                    case sp::render::Modality::FinalColor:
                        final[pixel + c] = std::uint8_t(
                            std::lround(255.0f * sp::render::toneMapChannel(hdr * vignette(x + 0.5, y + 0.5),
                                                                            c, renderCamera.params)));
                        break;
                    case sp::render::Modality::HdrColor:
                        half[pixel + c] = sp::render::floatToHalf(hdr);
                        break;
                    case sp::render::Modality::DiffuseIllumination:
                        half[pixel + c] =
                            sp::render::floatToHalf(image.mean(image.diffuseIlluminationSum, x, y, c));
                        break;
                    case sp::render::Modality::DiffuseOnly:
                        half[pixel + c] = sp::render::floatToHalf(image.mean(image.diffuseOnlySum, x, y, c));
                        break;
                    default: // SpecularResidual: what the unfiltered hdr_color holds beyond diffuse_only
                        half[pixel + c] =
                            sp::render::floatToHalf(raw - image.mean(image.diffuseOnlySum, x, y, c));
                        break;
                    }
                }
                if (modality == sp::render::Modality::FinalColor)
                    final[pixel + 3] = 255;
                else if (channels == 4)
                    half[pixel + 3] = sp::render::floatToHalf(1.0f);
            }
    }
    return traced;
}

void RenderSubsystem::restartAccumulation(UCameraSensorComponent& camera) {
    cameraState(camera).accumulation = {};
}

void RenderSubsystem::OnWorldsTicked() {
    if (gl_)
        gl_->runQueued();
}

const RenderSubsystem::PendingFrame* RenderSubsystem::dueFrame(UCameraSensorComponent& camera) const {
    if (gl_)
        gl_->runQueued(); // a read within the frame (a later subsystem of this world)
    auto it = cameras_.find(camera.GetHandle());
    if (it == cameras_.end() || !it->second->target)
        return nullptr;
    const CameraState& state = *it->second;
    if (state.readSinceSubmit)
        return state.lastRead ? &*state.lastRead : nullptr;
    const std::uint64_t submitted = state.target->submittedFrames();
    const std::uint64_t latency = std::uint64_t(state.target->latency());
    auto due = std::find_if(state.pending.begin(), state.pending.end(), [&](const PendingFrame& f) {
        return submitted > latency && f.submit == submitted - latency;
    });
    return due == state.pending.end() ? nullptr : &*due;
}

std::optional<RenderSubsystem::FrameShape> RenderSubsystem::dueShape(UCameraSensorComponent& camera) const {
    const PendingFrame* frame = dueFrame(camera);
    if (frame == nullptr)
        return std::nullopt;
    return FrameShape{frame->width, frame->height, frame->modalities};
}

bool RenderSubsystem::readInto(UCameraSensorComponent& camera,
                               const std::vector<sp::render::OutputView>& views) {
    const PendingFrame* frame = dueFrame(camera);
    if (frame == nullptr) {
        if (auto it = cameras_.find(camera.GetHandle()); it != cameras_.end() && it->second->target) {
            it->second->readSinceSubmit = true; // priming: this frame's read found nothing, as it will again
            it->second->pixelsFrame = -1;
        }
        camera.setPixelsFrame(-1);
        return false;
    }
    CameraState& state = *cameras_.at(camera.GetHandle());
    gl_->context->makeCurrent();
    // A lens frame is read at its render's size into buffers of its own, then remapped into `views`.
    const std::shared_ptr<const sp::render::LensRemap> lens = frame->lens;
    std::vector<std::vector<std::byte>> rendered;
    std::vector<sp::render::OutputView> readViews = views;
    if (lens)
        for (sp::render::OutputView& view : readViews) {
            rendered.emplace_back(
                sp::render::modalityByteSize(view.modality, lens->sourceWidth(), lens->sourceHeight()));
            view = {view.modality, rendered.back().data(), rendered.back().size()};
        }
    bool read = false;
    if (!state.readSinceSubmit) {
        const PendingFrame due = *frame;
        state.readSinceSubmit = true;
        state.pixelsFrame = -1;
        read = state.target->read(readViews).has_value();
        if (read) {
            state.pixelsFrame = due.worldFrame;
            state.lastRead = due;
            // A rasterised final_color is what the automatic exposure adapts to (at its rendered size).
            if (!due.traced && camera.AutoExposureMethod != EAutoExposureMethod::AEM_Manual)
                for (const sp::render::OutputView& view : readViews)
                    if (view.modality == sp::render::Modality::FinalColor) {
                        const sp::render::FinalColorMetering metering = sp::render::meterFinalColor(
                            static_cast<const std::uint8_t*>(view.data), due.params.width, due.params.height,
                            due.params, meteringSettings(camera));
                        state.exposure.metered(metering.ev100, metering.exact);
                    }
        }
        auto end = std::find_if(state.pending.begin(), state.pending.end(),
                                [&](const PendingFrame& f) { return f.submit == due.submit; });
        state.pending.erase(state.pending.begin(), std::next(end));
    } else {
        read = state.target->readAgain(readViews).has_value();
    }
    // A path-traced frame's images replace the rasterised ones.
    const TracedImages* traced = read && state.lastRead ? state.lastRead->traced.get() : nullptr;
    if (traced)
        for (const sp::render::OutputView& view : readViews)
            if (auto image = traced->images.find(view.modality); image != traced->images.end())
                std::memcpy(view.data, image->second.data(), std::min(view.size, image->second.size()));
    if (read && lens)
        for (std::size_t i = 0; i < views.size(); ++i) {
            SP_CHECK(views[i].size ==
                         sp::render::modalityByteSize(views[i].modality, lens->width(), lens->height()),
                     sp::InvalidArgument,
                     "RenderSubsystem::readInto(): ", sp::render::modalityName(views[i].modality), " needs ",
                     sp::render::modalityByteSize(views[i].modality, lens->width(), lens->height()),
                     " bytes, got ", views[i].size);
            const sp::render::ModalityInfo& info = sp::render::modalityInfo(views[i].modality);
            lens->apply(static_cast<const std::byte*>(readViews[i].data),
                        static_cast<std::byte*>(views[i].data),
                        sp::render::dtypeSize(info.dtype) * std::size_t(info.channels));
        }
    camera.setAccumulatedSamples(traced ? std::int64_t(traced->samples) : 0);
    camera.setAppliedExposure(read && state.lastRead ? state.lastRead->params.exposure : 0.0f);
    camera.setPixelsFrame(read ? state.pixelsFrame : -1);
    return read;
}

FCameraPixels RenderSubsystem::readPixels(UCameraSensorComponent& camera) {
    FCameraPixels pixels;
    std::vector<sp::render::OutputView> views;
    if (const std::optional<FrameShape> shape = dueShape(camera))
        for (sp::render::Modality modality : shape->modalities.list())
            views.push_back(allocate(pixels, modality, shape->width, shape->height, 0));
    if (!readInto(camera, views))
        return {};
    if (!camera.bFinalColorAlpha)
        dropAlpha(pixels.final_color);
    return pixels;
}

FCameraPixels RenderSubsystem::readPixelsStacked(const std::vector<UCameraSensorComponent*>& cameras,
                                                 const char* context) {
    SP_CHECK(!cameras.empty(), sp::InvalidArgument, context, ": Cameras is empty");
    std::vector<std::pair<RenderSubsystem*, FrameShape>> shapes;
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        SP_CHECK(cameras[i], sp::InvalidArgument, context, ": Cameras[", i, "] is None");
        UWorld* world = cameras[i]->GetWorld();
        SP_CHECK(world, sp::InvalidState, context, ": Cameras[", i, "] (", cameras[i]->GetDebugName(),
                 ") is not in a world");
        auto& subsystem = world->GetSubsystem<RenderSubsystem>();
        const std::optional<FrameShape> shape = subsystem.dueShape(*cameras[i]);
        if (!shape) { // a camera still priming: nothing read, as read_pixels() would return for it
            for (UCameraSensorComponent* camera : cameras)
                if (camera)
                    camera->setPixelsFrame(-1);
            return {};
        }
        if (!shapes.empty()) {
            const FrameShape& first = shapes.front().second;
            SP_CHECK(shape->width == first.width && shape->height == first.height, sp::InvalidArgument,
                     context, ": Cameras[", i, "] shows ", shape->width, "x", shape->height,
                     " images, Cameras[0] ", first.width, "x", first.height,
                     "; stacked cameras need one size");
            SP_CHECK(cameras[i]->bFinalColorAlpha == cameras.front()->bFinalColorAlpha, sp::InvalidArgument,
                     context, ": Cameras[", i, "] has bFinalColorAlpha ",
                     cameras[i]->bFinalColorAlpha ? "True" : "False", ", Cameras[0] ",
                     cameras.front()->bFinalColorAlpha ? "True" : "False", "; stacked cameras need one");
            SP_CHECK(shape->modalities == first.modalities, sp::InvalidArgument, context, ": Cameras[", i,
                     "] renders other modalities than Cameras[0] (", joined(shape->modalities.names()),
                     " against ", joined(first.modalities.names()), ")");
        }
        shapes.emplace_back(&subsystem, *shape);
    }
    // One array per modality with a leading camera axis; each camera's images are read into their slice.
    const FrameShape& shape = shapes.front().second;
    FCameraPixels pixels;
    std::vector<sp::render::OutputView> first;
    for (sp::render::Modality modality : shape.modalities.list())
        first.push_back(allocate(pixels, modality, shape.width, shape.height, int(cameras.size())));
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        std::vector<sp::render::OutputView> views = first;
        for (sp::render::OutputView& view : views)
            view.data = static_cast<std::byte*>(view.data) + i * view.size;
        if (!shapes[i].first->readInto(*cameras[i], views))
            return {};
    }
    if (!cameras.front()->bFinalColorAlpha)
        dropAlpha(pixels.final_color);
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

const sp::render::Renderer* RenderSubsystem::renderer() const {
    return gl_ ? gl_->renderer.get() : nullptr;
}

FRenderDeviceInfo RenderSubsystem::deviceInfo() {
    ensureRenderer();
    const sp::render::ContextReport& report = gl_->context->report();
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
    if (!gl_)
        return result;
    gl_->runQueued(); // counts this frame's renders
    // stats() collects timer queries, which needs the context current.
    gl_->context->makeCurrent();
    const sp::render::RenderStats stats = gl_->renderer->stats(scene_->scene().uid());
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
    result.UnshadowedInstances = int64_t(stats.unshadowedInstances);
    result.SplitInstances = int64_t(stats.splitInstances);
    result.WindingFacedInstances = int64_t(stats.windingFacedInstances);
    result.LightsLeftOut = int64_t(stats.lightsLeftOut);
    result.DrawCalls = int64_t(stats.drawCalls);
    result.MeshUploads = int64_t(stats.meshUploads);
    result.TextureUploads = int64_t(stats.textureUploads);
    const auto time = [&](sp::render::Pass pass) { return stats.passTimes[std::size_t(pass)]; };
    result.ShadowMs = time(sp::render::Pass::Shadow).gpuMs;
    result.SurfaceMs = time(sp::render::Pass::Surface).gpuMs;
    result.AttributeMs = time(sp::render::Pass::Attribute).gpuMs;
    result.ReadbackMs = time(sp::render::Pass::Readback).cpuMs;
    return result;
}

} // namespace sp::sensors
