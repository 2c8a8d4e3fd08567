#pragma once
// RenderSubsystem: the renderer of one world, made by the world's first camera. It mirrors the world by
// registration, as physics does: the world tells both of actors and components as they begin and end play
// (sp::world::WorldSubsystem), which it passes to its render scene and its camera list, so a frame never
// walks every actor. The worlds of one engine share one GL context and renderer (through the world's
// host; the renderer keeps each world's scene apart), started on the first frame of any of them that
// has a camera (worlds without cameras never touch EGL). Every frame, after the actors and physics ticked:
//   1. syncs the render scene with what it tracks: static mesh components (mesh, one material per slot,
//      world transform, visibility), light components and the sky light;
//   2. queues one render per camera sensor into that camera's render target (latency ring).
// Once every world ticked, the queued renders of all worlds run as one batch (OnWorldsTicked; see
// sp::render::Renderer::render): shadow maps first, then the views, so that a software rasteriser gets a
// few jobs a frame rather than two per world. read_pixels() then reads the due frame. Object ids are one per
// (component, material slot), assigned from a counter that never repeats, so they are stable while the
// component lives and never reused.

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/reflect/value.h"
#include "core/render/image_buffer.h"
#include "core/render/modality.h"
#include "core/sensors/camera_sensor_component.h"
#include "core/sensors/material_library.h"
#include "core/sensors/render_scene.h"
#include "core/world/world_subsystem.h"

class UWorld;
class UStaticMeshComponent;

namespace sp::render {
struct Camera;
class GlContext;
struct MeteringSettings;
class Renderer;
class RenderTarget;
class Scene;
} // namespace sp::render

namespace sp::pathtrace {
class IrradianceProbes;
class PathTracer;
} // namespace sp::pathtrace

namespace sp::sensors {

class RenderScene;
struct TracedImages;

class RenderSubsystem : public sp::world::WorldSubsystem {
  public:
    static constexpr int kTickOrder = sp::world::tick_order::kRendering;

    explicit RenderSubsystem(UWorld& world);
    ~RenderSubsystem() override;

    void Tick(double deltaSeconds) override;
    // Renders the cameras every world of the engine queued this frame, as one batch (the first world to be
    // told does it for all).
    void OnWorldsTicked() override;
    // Registration: the render scene and the camera list follow the world as things begin and end play.
    void OnActorBeginPlay(AActor& actor) override;
    void OnActorEndPlay(AActor& actor) override;
    void OnComponentBeginPlay(UActorComponent& component) override;
    void OnComponentEndPlay(UActorComponent& component) override;
    // The world as the render scene mirrors it (no GL: read without rendering).
    RenderScene& renderScene() { return *scene_; }

    // The due frame of `camera` (see UCameraSensorComponent); empty while priming or before the first
    // render. Reading twice returns the same images.
    FCameraPixels readPixels(UCameraSensorComponent& camera);
    // Renders `camera` at once, between frames: the world as it stands, as frame get_frame_count() (its
    // latency ring advances as a frame's render would). UCameraSensorComponent::RenderNow.
    void renderNow(UCameraSensorComponent& camera);
    // The due frames of cameras of any worlds, one array per modality with a leading camera axis, each
    // camera's images read into their slice (UCameraSensorComponent.read_pixels_stacked()).
    static FCameraPixels readPixelsStacked(const std::vector<UCameraSensorComponent*>& cameras,
                                           const char* context);

    // What readPixels would return now: the size and modalities of the due frame (none while priming).
    struct FrameShape {
        int width = 0;
        int height = 0;
        sp::render::ModalitySet modalities;
    };
    std::optional<FrameShape> dueShape(UCameraSensorComponent& camera) const;
    // Reads the due frame into `views` (one per modality of dueShape(), in list order, each of its size);
    // false, with nothing written, while priming.
    bool readInto(UCameraSensorComponent& camera, const std::vector<sp::render::OutputView>& views);

    struct ObjectIdInfo {
        sp::reflect::ObjectHandle component;
        int slot = -1;
        std::string materialName;
    };
    std::optional<ObjectIdInfo> objectIdInfo(std::uint32_t id) const;
    std::uint32_t objectId(sp::reflect::ObjectHandle component, int slot) const;
    std::uint32_t materialId(const std::string& name) const;

    // Makes the camera's next path-traced frame start a new image (its samples only), even when nothing
    // moved since the last one.
    void restartAccumulation(UCameraSensorComponent& camera);

    // Makes the camera's next frame a cut for its automatic exposure
    // (UCameraSensorComponent::ResetAutoExposure).
    void resetAutoExposure(UCameraSensorComponent& camera);

    // Starts the GL context and renderer if they are not running yet.
    FRenderDeviceInfo deviceInfo();
    // The renderer this world draws with (shared by the engine's worlds); null before its first render.
    const sp::render::Renderer* renderer() const;
    FRenderStats stats() const;

  private:
    struct CameraState;
    struct PendingFrame;
    struct Gl; // the GL context and renderer, shared with the engine's other worlds

    void ensureRenderer();
    // Lights the render scene's irradiance probes for the frame's rasterised cameras (none asking: no
    // volume).
    void updateIndirectLight(const std::vector<UCameraSensorComponent*>& cameras);
    const PendingFrame* dueFrame(UCameraSensorComponent& camera) const;
    // The EV100 that what `renderCamera` is about to show meters with `settings`: a small hdr_color render of
    // it, now (a cut of the camera's automatic exposure).
    double meterView(const UCameraSensorComponent& camera, const sp::render::Camera& renderCamera,
                     CameraState& state, const sp::render::MeteringSettings& settings);
    CameraState& cameraState(UCameraSensorComponent& camera);
    // Renders the camera's frame, which shows world frame `shownFrame`; `sizedShadowResolution` stands for
    // its ShadowResolution 0 (see Tick).
    void submit(UCameraSensorComponent& camera, int sizedShadowResolution, int64_t shownFrame);
    // Adds the camera's path-traced samples of this frame and returns the images of `modalities` that the
    // path tracer makes.
    // Sets renderCamera's exposure (the camera's automatic exposure meters the traced image).
    std::shared_ptr<const TracedImages> trace(UCameraSensorComponent& camera,
                                              sp::render::Camera& renderCamera,
                                              const sp::render::ModalitySet& modalities, CameraState& state);

    UWorld& world_;
    // Destruction order matters: the targets and the scene's GPU data go before this world lets go of
    // the shared renderer (the destructor releases them first, with the context current).
    std::shared_ptr<Gl> gl_;
    std::unique_ptr<RenderScene> scene_;                // from construction, to be told of what begins play
    std::unique_ptr<sp::pathtrace::PathTracer> tracer_; // started by the first path-traced camera or probes
    std::unique_ptr<sp::pathtrace::IrradianceProbes> probes_; // while a camera asks for indirect light
    PlayOrder<UCameraSensorComponent> cameraComponents_;      // the world's cameras in play
    std::map<sp::reflect::ObjectHandle, std::unique_ptr<CameraState>> cameras_;
};

} // namespace sp::sensors
