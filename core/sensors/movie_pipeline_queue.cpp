#include "core/sensors/movie_pipeline_queue.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/regular_file.h"
#include "core/imageio/exr.h"
#include "core/imageio/file_writer.h"
#include "core/imageio/png.h"
#include "core/imageio/video.h"
#include "core/render/image_buffer.h"
#include "core/render/modality.h"
#include "core/render/texture_image.h"
#include "core/sensors/render_subsystem.h"
#include "core/world/object_access.h"
#include "core/world/world.h"

namespace sp::sensors {
namespace {

constexpr const char* kQueue = "UMoviePipelineQueueEngineSubsystem";
// Images waiting to be written, at most (one frame always may, whatever its size).
constexpr std::size_t kMaxBytesInFlight = std::size_t(1) << 30;

// Runs after the world rendered, so that the queue reads the images of this frame.
class MoviePipelineOutput : public sp::world::WorldSubsystem {
  public:
    static constexpr int kTickOrder = sp::world::tick_order::kRendering + 1;
    explicit MoviePipelineOutput(UWorld& world) : world_(world) {}
    void Tick(double /*deltaSeconds*/) override {
        if (auto* queue = world_.FindSubsystem<MoviePipelineQueue>())
            queue->afterRender();
    }

  private:
    UWorld& world_;
};

std::string frameName(int32_t frame) {
    char name[16];
    std::snprintf(name, sizeof name, "%04d", int(frame));
    return name;
}

// PNG for 8-bit images, EXR for the rest (half, float, uint32), as read_pixels() returns them.
bool isPng(sp::render::Modality modality) {
    return sp::render::modalityInfo(modality).dtype == sp::render::DType::UInt8;
}

sp::imageio::PixelType pixelType(sp::render::DType dtype) {
    switch (dtype) {
    case sp::render::DType::UInt8:
        return sp::imageio::PixelType::UInt8;
    case sp::render::DType::UInt32:
        return sp::imageio::PixelType::UInt32;
    case sp::render::DType::Float16:
        return sp::imageio::PixelType::Half;
    case sp::render::DType::Float32:
        return sp::imageio::PixelType::Float;
    }
    return sp::imageio::PixelType::Float;
}

std::vector<ECameraModality> effectiveModalities(const FMoviePipelineConfiguration& configuration,
                                                 const UCameraSensorComponent* camera) {
    if (!configuration.Modalities.empty() || camera == nullptr)
        return configuration.Modalities;
    return camera->Modalities;
}

// Whether final_color is among `modalities` (what the video, bWriteVideo, is made of).
bool hasFinalColor(const std::vector<ECameraModality>& modalities) {
    return std::find(modalities.begin(), modalities.end(), ECameraModality::FinalColor) != modalities.end();
}

UCameraSensorComponent* findCamera(sp::reflect::ObjectHandle handle) {
    return dynamic_cast<UCameraSensorComponent*>(sp::reflect::ObjectTable::find(handle));
}

// Where output frame `frame`'s image of `modality` goes, and its camera file.
std::string imageFile(const std::string& folder, sp::render::Modality modality, int32_t frame) {
    const std::string name = frameName(frame) + (isPng(modality) ? ".png" : ".exr");
    return (std::filesystem::path(folder) / std::string(sp::render::modalityName(modality)) / name).string();
}
std::string cameraFile(const std::string& folder, int32_t frame) {
    return (std::filesystem::path(folder) / "camera" / (frameName(frame) + ".json")).string();
}

// Every file output frame `frame` writes into `folder`: one per modality, in list order, then the camera
// file.
std::vector<std::string> frameFiles(const std::string& folder, const std::vector<ECameraModality>& modalities,
                                    int32_t frame) {
    std::vector<std::string> files;
    for (ECameraModality modality : modalities)
        files.push_back(imageFile(folder, static_cast<sp::render::Modality>(modality), frame));
    files.push_back(cameraFile(folder, frame));
    return files;
}

nlohmann::json matrix(const sp::reflect::SpArray<double>& array) {
    const std::vector<int64_t>& shape = array.getShape();
    nlohmann::json rows = nlohmann::json::array();
    for (int64_t i = 0; i < shape[0]; ++i) {
        nlohmann::json row = nlohmann::json::array();
        for (int64_t j = 0; j < shape[1]; ++j)
            row.push_back(array.data()[i * shape[1] + j]);
        rows.push_back(std::move(row));
    }
    return rows;
}

} // namespace

// The active job's run: what it renders, where it is, and the camera settings it put aside.
struct MoviePipelineQueue::Run {
    UMoviePipelineExecutorJob* job = nullptr;
    FMoviePipelineConfiguration configuration;
    std::vector<ECameraModality> modalities;
    bool poses = false;
    int32_t frame = 0; // the output frame of this engine frame
    int32_t end = 0;
    bool renderThisFrame = false;
    std::string
        folder; // OutputDirectory resolved once (absolute), so a later change of directory does not move it
    std::set<std::uint64_t> writing; // the writer's tickets of this run's frames being written
    std::string writeError;          // the first frame that could not be written
    std::chrono::steady_clock::time_point started;
    std::optional<std::chrono::steady_clock::time_point> firstRender; // of this run, for the ETA
    std::unique_ptr<sp::base::Progress> progress;

