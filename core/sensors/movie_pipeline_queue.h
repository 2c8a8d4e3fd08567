#pragma once
// The offline render queue (UE's Movie Render Queue: UMoviePipelineQueueEngineSubsystem and its jobs). A job
// drives one camera through a list of poses, or through consecutive frames of the running world, and
// writes each output frame's images to files: 8-bit modalities (final_color) as PNG, float and id
// modalities as lossless OpenEXR (half, float or uint32, as read_pixels() returns them), and the camera's
// calibration as JSON:
//
//   <OutputDirectory>/<modality>/<frame>.png|.exr    e.g. out/final_color/0007.png, out/depth/0007.exr
//   <OutputDirectory>/camera/<frame>.json             K, distortion, world-to-camera, pose, engine frame,
//   samples
//   <OutputDirectory>/final_color.mp4                 with bWriteVideo, once every frame is written
//
// RenderJob() only queues a job: the work proceeds in the engine, one output frame per engine frame, while
// the client keeps stepping frames (each frame's images are those of that frame's world; a path-traced
// frame has exactly SamplesPerPixel samples, its own). IsRendering() and the job's GetProgress() say how
// far it is. Each file is written whole, and a frame's camera file last, so a job that is run again (after
// a crash, a cancel, or on another machine) skips the frames whose files are all there: resume. While a job
// renders, it owns its camera's size, modalities, samples and latency (and its pose, given poses); they are
// put back when it ends. A job that fails (its camera destroyed, a file that cannot be written) ends with
// status Failed and the error in GetErrorMessage(), logged; the engine and the rest of the queue go on.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/progress.h"
#include "core/sensors/camera_sensor_component.h"
#include "core/world/math.h"
#include "core/world/object.h"
#include "core/world/world_subsystem.h"

namespace sp::imageio {
class FileWriter;
} // namespace sp::imageio
namespace sp::sensors {
class MoviePipelineQueue;
} // namespace sp::sensors

/// Where a render job is in its life.
SPENUM()
enum class EMoviePipelineJobStatus : uint8_t {
    /// Allocated; SetConfiguration has not been called yet.
    Unconfigured = 0,
    /// Configured; RenderJob has not been called (or it ended and may be rendered again).
    Ready = 1,
    /// Waiting for the jobs before it.
    Queued = 2,
    /// Rendering, one output frame per engine frame.
    Rendering = 3,
    /// Every frame's files are written.
    Finished = 4,
    /// Cancel() or CancelAllJobs() stopped it; the frames written so far stay (a new run resumes).
    Cancelled = 5,
    /// An error stopped it (GetErrorMessage() says which); the frames written so far stay.
    Failed = 6,
};

/// What a render job renders, and where its files go.
SPSTRUCT()
struct FMoviePipelineConfiguration {
    SP_GENERATED_BODY()

    /// The folder the files go to (created when missing): <modality>/<frame>.png|.exr and
    /// camera/<frame>.json.
    SPPROPERTY()
    std::string OutputDirectory;
    /// The modalities written; empty: the camera's Modalities.
    SPPROPERTY()
    std::vector<ECameraModality> Modalities;
    /// Image width in pixels, in [1, 16384]; 0: the camera's Width.
    SPPROPERTY()
    int32_t Width = 0;
    /// Image height in pixels, in [1, 16384]; 0: the camera's Height.
    SPPROPERTY()
    int32_t Height = 0;
    /// Path-traced cameras: samples per pixel of each output frame, in [1, 65536] (each frame's own, never
    /// accumulated across frames); 0: the camera's SamplesPerPixel. Raster cameras ignore it.
    SPPROPERTY()
    int32_t SamplesPerPixel = 0;
    /// World locations of the camera, one per output frame; empty: the camera stays where the world puts it
    /// and output frame k is the k-th engine frame of the job (a recording of the running world).
    SPPROPERTY()
    std::vector<FVector> CameraLocations;
    /// World rotations of the camera, one per location.
    SPPROPERTY()
    std::vector<FRotator> CameraRotations;
    /// The first output frame rendered (>= 0); frames are numbered from 0 and name the files.
    SPPROPERTY()
    int32_t FrameStart = 0;
    /// One past the last output frame rendered; -1: the number of poses (required without poses).
    SPPROPERTY()
    int32_t FrameEnd = -1;
    /// Whether frames whose files all exist are rendered again (false: they are skipped, which resumes an
    /// interrupted job).
    SPPROPERTY()
    bool bOverwriteExisting = false;
    /// Also write final_color as a video, <OutputDirectory>/final_color.mp4 (H.264, constant quality with no
    /// visible loss; an odd width or height is padded by one repeated column or row), once every frame of the
    /// job is written. It is made from the frames' PNG files, so the video of a resumed job has every frame.
    /// final_color must be among the modalities.
    SPPROPERTY()
    bool bWriteVideo = false;
    /// The video's frames a second, in (0, 1000].
    SPPROPERTY()
    double VideoFrameRate = 30.0;
};

/// How far a render job is.
SPSTRUCT()
struct FMoviePipelineProgress {
    SP_GENERATED_BODY()

    /// Output frames in the job's range.
    SPPROPERTY()
    int32_t FramesTotal = 0;
    /// Frames rendered and written by this run.
    SPPROPERTY()
    int32_t FramesRendered = 0;
    /// Frames rendered whose files are still being written (on background threads, while the next frames
    /// render); a job ends only when this is 0.
    SPPROPERTY()
    int32_t FramesWriting = 0;
    /// Frames skipped because their files were already there.
    SPPROPERTY()
    int32_t FramesSkipped = 0;
    /// Seconds since the job started rendering (0 before).
    SPPROPERTY()
    double ElapsedSeconds = 0.0;
    /// Seconds left at the pace of the frames rendered so far (0 when finished; -1 before the first frame and
    /// after a cancel or a failure).
    SPPROPERTY()
    double EstimatedSecondsLeft = -1.0;
};

/// One render job: a camera, a configuration, and where rendering is.
SPCLASS(Abstract)
class UMoviePipelineExecutorJob : public UObject {
    SP_GENERATED_BODY()
  public:
    /// The name given to AllocateJob (used in progress and log lines).
    SPPROPERTY(ReadOnly)
    std::string JobName;

    /// Sets what the job renders; checked now (each field's range, poses that pair up, a frame range), and
    /// refused while the job is queued or rendering.
    SPFUNCTION()
    void SetConfiguration(const FMoviePipelineConfiguration& Configuration);

    /// Returns the configuration set last.
    SPFUNCTION()
    FMoviePipelineConfiguration GetConfiguration() const { return configuration_; }

    /// Returns the camera the job renders with, or None when it was destroyed.
    SPFUNCTION()
    UCameraSensorComponent* GetCamera() const;

    /// Returns where the job is.
    SPFUNCTION()
    EMoviePipelineJobStatus GetStatus() const { return status_; }

    /// Returns how far the job is (of its current or last run).
    SPFUNCTION()
    FMoviePipelineProgress GetProgress() const;

    /// Returns why the job failed, or "" when it did not.
    SPFUNCTION()
    std::string GetErrorMessage() const { return error_; }

    /// Returns the paths of the files output frame Frame writes: one per modality, then the camera file.
    SPFUNCTION()
    std::vector<std::string> GetOutputFiles(int32_t Frame) const;

    /// Stops the job (queued or rendering) now, once the frames being written are on disk; frames written
    /// stay.
    SPFUNCTION()
    void Cancel();

    // The queue that made this job, and the camera it renders with.
    void initJob(sp::reflect::ObjectHandle camera, sp::sensors::MoviePipelineQueue& queue);
    sp::reflect::ObjectHandle cameraHandle() const { return camera_; }
    void setStatus(EMoviePipelineJobStatus status, std::string error = {});
    FMoviePipelineProgress& progress() { return progress_; }
    // One past the last output frame of the configured range.
    int32_t frameEnd() const;

  private:
    sp::reflect::ObjectHandle camera_;
    sp::sensors::MoviePipelineQueue* queue_ = nullptr;
    FMoviePipelineConfiguration configuration_;
    EMoviePipelineJobStatus status_ = EMoviePipelineJobStatus::Unconfigured;
    FMoviePipelineProgress progress_;
    std::string error_;
};