    struct Saved {
        int32_t width, height, samplesPerPixel, latency;
        std::vector<ECameraModality> modalities;
        FTransform relative;
    } saved{};
};

MoviePipelineQueue::MoviePipelineQueue(UWorld& world)
    : world_(world), object_(std::make_unique<UMoviePipelineQueueEngineSubsystem>()) {
    object_->InitObject("MoviePipelineQueueEngineSubsystem", &world);
    object_->initQueue(*this);
    world.GetSubsystem<MoviePipelineOutput>();
}

MoviePipelineQueue::~MoviePipelineQueue() {
    for (const auto& job : jobs_)
        sp::reflect::ObjectTable::rememberName(*job);
    sp::reflect::ObjectTable::rememberName(*object_);
}

UMoviePipelineExecutorJob& MoviePipelineQueue::allocate(UCameraSensorComponent& camera,
                                                        const std::string& name) {
    auto job = std::make_unique<UMoviePipelineExecutorJob>();
    const std::string jobName = name.empty() ? "RenderJob_" + std::to_string(nextJobNumber_) : name;
    ++nextJobNumber_;
    job->InitObject(jobName, &world_);
    job->JobName = jobName;
    job->initJob(camera.GetHandle(), *this);
    jobs_.push_back(std::move(job));
    return *jobs_.back();
}

void MoviePipelineQueue::enqueue(UMoviePipelineExecutorJob& job) {
    const std::string who = std::string(kQueue) + ".RenderJob(): job '" + job.JobName + "'";
    switch (job.GetStatus()) {
    case EMoviePipelineJobStatus::Unconfigured:
        SP_THROW(InvalidState, who, " has no configuration; call its SetConfiguration() first");
    case EMoviePipelineJobStatus::Queued:
    case EMoviePipelineJobStatus::Rendering:
        SP_THROW(InvalidState, who, " is already queued or rendering");
    default:
        break;
    }
    SP_CHECK(findCamera(job.cameraHandle()), InvalidState, who, "'s camera was destroyed");
    job.setStatus(EMoviePipelineJobStatus::Queued);
    job.progress() = FMoviePipelineProgress{};
    queued_.push_back(&job);
}

void MoviePipelineQueue::cancel(UMoviePipelineExecutorJob& job) {
    if (active_ && active_->job == &job) {
        end(EMoviePipelineJobStatus::Cancelled);
        return;
    }
    if (auto it = std::find(queued_.begin(), queued_.end(), &job); it != queued_.end()) {
        queued_.erase(it);
        job.setStatus(EMoviePipelineJobStatus::Cancelled);
    }
}

void MoviePipelineQueue::remove(UMoviePipelineExecutorJob& job) {
    SP_CHECK(job.GetStatus() != EMoviePipelineJobStatus::Queued &&
                 job.GetStatus() != EMoviePipelineJobStatus::Rendering,
             InvalidState, kQueue, ".DeleteJob(): job '", job.JobName,
             "' is queued or rendering; cancel it first");
    auto it =
        std::find_if(jobs_.begin(), jobs_.end(), [&](const auto& owned) { return owned.get() == &job; });
    sp::reflect::ObjectTable::rememberName(job);
    jobs_.erase(it);
}

UMoviePipelineExecutorJob* MoviePipelineQueue::active() const {
    return active_ ? active_->job : nullptr;
}

std::vector<UMoviePipelineExecutorJob*> MoviePipelineQueue::jobs() const {
    std::vector<UMoviePipelineExecutorJob*> list;
    for (const auto& job : jobs_)
        list.push_back(job.get());
    return list;
}

std::vector<std::string> MoviePipelineQueue::outputFiles(const UMoviePipelineExecutorJob& job,
                                                         int32_t frame) const {
    const FMoviePipelineConfiguration& configuration =
        active_ && active_->job == &job ? active_->configuration : job.GetConfiguration();
    const std::vector<ECameraModality> modalities =
        active_ && active_->job == &job ? active_->modalities
                                        : effectiveModalities(configuration, findCamera(job.cameraHandle()));
    return frameFiles(configuration.OutputDirectory, modalities, frame);
}

bool MoviePipelineQueue::frameWritten(int32_t frame) const {
    const Run& run = *active_;
    if (run.configuration.bOverwriteExisting)
        return false;
    std::error_code error;
    for (const std::string& file : frameFiles(run.folder, run.modalities, frame))
        if (!std::filesystem::is_regular_file(file, error))
            return false;
    return true;
}

void MoviePipelineQueue::start(UMoviePipelineExecutorJob& job) {
    const std::string function = std::string(kQueue) + ".RenderJob()";
    UCameraSensorComponent* camera = findCamera(job.cameraHandle());
    SP_CHECK(camera, InvalidState, function, ": job '", job.JobName, "'s camera was destroyed");
    auto run = std::make_unique<Run>();
    run->job = &job;
    run->configuration = job.GetConfiguration();
    run->modalities = effectiveModalities(run->configuration, camera);
    SP_CHECK(!run->modalities.empty(), InvalidArgument, function, ": job '", job.JobName,
             "' renders no modality (its configuration and its camera list none)");
    SP_CHECK(!run->configuration.bWriteVideo || hasFinalColor(run->modalities), InvalidArgument, function,
             ": job '", job.JobName,
             "' writes final_color as a video (bWriteVideo), but its camera does not render final_color");
    run->poses = !run->configuration.CameraLocations.empty();
    SP_CHECK(!run->poses || camera->Mobility != EComponentMobility::Static, InvalidState, function, ": job '",
             job.JobName, "' moves its camera through poses, but ", camera->GetDebugName(),
             " is static; set its Mobility to Movable");
    run->end = job.frameEnd();
    run->frame = run->poses ? run->configuration.FrameStart : 0;
    run->started = std::chrono::steady_clock::now();
    run->saved = {camera->Width,   camera->Height,     camera->SamplesPerPixel,
                  camera->Latency, camera->Modalities, camera->GetRelativeTransform()};

    // The folders first: a job that cannot write fails before it touches the camera.
    const std::filesystem::path folder = std::filesystem::absolute(
        resolveUserPath(run->configuration.OutputDirectory, function, "output folder", FileAccess::Write));
    run->folder = folder.string();
    std::vector<std::string> folders{"camera"};
    for (ECameraModality modality : run->modalities)
        folders.emplace_back(sp::render::modalityName(static_cast<sp::render::Modality>(modality)));
    for (const std::string& name : folders) {
        std::error_code error;
        std::filesystem::create_directories(folder / name, error);
        SP_CHECK(!error, InvalidArgument, function, ": cannot create folder '", (folder / name).string(),
                 "': ", error.message());
    }
    const int32_t total = run->end - run->configuration.FrameStart;
    run->progress = std::make_unique<sp::base::Progress>(
        "render job '" + job.JobName + "': " + std::to_string(total) + " frames", double(total));
    job.progress().FramesTotal = total;
    job.setStatus(EMoviePipelineJobStatus::Rendering);
    active_ = std::move(run);
}

void MoviePipelineQueue::end(EMoviePipelineJobStatus status, std::string error) {
    // Frames being written are finished first: a job that ended writes nothing more.
    if (writer_)
        writer_->waitAll();
    collectWritten();
    if (!active_->writeError.empty() && status != EMoviePipelineJobStatus::Failed) {
        SP_LOG("render job '", active_->job->JobName, "': ", active_->writeError);
        if (status == EMoviePipelineJobStatus::Finished)
            status = EMoviePipelineJobStatus::Failed;
        error = active_->writeError;
    }
    if (status == EMoviePipelineJobStatus::Finished && active_->configuration.bWriteVideo) {
        try {
            writeVideo();
        } catch (const std::exception& failure) {
            SP_LOG("render job '", active_->job->JobName, "': ", failure.what());
            status = EMoviePipelineJobStatus::Failed;
            error = failure.what();
        }
    }
    std::unique_ptr<Run> run = std::move(active_);
    FMoviePipelineProgress& progress = run->job->progress();
    progress.ElapsedSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - run->started).count();
    progress.EstimatedSecondsLeft = status == EMoviePipelineJobStatus::Finished ? 0.0 : -1.0;
    run->job->setStatus(status, std::move(error));
    // The camera as it was; nothing here may throw, as end() runs from error handlers too.
    if (UCameraSensorComponent* camera = findCamera(run->job->cameraHandle())) {
        camera->Width = run->saved.width;
        camera->Height = run->saved.height;
        camera->SamplesPerPixel = run->saved.samplesPerPixel;
        camera->Latency = run->saved.latency;
        camera->Modalities = run->saved.modalities;
        camera->setRenderSuspended(false);
        if (run->poses) {
            try {
                camera->SetRelativeTransform(run->saved.relative);
            } catch (const std::exception& failure) {
                SP_LOG("render job '", run->job->JobName,
                       "' could not put its camera back: ", failure.what());
            }
        }
    }
}

void MoviePipelineQueue::fail(const std::exception& error) {
    if (!active_)
        return;
    SP_LOG("render job '", active_->job->JobName, "' failed: ", error.what());
    end(EMoviePipelineJobStatus::Failed, error.what());
}

void MoviePipelineQueue::Tick(double /*deltaSeconds*/) {
    // A job that fails to start, or ends here without rendering (every frame already written), leaves this
    // engine frame to the next job in the queue.
    for (;;) {
        if (!active_) {
            if (queued_.empty())
                return;
            UMoviePipelineExecutorJob& job = *queued_.front();
            queued_.erase(queued_.begin());
            try {
                start(job);
            } catch (const std::exception& error) {
                SP_LOG("render job '", job.JobName, "' failed: ", error.what());
                job.setStatus(EMoviePipelineJobStatus::Failed, error.what());
                continue;
            }
        }
        if (prepareFrame())
            return;
    }
}

bool MoviePipelineQueue::prepareFrame() {
    Run& run = *active_;
    run.renderThisFrame = false;
    try {
        collectWritten();
        SP_CHECK(run.writeError.empty(), InvalidArgument, run.writeError);
        UCameraSensorComponent* camera = findCamera(run.job->cameraHandle());
        SP_CHECK(camera, InvalidState, "render job '", run.job->JobName, "': its camera was destroyed");
        FMoviePipelineProgress& progress = run.job->progress();
        // Frames whose files are all there are skipped: at once with poses, by letting their engine frame
        // pass without rendering without them (the world must still get there).
        if (run.poses)
            for (; run.frame < run.end && frameWritten(run.frame); ++run.frame)
                ++progress.FramesSkipped;
        if (run.frame >= run.end) {
            end(EMoviePipelineJobStatus::Finished);
            return false;
        }
        const bool inRange = run.frame >= run.configuration.FrameStart;
        if (!inRange || frameWritten(run.frame)) {
            camera->setRenderSuspended(true);
            return true;
        }
        const FMoviePipelineConfiguration& c = run.configuration;
        camera->Width = c.Width > 0 ? c.Width : run.saved.width;
        camera->Height = c.Height > 0 ? c.Height : run.saved.height;
        camera->SamplesPerPixel = c.SamplesPerPixel > 0 ? c.SamplesPerPixel : run.saved.samplesPerPixel;
        camera->Modalities = run.modalities;
        camera->Latency = 0;
        camera->setRenderSuspended(false);
        if (run.poses) {
            camera->SetWorldLocation(c.CameraLocations[std::size_t(run.frame)]);
            camera->SetWorldRotation(c.CameraRotations[std::size_t(run.frame)]);
        }
        // Each output frame has its own samples, even when nothing moved since the last one.
        world_.GetSubsystem<RenderSubsystem>().restartAccumulation(*camera);
        run.renderThisFrame = true;
        if (!run.firstRender)
            run.firstRender = std::chrono::steady_clock::now();
        return true;
    } catch (const std::exception& error) {
        fail(error);
        return false;
    }
}