/// A world's render queue (UE's UMoviePipelineQueueEngineSubsystem): jobs render one after another, in the
/// order RenderJob queued them.
SPCLASS(Abstract)
class UMoviePipelineQueueEngineSubsystem : public UObject {
    SP_GENERATED_BODY()
  public:
    /// Returns the render queue of WorldContextObject's world.
    SPFUNCTION(NotNull)
    static UMoviePipelineQueueEngineSubsystem*
    GetMoviePipelineQueueEngineSubsystem(UObject* WorldContextObject);

    /// Makes a job that renders with Camera (a camera of this world), named JobName ("" gives one).
    SPFUNCTION(NotNull)
    UMoviePipelineExecutorJob* AllocateJob(UCameraSensorComponent* Camera, const std::string& JobName = "");

    /// Queues a configured job and returns at once; it renders over the next engine frames. A job that
    /// ended (finished, cancelled, failed) may be queued again: it skips the frames already written.
    SPFUNCTION()
    void RenderJob(UMoviePipelineExecutorJob* Job);

    /// Returns whether a job is rendering or queued.
    SPFUNCTION()
    bool IsRendering() const;

    /// Returns the job rendering now, or None.
    SPFUNCTION()
    UMoviePipelineExecutorJob* GetActiveJob() const;

    /// Returns every job of this queue, in allocation order.
    SPFUNCTION()
    std::vector<UMoviePipelineExecutorJob*> GetJobs() const;

    /// Cancels the rendering job and every queued one.
    SPFUNCTION()
    void CancelAllJobs();

    /// Destroys a job that is not queued or rendering; its handles become stale.
    SPFUNCTION()
    void DeleteJob(UMoviePipelineExecutorJob* Job);

    void initQueue(sp::sensors::MoviePipelineQueue& queue) { queue_ = &queue; }

  private:
    sp::sensors::MoviePipelineQueue* queue_ = nullptr;
};

namespace sp::sensors {

// The C++ side of a world's render queue: owns the jobs and runs the active one. It ticks just before the
// world renders (to place and set up the camera for this frame's output frame) and, through a second
// subsystem, just after (to read the images and write the files).
class MoviePipelineQueue : public sp::world::WorldSubsystem {
  public:
    static constexpr int kTickOrder = sp::world::tick_order::kRendering - 1;

    explicit MoviePipelineQueue(UWorld& world);
    ~MoviePipelineQueue() override;

    void Tick(double deltaSeconds) override;
    // The second half of a frame's work, after the world rendered.
    void afterRender();

    UMoviePipelineQueueEngineSubsystem& object() { return *object_; }
    UMoviePipelineExecutorJob& allocate(UCameraSensorComponent& camera, const std::string& name);
    void enqueue(UMoviePipelineExecutorJob& job);
    void cancel(UMoviePipelineExecutorJob& job);
    void remove(UMoviePipelineExecutorJob& job);
    bool busy() const { return active_ || !queued_.empty(); }
    UMoviePipelineExecutorJob* active() const;
    std::vector<UMoviePipelineExecutorJob*> jobs() const;
    // The files output frame `frame` of `job` writes (modalities in list order, then the camera file).
    std::vector<std::string> outputFiles(const UMoviePipelineExecutorJob& job, int32_t frame) const;

  private:
    struct Run;

    void start(UMoviePipelineExecutorJob& job);
    // Sets the camera up for this engine frame's output frame (or skips it); false when the job ended.
    bool prepareFrame();
    // Ends the active run with `status`, putting the camera back as it was.
    void end(EMoviePipelineJobStatus status, std::string error = {});
    void fail(const std::exception& error);
    bool frameWritten(int32_t frame) const;
    // Reads the frame the camera rendered and hands its files to the writer.
    void writeFrame(UCameraSensorComponent& camera);
    // Counts the active run's frames the writer finished (and keeps the first error).
    void collectWritten();
    // The active run's final_color frames, read back from their files, as <folder>/final_color.mp4.
    void writeVideo();

    UWorld& world_;
    std::unique_ptr<UMoviePipelineQueueEngineSubsystem> object_;
    std::vector<std::unique_ptr<UMoviePipelineExecutorJob>> jobs_;
    std::vector<UMoviePipelineExecutorJob*> queued_;
    std::unique_ptr<Run> active_;
    // Started by the first frame written; destroyed first (members go bottom-up), waiting for its files.
    std::unique_ptr<sp::imageio::FileWriter> writer_;
    int nextJobNumber_ = 0;
};

} // namespace sp::sensors