void MoviePipelineQueue::afterRender() {
    if (!active_)
        return;
    Run& run = *active_;
    try {
        UCameraSensorComponent* camera = findCamera(run.job->cameraHandle());
        SP_CHECK(camera, InvalidState, "render job '", run.job->JobName, "': its camera was destroyed");
        if (run.renderThisFrame)
            writeFrame(*camera);
        else if (run.frame >= run.configuration.FrameStart)
            ++run.job->progress().FramesSkipped;
        camera->setRenderSuspended(false);
        ++run.frame;
        collectWritten();
        SP_CHECK(run.writeError.empty(), InvalidArgument, run.writeError);
        // The last frame waits for the files still being written, so that when IsRendering() turns false
        // every file is on disk.
        if (run.frame >= run.end)
            end(EMoviePipelineJobStatus::Finished);
    } catch (const std::exception& error) {
        fail(error);
    }
}

void MoviePipelineQueue::writeVideo() {
    const Run& run = *active_;
    const std::string function = "render job '" + run.job->JobName + "'";
    const int32_t first = run.configuration.FrameStart;
    const std::string file = (std::filesystem::path(run.folder) / "final_color.mp4").string();
    std::optional<sp::imageio::Mp4Encoder> encoder;
    sp::base::Progress progress(function + ": " + file, double(run.end - first));
    for (int32_t frame = first; frame < run.end; ++frame) {
        const sp::render::TextureImage image =
            sp::render::TextureImage::load(imageFile(run.folder, sp::render::Modality::FinalColor, frame));
        if (!encoder)
            encoder.emplace(image.width, image.height, run.configuration.VideoFrameRate, function);
        encoder->add({image.width, image.height, 4, sp::imageio::PixelType::UInt8, image.rgba.data()});
        progress.advance(1.0);
    }
    sp::writeRegularFile(file, encoder->finish(), function, "video");
}

void MoviePipelineQueue::writeFrame(UCameraSensorComponent& camera) {
    Run& run = *active_;
    const std::string function = "render job '" + run.job->JobName + "'";
    RenderSubsystem& render = world_.GetSubsystem<RenderSubsystem>();
    const std::optional<RenderSubsystem::FrameShape> shape = render.dueShape(camera);
    SP_CHECK(shape, InvalidState, function, ": frame ", run.frame, " was not rendered");

    // What the writer's thread needs, owned by the task: the images, their files, and the camera record.
    struct FrameFiles {
        struct File {
            std::string path;
            sp::render::Modality modality;
            std::vector<std::byte> pixels;
        };
        std::vector<File> images;
        std::string cameraPath, cameraRecord, function;
        int width = 0, height = 0;
    };
    auto files = std::make_shared<FrameFiles>();
    files->width = shape->width;
    files->height = shape->height;
    files->function = function;
    std::vector<sp::render::OutputView> views;
    for (sp::render::Modality modality : shape->modalities.list())
        files->images.push_back(
            {imageFile(run.folder, modality, run.frame), modality,
             std::vector<std::byte>(sp::render::modalityByteSize(modality, shape->width, shape->height))});
    for (FrameFiles::File& file : files->images)
        views.push_back({file.modality, file.pixels.data(), file.pixels.size()});
    SP_CHECK(render.readInto(camera, views), InvalidState, function, ": frame ", run.frame,
             " could not be read");

    const FTransform pose = camera.GetComponentTransform();
    const FRotator rotation = camera.GetComponentRotation();
    const nlohmann::json record{
        {"frame", run.frame},
        {"engine_frame", world_.get_frame_count() + 1},
        {"width", shape->width},
        {"height", shape->height},
        {"intrinsic_matrix", matrix(camera.GetIntrinsicMatrix())},
        {"world_to_camera", matrix(camera.GetWorldToCamera())},
        {"distortion_coefficients", camera.GetDistortionCoefficients().getView()},
        {"location", {pose.Translation.X, pose.Translation.Y, pose.Translation.Z}},
        {"rotation", {{"Pitch", rotation.Pitch}, {"Yaw", rotation.Yaw}, {"Roll", rotation.Roll}}},
        {"renderer", camera.Renderer == ECameraRenderer::PathTraced ? "path_traced" : "raster"},
        {"samples_per_pixel", camera.GetAccumulatedSamples()},
    };
    files->cameraPath = cameraFile(run.folder, run.frame);
    files->cameraRecord = record.dump() + "\n";

    if (!writer_) { // threads beside the renderer's: encoding overlaps the next frames
        const int threads = int(std::clamp(std::thread::hardware_concurrency(), 2u, 8u));
        writer_ = std::make_unique<sp::imageio::FileWriter>(threads, threads + 1, kMaxBytesInFlight);
    }
    std::size_t bytes = 0;
    for (const FrameFiles::File& file : files->images)
        bytes += file.pixels.size();
    const std::uint64_t ticket = writer_->submit(bytes, [files] {
        // An older camera file goes first: until the new one is written the frame is not whole (a run that
        // overwrites and stops midway must not leave new images beside an old camera file).
        std::error_code stale;
        std::filesystem::remove(files->cameraPath, stale);
        for (const FrameFiles::File& file : files->images) {
            const sp::render::ModalityInfo& info = sp::render::modalityInfo(file.modality);
            const sp::imageio::ImageView image{files->width, files->height, info.channels,
                                               pixelType(info.dtype), file.pixels.data()};
            if (isPng(file.modality))
                sp::imageio::writePng(file.path, image, files->function);
            else
                sp::imageio::writeExr(file.path, image, files->function);
        }
        // The camera file last: its presence means the frame is whole.
        writeRegularFile(files->cameraPath, files->cameraRecord, files->function, "camera file");
    });
    run.writing.insert(ticket);
}

void MoviePipelineQueue::collectWritten() {
    if (!active_)
        return;
    Run& run = *active_;
    FMoviePipelineProgress& progress = run.job->progress();
    for (const sp::imageio::FileWriter::Finished& done :
         writer_ ? writer_->takeFinished() : std::vector<sp::imageio::FileWriter::Finished>{}) {
        if (!run.writing.erase(done.ticket))
            continue; // a task of an earlier run
        if (!done.error.empty() && run.writeError.empty())
            run.writeError = done.error;
        else if (done.error.empty())
            ++progress.FramesRendered;
    }
    progress.FramesWriting = int32_t(run.writing.size());
    const auto now = std::chrono::steady_clock::now();
    progress.ElapsedSeconds = std::chrono::duration<double>(now - run.started).count();
    // The pace of rendering (frames being written included) since this run's first rendered frame.
    const int32_t rendered = progress.FramesRendered + progress.FramesWriting;
    if (run.firstRender && rendered > 0) {
        const double seconds = std::chrono::duration<double>(now - *run.firstRender).count();
        const int32_t left = progress.FramesTotal - rendered - progress.FramesSkipped;
        progress.EstimatedSecondsLeft = seconds / rendered * std::max(left, 0);
    }
    run.progress->set(progress.FramesRendered + progress.FramesSkipped);
}

} // namespace sp::sensors

// -- UMoviePipelineExecutorJob ------------------------------------------------------------------------------

void UMoviePipelineExecutorJob::initJob(sp::reflect::ObjectHandle camera,
                                        sp::sensors::MoviePipelineQueue& queue) {
    camera_ = camera;
    queue_ = &queue;
}

void UMoviePipelineExecutorJob::setStatus(EMoviePipelineJobStatus status, std::string error) {
    status_ = status;
    error_ = std::move(error);
}

int32_t UMoviePipelineExecutorJob::frameEnd() const {
    return configuration_.FrameEnd >= 0 ? configuration_.FrameEnd
                                        : int32_t(configuration_.CameraLocations.size());
}

void UMoviePipelineExecutorJob::SetConfiguration(const FMoviePipelineConfiguration& Configuration) {
    const std::string who = "UMoviePipelineExecutorJob.SetConfiguration(): ";
    SP_CHECK(status_ != EMoviePipelineJobStatus::Queued && status_ != EMoviePipelineJobStatus::Rendering,
             sp::InvalidState, who, "job '", JobName, "' is queued or rendering; cancel it first");
    const FMoviePipelineConfiguration& c = Configuration;
    SP_CHECK(!c.OutputDirectory.empty(), sp::InvalidArgument, who, "OutputDirectory is empty");
    SP_CHECK(c.Width == 0 || (c.Width >= 1 && c.Width <= 16384), sp::InvalidArgument, who,
             "Width must be 0 (the camera's) or in [1, 16384], got ", c.Width);
    SP_CHECK(c.Height == 0 || (c.Height >= 1 && c.Height <= 16384), sp::InvalidArgument, who,
             "Height must be 0 (the camera's) or in [1, 16384], got ", c.Height);
    SP_CHECK(c.SamplesPerPixel >= 0 && c.SamplesPerPixel <= 65536, sp::InvalidArgument, who,
             "SamplesPerPixel must be 0 (the camera's) or in [1, 65536], got ", c.SamplesPerPixel);
    SP_CHECK(c.CameraLocations.size() == c.CameraRotations.size(), sp::InvalidArgument, who,
             "CameraLocations has ", c.CameraLocations.size(), " poses and CameraRotations ",
             c.CameraRotations.size(), "; they pair up");
    for (std::size_t i = 0; i < c.CameraLocations.size(); ++i) {
        const FVector& l = c.CameraLocations[i];
        const FRotator& r = c.CameraRotations[i];
        SP_CHECK(std::isfinite(l.X) && std::isfinite(l.Y) && std::isfinite(l.Z), sp::InvalidArgument, who,
                 "CameraLocations[", i, "] must be finite, got (", l.X, ", ", l.Y, ", ", l.Z, ")");
        SP_CHECK(std::isfinite(r.Pitch) && std::isfinite(r.Yaw) && std::isfinite(r.Roll), sp::InvalidArgument,
                 who, "CameraRotations[", i, "] must be finite, got (Pitch ", r.Pitch, ", Yaw ", r.Yaw,
                 ", Roll ", r.Roll, ")");
    }
    SP_CHECK(c.FrameStart >= 0, sp::InvalidArgument, who, "FrameStart must be >= 0, got ", c.FrameStart);
    const int64_t poses = int64_t(c.CameraLocations.size());
    if (poses == 0)
        SP_CHECK(c.FrameEnd > c.FrameStart, sp::InvalidArgument, who,
                 "without CameraLocations, FrameEnd must be given and exceed FrameStart (", c.FrameStart,
                 "), got ", c.FrameEnd);
    else
        SP_CHECK(
            (c.FrameEnd == -1 && c.FrameStart < poses) || (c.FrameEnd > c.FrameStart && c.FrameEnd <= poses),
            sp::InvalidArgument, who, "frames [", c.FrameStart, ", ", c.FrameEnd == -1 ? poses : c.FrameEnd,
            ") are not a non-empty range within the ", poses, " poses");
    SP_CHECK(c.VideoFrameRate > 0.0 && c.VideoFrameRate <= 1000.0, sp::InvalidArgument, who,
             "VideoFrameRate must be in (0, 1000] frames a second, got ", c.VideoFrameRate);
    SP_CHECK(!c.bWriteVideo || c.Modalities.empty() || sp::sensors::hasFinalColor(c.Modalities),
             sp::InvalidArgument, who,
             "bWriteVideo writes final_color as a video, which Modalities leaves out");
    configuration_ = Configuration;
    status_ = EMoviePipelineJobStatus::Ready;
    error_.clear();
}

UCameraSensorComponent* UMoviePipelineExecutorJob::GetCamera() const {
    return dynamic_cast<UCameraSensorComponent*>(sp::reflect::ObjectTable::find(camera_));
}

FMoviePipelineProgress UMoviePipelineExecutorJob::GetProgress() const {
    return progress_;
}

std::vector<std::string> UMoviePipelineExecutorJob::GetOutputFiles(int32_t Frame) const {
    SP_CHECK(status_ != EMoviePipelineJobStatus::Unconfigured, sp::InvalidState,
             "UMoviePipelineExecutorJob.GetOutputFiles(): job '", JobName, "' has no configuration yet");
    SP_CHECK(Frame >= 0, sp::InvalidArgument,
             "UMoviePipelineExecutorJob.GetOutputFiles(): Frame must be >= 0, got ", Frame);
    return queue_->outputFiles(*this, Frame);
}

void UMoviePipelineExecutorJob::Cancel() {
    queue_->cancel(*this);
}

// -- UMoviePipelineQueueEngineSubsystem ---------------------------------------------------------------------

UMoviePipelineQueueEngineSubsystem*
UMoviePipelineQueueEngineSubsystem::GetMoviePipelineQueueEngineSubsystem(UObject* WorldContextObject) {
    UWorld& world = sp::world::worldOfContext(
        WorldContextObject, "UMoviePipelineQueueEngineSubsystem.GetMoviePipelineQueueEngineSubsystem()");
    return &world.GetSubsystem<sp::sensors::MoviePipelineQueue>().object();
}

UMoviePipelineExecutorJob* UMoviePipelineQueueEngineSubsystem::AllocateJob(UCameraSensorComponent* Camera,
                                                                           const std::string& JobName) {
    SP_CHECK(Camera, sp::InvalidArgument, "UMoviePipelineQueueEngineSubsystem.AllocateJob(): Camera is None");
    SP_CHECK(Camera->GetWorld() == GetWorld(), sp::InvalidArgument,
             "UMoviePipelineQueueEngineSubsystem.AllocateJob(): Camera ", Camera->GetDebugName(),
             " is not in this queue's world");
    return &queue_->allocate(*Camera, JobName);
}

namespace {

UMoviePipelineExecutorJob& jobOfQueue(UMoviePipelineExecutorJob* job, const UObject& queue,
                                      const char* function) {
    SP_CHECK(job, sp::InvalidArgument, "UMoviePipelineQueueEngineSubsystem.", function, "(): Job is None");
    SP_CHECK(job->GetWorld() == queue.GetWorld(), sp::InvalidArgument, "UMoviePipelineQueueEngineSubsystem.",
             function, "(): job '", job->JobName, "' belongs to another world's queue");
    return *job;
}

} // namespace

void UMoviePipelineQueueEngineSubsystem::RenderJob(UMoviePipelineExecutorJob* Job) {
    queue_->enqueue(jobOfQueue(Job, *this, "RenderJob"));
}

bool UMoviePipelineQueueEngineSubsystem::IsRendering() const {
    return queue_->busy();
}

UMoviePipelineExecutorJob* UMoviePipelineQueueEngineSubsystem::GetActiveJob() const {
    return queue_->active();
}

std::vector<UMoviePipelineExecutorJob*> UMoviePipelineQueueEngineSubsystem::GetJobs() const {
    return queue_->jobs();
}

void UMoviePipelineQueueEngineSubsystem::CancelAllJobs() {
    for (UMoviePipelineExecutorJob* job : queue_->jobs())
        queue_->cancel(*job);
}

void UMoviePipelineQueueEngineSubsystem::DeleteJob(UMoviePipelineExecutorJob* Job) {
    queue_->remove(jobOfQueue(Job, *this, "DeleteJob"));
}
