#include "core/render/render_target.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstring>

#include "core/base/error.h"
#include "core/render/derived_images.h"
#include "core/render/framebuffer_atlas.h"
#include "core/render/framebuffers.h"
#include "core/render/fxaa.h"
#include "core/render/parallel_copy.h"
#include "core/render/renderer.h"
#include "core/render/shader_program.h"
#include "core/render/shaders.h"

namespace sp::render {
namespace {

// How each modality is read from its target: the glReadPixels format and type.
struct ReadFormat {
    GLenum format;
    GLenum type;
};

ReadFormat readFormat(Modality modality, bool compact) {
    if (compact && modality == Modality::Normal)
        return {GL_RG, GL_FLOAT}; // the octahedral coordinates, decoded on the CPU
    if (compact && (kHalfTargets & targetBit(targetOf(modality))) != 0) {
        // The float16 bits, as 16-bit integers: the same channels.
        switch (readFormat(modality, false).format) {
        case GL_RGBA:
            return {GL_RGBA_INTEGER, GL_UNSIGNED_SHORT};
        case GL_RGB:
            return {GL_RGB_INTEGER, GL_UNSIGNED_SHORT};
        case GL_RED:
            return {GL_RED_INTEGER, GL_UNSIGNED_SHORT};
        case GL_GREEN:
            return {GL_GREEN_INTEGER, GL_UNSIGNED_SHORT};
        default:
            return {GL_BLUE_INTEGER, GL_UNSIGNED_SHORT};
        }
    }
    switch (modality) {
    case Modality::FinalColor:
        return {GL_RGBA, GL_UNSIGNED_BYTE};
    case Modality::HdrColor:
        return {GL_RGBA, GL_HALF_FLOAT};
    case Modality::DiffuseIllumination:
    case Modality::DiffuseOnly:
    case Modality::SpecularResidual:
    case Modality::BaseColor:
        return {GL_RGB, GL_HALF_FLOAT};
    case Modality::Depth:
        return {GL_RED, GL_FLOAT};
    case Modality::Position:
    case Modality::Normal:
        return {GL_RGB, GL_FLOAT};
    case Modality::ObjectIds:
        return {GL_RED_INTEGER, GL_UNSIGNED_INT};
    case Modality::MaterialIds:
        return {GL_GREEN_INTEGER, GL_UNSIGNED_INT};
    case Modality::Roughness:
        return {GL_RED, GL_HALF_FLOAT};
    case Modality::Metallic:
        return {GL_GREEN, GL_HALF_FLOAT};
    case Modality::MaterialAo:
        return {GL_BLUE, GL_HALF_FLOAT};
    }
    SP_THROW(InvalidArgument, "readFormat(): bad modality ", int(modality));
}

// The bytes a readback of the modality moves: the image's, but for a compact target's encoded normals.
std::size_t readBytes(Modality modality, bool compact, int width, int height) {
    if (compact && modality == Modality::Normal)
        return std::size_t(width) * std::size_t(height) * 2 * sizeof(float);
    return modalityByteSize(modality, width, height);
}

// Starts glReadPixels of one modality of the view `at` into the bound pixel-pack buffer (offset 0) or, with
// none bound, into `destination`.
void readTarget(const FramebufferAtlas::Place& at, Target target, ReadFormat format, int width, int height,
                void* destination) {
    const Framebuffers::Attachment source = at.layer >= 0 ? at.framebuffers->layerAttachment(target, at.layer)
                                                          : at.framebuffers->attachment(target);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, source.fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0 + source.index);
    glReadPixels(0, 0, width, height, format.format, format.type, destination);
}
void readModality(const FramebufferAtlas::Place& at, Modality modality, bool compact, int width, int height,
                  void* destination) {
    readTarget(at, targetOf(modality), readFormat(modality, compact), width, height, destination);
}
// The same for Target::Record (R32UI).
void readRecord(const FramebufferAtlas::Place& at, int width, int height, void* destination) {
    readTarget(at, Target::Record, {GL_RED_INTEGER, GL_UNSIGNED_INT}, width, height, destination);
}

// Copies one id channel into `buffer` (width x height uint32, glReadPixels' row order) with a compute pass.
// glReadPixels of one channel of the RG32UI ids target (GL_RED_INTEGER, GL_GREEN_INTEGER) takes NVIDIA's
// driver 4-6 ms at 1920x1080 on an H200 where a float image of the same size takes 0.8 ms
// (spear_render_bench); the copy costs a dispatch and moves the bytes once.
void packIds(Renderer& renderer, const FramebufferAtlas::Place& at, Modality modality, int width, int height,
             unsigned buffer) {
    const bool layered = at.layer >= 0;
    ShaderProgram& program = renderer.idChannelProgram(layered);
    program.use();
    program.set("uChannel", modality == Modality::ObjectIds ? 0 : 1);
    glProgramUniform2i(program.id(), program.location("uSize"), width, height);
    if (layered)
        program.set("uLayer", at.layer);
    glBindImageTexture(shaders::kIdsImageUnit, at.framebuffers->texture(Target::Ids), 0,
                       layered ? GL_TRUE : GL_FALSE, 0, GL_READ_ONLY, GL_RG32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shaders::kPackedIdsBinding, buffer);
    const int group = shaders::kIdChannelGroupSize;
    glDispatchCompute(GLuint((width + group - 1) / group), GLuint((height + group - 1) / group), 1);
    // The buffer's readers see the writes: a get or a mapping made afterwards, and a persistent mapping.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shaders::kPackedIdsBinding, 0);
}

} // namespace

FramebufferAtlas::Place RenderTarget::place() const {
    if (framebuffers_)
        return {framebuffers_.get(), -1};
    const FramebufferAtlas::Place layer = renderer_.atlas().place(this);
    SP_CHECK(layer.framebuffers != nullptr, InvalidState, "RenderTarget: no frame has been rendered");
    return layer;
}

RenderTarget::RenderTarget(Renderer& renderer, ModalitySet modalities, int latency)
    : renderer_(renderer), latency_(latency) {
    SP_CHECK(latency >= 0 && latency <= kMaxLatency, InvalidArgument,
             "RenderTarget::RenderTarget(): latency must be 0, 1 or 2 frames, got ", latency);
    setModalities(modalities);
    slots_.resize(static_cast<std::size_t>(latency) + 1);
}

RenderTarget::~RenderTarget() {
    renderer_.atlas().release(this); // its layer, if it took one (a GL call only when its page goes)
    if (submitted_ == 0)
        return; // nothing allocated: no GL call
    for (Slot& slot : slots_) {
        dropFence(slot);
        glDeleteBuffers(GLsizei(slot.buffers.size()), slot.buffers.data());
    }
    glDeleteBuffers(1, &idScratch_);
}

void RenderTarget::setModalities(ModalitySet modalities) {
    SP_CHECK(!modalities.empty(), InvalidArgument,
             "RenderTarget::setModalities(): the modality set is empty");
    modalities_ = modalities;
}

void RenderTarget::dropFence(Slot& slot) {
    if (slot.fence != nullptr)
        glDeleteSync(static_cast<GLsync>(slot.fence));
    slot.fence = nullptr;
    slot.pending = false;
}

std::uint64_t RenderTarget::submit(const Scene& scene, const Camera& camera) {
    const Submission submission{this, &scene, &camera};
    return submitAll(std::span<const Submission>(&submission, 1)).front();
}

std::vector<std::uint64_t> RenderTarget::submitAll(std::span<const Submission> submissions) {
    if (submissions.empty())
        return {};
    Renderer& renderer = submissions.front().target->renderer_;
    std::vector<Renderer::View> views;
    views.reserve(submissions.size());
    for (const Submission& s : submissions) {
        SP_CHECK(&s.target->renderer_ == &renderer, InvalidArgument,
                 "RenderTarget::submitAll(): the targets belong to different renderers");
        SP_CHECK(std::count_if(submissions.begin(), submissions.end(),
                               [&](const Submission& other) { return other.target == s.target; }) == 1,
                 InvalidArgument, "RenderTarget::submitAll(): a target is submitted twice in one batch");
        s.camera->params.validate("RenderTarget::submit");
    }
    // Small views take layers of shared framebuffers, the rest framebuffers of their own; then the views are
    // placed (taking a layer may give its page new framebuffers).
    std::vector<PassSet> passes;
    for (const Submission& s : submissions) {
        ModalityPlan& plan = s.target->plan_;
        ModalitySet uniform = materialModalities();
        const Scene::TexturedFactors textured = s.scene->texturedFactors();
        if (textured.baseColor)
            uniform.remove(Modality::BaseColor);
        if (textured.roughnessMetallic)
            uniform.remove(Modality::Roughness).remove(Modality::Metallic).remove(Modality::MaterialAo);
        // Multisampled or spatially sampled, every modality is drawn (none computed on the CPU from others:
        // diffuse_only from the exact base colour and the averaged illumination would not be the average of
        // the samples' products).
        // (Spatial samples stand in for MSAA's coverage samples: CameraParams::spatialSamples.)
        const bool msaa =
            s.camera->params.antiAliasing == AntiAliasing::Msaa && s.camera->params.spatialSamples == 1;
        const bool averaged = msaa || s.camera->params.spatialSamples > 1;
        plan = planModalities(s.target->modalities_, renderer.derivesOnCpu() && !averaged, uniform);
        plan.compactTargets = renderer.compactTargets() && !averaged;
        passes.push_back(plan.rendered.requiredPasses(s.camera->params.shadows));
        passes.back().compactTargets = plan.compactTargets;
        if (!plan.lookedUp.empty()) { // planned to fit the surface pass
            passes.back().surface = true;
            passes.back().surfaceTargets |= targetBit(Target::Record);
        }
        if (msaa)
            passes.back() =
                multisampled(passes.back(), std::min(s.camera->params.msaaSamples, renderer.maxSamples()));
        passes.back() = spatiallySampled(passes.back(), s.camera->params.spatialSamples);
        const int width = s.camera->params.width, height = s.camera->params.height;
        if (passes.back().samples == 1 && passes.back().spatialSamples == 1 &&
            renderer.atlas().suits(width, height)) {
            renderer.atlas().acquire(s.target, width, height, passes.back());
            s.target->framebuffers_.reset();
        } else {
            renderer.atlas().release(s.target);
            renderer.planComputeLighting(passes.back());
            if (!s.target->framebuffers_)
                s.target->framebuffers_ = std::make_unique<Framebuffers>();
            s.target->framebuffers_->ensure(width, height, passes.back());
        }
    }
    for (std::size_t i = 0; i < submissions.size(); ++i) {
        const Submission& s = submissions[i];
        const FramebufferAtlas::Place at = s.target->place();
        views.push_back({s.scene, s.camera, passes[i], at.framebuffers, at.layer,
                         s.target->plan_.lookedUp.empty() ? nullptr : &s.target->drawMaterials_});
        if (at.layer >= 0)
            renderer.atlas().drawing(*at.framebuffers);
    }
    renderer.render(views);
    std::vector<std::uint64_t> numbers;
    numbers.reserve(submissions.size());
    for (const Submission& s : submissions)
        numbers.push_back(s.target->queueReadback(*s.scene, *s.camera));
    glFlush(); // one flush for the batch: the driver starts on all of it
    return numbers;
}

std::uint64_t RenderTarget::queueReadback(const Scene& scene, const Camera& camera) {
    lastRead_ = nullptr; // latency 0's framebuffers take this frame: the last one cannot be read again
    const std::uint64_t frameNumber = ++submitted_;
    Slot& slot = slots_[frameNumber % slots_.size()];
    dropFence(slot); // an unread frame N + 1 submits old is dropped
    slot.frameNumber = frameNumber;
    slot.sceneUid = scene.uid();
    slot.camera = camera;
    slot.modalities = modalities_;
    slot.plan = plan_;
    slot.materials.swap(drawMaterials_); // what this frame's Target::Record names
    // A longer ring copies into pixel-buffer objects now, so that the framebuffers can take the next frames
    // while this one waits; so does latency 0 on a GPU (stagesReadback()), whose copy engine then moves
    // this view out while the next one is drawn. Otherwise latency 0 reads straight from the framebuffers
    // into the caller's memory when the frame is read (and not at all if it never is).
    slot.staged = stagesReadback();
    if (slot.staged) {
        // A buffer of `bytes` for slot.buffers[m], mapped once for good: on an NVIDIA H100, mapping and
        // unmapping each buffer at every read cost all 14 modalities at latency 1 a fifth of their frame
        // (14.4-15.1 against 11.6 ms).
        const auto bufferFor = [&](std::size_t m, std::size_t bytes, std::string_view what) {
            if (slot.capacity[m] == bytes)
                return;
            glDeleteBuffers(1, &slot.buffers[m]); // storage cannot be resized (0 is ignored)
            glCreateBuffers(1, &slot.buffers[m]);
            constexpr GLbitfield kMapping = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
            glNamedBufferStorage(slot.buffers[m], GLsizeiptr(bytes), nullptr,
                                 kMapping | GL_CLIENT_STORAGE_BIT);
            slot.mapped[m] = glMapNamedBufferRange(slot.buffers[m], 0, GLsizeiptr(bytes), kMapping);
            SP_CHECK(slot.mapped[m] != nullptr, InvalidState, "RenderTarget::submit(): cannot map the ", what,
                     " readback buffer of ", bytes, " bytes");
            slot.capacity[m] = bytes;
        };
        for (Modality modality : plan_.rendered.list()) {
            const auto m = static_cast<std::size_t>(modality);
            bufferFor(m, readBytes(modality, plan_.compactTargets, slot.width(), slot.height()),
                      modalityName(modality));
            if (packedOnGpu(modality)) {
                packIds(renderer_, place(), modality, slot.width(), slot.height(), slot.buffers[m]);
                continue;
            }
            glBindBuffer(GL_PIXEL_PACK_BUFFER, slot.buffers[m]);
            readModality(place(), modality, plan_.compactTargets, slot.width(), slot.height(), nullptr);
        }
        if (!plan_.lookedUp.empty()) {
            bufferFor(kRecordBuffer, std::size_t(slot.width()) * std::size_t(slot.height()) * 4, "record");
            glBindBuffer(GL_PIXEL_PACK_BUFFER, slot.buffers[kRecordBuffer]);
            readRecord(place(), slot.width(), slot.height(), nullptr);
        }
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }
    slot.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    slot.pending = true;
    const GLenum error = glGetError();
    SP_CHECK(error == GL_NO_ERROR, InvalidState, "RenderTarget::submit(): GL error 0x", std::hex, error,
             " while rendering frame ", std::dec, frameNumber);
    return frameNumber;
}

RenderTarget::Slot* RenderTarget::dueSlot() {
    if (submitted_ <= std::uint64_t(latency_))
        return nullptr; // priming
    const std::uint64_t due = submitted_ - std::uint64_t(latency_);
    Slot& slot = slots_[due % slots_.size()];
    if (!slot.pending || slot.frameNumber != due)
        return nullptr; // already read
    const GLenum status = glClientWaitSync(static_cast<GLsync>(slot.fence), GL_SYNC_FLUSH_COMMANDS_BIT,
                                           GLuint64(60) * 1000 * 1000 * 1000);
    SP_CHECK(status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED, InvalidState,
             "RenderTarget::read(): frame ", due, " did not finish within 60 s (status 0x", std::hex, status,
             ")");
    return &slot;
}

void RenderTarget::copyOut(Slot& slot, Modality modality, void* destination) {
    renderer_.beginReadback(slot.sceneUid);
    const bool compact = slot.plan.compactTargets;
    const std::size_t pixels = std::size_t(slot.width()) * std::size_t(slot.height());
    const bool decode = compact && modality == Modality::Normal; // octahedral coordinates to unit vectors
    if (!slot.staged) { // latency 0: the framebuffers still hold this frame, read straight into `destination`
        if (!decode) {
            readNow(modality, compact, slot.width(), slot.height(), destination);
        } else {
            normalScratch_.resize(2 * pixels);
            readNow(modality, compact, slot.width(), slot.height(), normalScratch_.data());
            decodeOctahedralNormals(normalScratch_.data(), static_cast<float*>(destination), pixels);
        }
        antiAlias(slot, modality, destination);
        renderer_.endReadback(slot.sceneUid);
        return;
    }
    const auto m = static_cast<std::size_t>(modality);
    if (decode)
        decodeOctahedralNormals(static_cast<const float*>(slot.mapped[m]), static_cast<float*>(destination),
                                pixels);
    else
        parallelCopy(destination, slot.mapped[m], modalityByteSize(modality, slot.width(), slot.height()),
                     renderer_.readbackThreads());
    antiAlias(slot, modality, destination);
    renderer_.endReadback(slot.sceneUid);
}

void RenderTarget::antiAlias(const Slot& slot, Modality modality, void* image) {
    if (modality == Modality::FinalColor && slot.camera.params.antiAliasing == AntiAliasing::Fxaa)
        fxaa(static_cast<std::uint8_t*>(image), slot.width(), slot.height(), defaultFxaaThreads());
}

void RenderTarget::readViews(Slot& slot, std::span<const OutputView> views) {
    for (const OutputView& view : views)
        if (!slot.plan.derived.contains(view.modality) && !slot.plan.lookedUp.contains(view.modality))
            copyOut(slot, view.modality, view.data);
    if (!slot.plan.lookedUp.empty())
        lookUp(slot, views);
    // diffuse_only before specular_residual, which is computed from it.
    for (Modality computed : {Modality::DiffuseOnly, Modality::SpecularResidual, Modality::Position})
        for (const OutputView& view : views)
            if (view.modality == computed && slot.plan.derived.contains(computed))
                derive(slot, computed, view.data, views);
}

void* RenderTarget::scratchFor(const Slot& slot, Modality modality) {
    std::vector<std::uint32_t>& scratch = deriveScratch_[static_cast<std::size_t>(modality)];
    scratch.resize((modalityByteSize(modality, slot.width(), slot.height()) + 3) / sizeof(std::uint32_t));
    return scratch.data();
}

void RenderTarget::lookUp(Slot& slot, std::span<const OutputView> views) {
    const std::size_t pixels = std::size_t(slot.width()) * std::size_t(slot.height());
    // Each looked-up modality into its view, or into scratch where a computed modality asked for needs it
    // (diffuse_only: base colour and metallic), or nowhere.
    ModalitySet needed;
    for (const OutputView& view : views)
        if (slot.plan.derived.contains(view.modality) && view.modality != Modality::Position)
            needed.add(Modality::BaseColor).add(Modality::Metallic); // the intrinsics' material inputs
    const auto into = [&](Modality m) -> void* {
        if (!slot.plan.lookedUp.contains(m))
            return nullptr;
        for (const OutputView& view : views)
            if (view.modality == m)
                return view.data;
        return needed.contains(m) ? scratchFor(slot, m) : nullptr;
    };
    MaterialImages out;
    out.objectIds = static_cast<std::uint32_t*>(into(Modality::ObjectIds));
    out.materialIds = static_cast<std::uint32_t*>(into(Modality::MaterialIds));
    out.baseColor = static_cast<std::uint16_t*>(into(Modality::BaseColor));
    out.roughness = static_cast<std::uint16_t*>(into(Modality::Roughness));
    out.metallic = static_cast<std::uint16_t*>(into(Modality::Metallic));
    out.ambientOcclusion = static_cast<std::uint16_t*>(into(Modality::MaterialAo));
    renderer_.beginReadback(slot.sceneUid);
    const std::uint32_t* record = static_cast<const std::uint32_t*>(slot.mapped[kRecordBuffer]);
    if (!slot.staged) { // latency 0: from the framebuffers
        recordScratch_.resize(pixels);
        readRecord(place(), slot.width(), slot.height(), recordScratch_.data());
        record = recordScratch_.data();
    }
    lookUpMaterials(record, slot.materials, pixels, out);
    renderer_.endReadback(slot.sceneUid);
}

void RenderTarget::derive(Slot& slot, Modality modality, void* destination,
                          std::span<const OutputView> read) {
    const std::size_t pixels = std::size_t(slot.width()) * std::size_t(slot.height());
    // An input's pixels: the view this read filled with it (readViews() computes diffuse_only before
    // specular_residual), else a scratch read of it.
    const auto input = [&](Modality in) -> const void* {
        for (const OutputView& view : read)
            if (view.modality == in)
                return view.data;
        void* scratch = scratchFor(slot, in);
        if (slot.plan.lookedUp.contains(in))
            return scratch; // filled by lookUp()
        if (in == Modality::DiffuseOnly)
            derive(slot, in, scratch, read);
        else
            copyOut(slot, in, scratch);
        return scratch;
    };
    const auto half = [&](Modality in) { return static_cast<const std::uint16_t*>(input(in)); };
    switch (modality) {
    case Modality::DiffuseOnly:
        computeDiffuseOnly(half(Modality::BaseColor), half(Modality::Metallic),
                           half(Modality::DiffuseIllumination), static_cast<std::uint16_t*>(destination),
                           pixels);
        return;
    case Modality::SpecularResidual:
        computeSpecularResidual(half(Modality::HdrColor), half(Modality::DiffuseOnly),
                                static_cast<std::uint16_t*>(destination), pixels);
        return;
    case Modality::Position:
        computePositionFromDepth(static_cast<const float*>(input(Modality::Depth)), slot.camera,
                                 static_cast<float*>(destination));
        return;
    default:
        SP_THROW(InvalidState, "RenderTarget::read(): ", modalityName(modality), " is not computed");
    }
}

bool RenderTarget::stagesReadback() const {
    return latency_ > 0 || (renderer_.stagedReadback() && framebuffers_ != nullptr);
}

bool RenderTarget::packedOnGpu(Modality modality) const {
    return (modality == Modality::ObjectIds || modality == Modality::MaterialIds) && renderer_.packIdsOnGpu();
}

void RenderTarget::readNow(Modality modality, bool compact, int width, int height, void* destination) {
    const FramebufferAtlas::Place at = place();
    if (!packedOnGpu(modality)) {
        if (at.layer >= 0 && readStaged(at, modality, compact, width, height, destination))
            return;
        readModality(at, modality, compact, width, height, destination);
        return;
    }
    const std::size_t bytes = modalityByteSize(modality, width, height);
    if (idScratch_ == 0)
        glCreateBuffers(1, &idScratch_);
    if (idScratchBytes_ != bytes) {
        glNamedBufferData(idScratch_, GLsizeiptr(bytes), nullptr, GL_STREAM_READ);
        idScratchBytes_ = bytes;
    }
    packIds(renderer_, place(), modality, width, height, idScratch_);
    glGetNamedBufferSubData(idScratch_, 0, GLsizeiptr(bytes), destination);
}

bool RenderTarget::readStaged(const FramebufferAtlas::Place& at, Modality modality, bool compact, int width,
                              int height, void* destination) {
    // Up to this much is copied at once (a page of sixteen 128 x 128 final_color views: 1 MiB).
    constexpr std::size_t kMostStagedBytes = std::size_t(64) << 20;
    FramebufferAtlas& atlas = renderer_.atlas();
    FramebufferAtlas::Staged* staged = atlas.staged(*at.framebuffers, modality);
    const std::size_t bytes = readBytes(modality, compact, width, height);
    const int layers = at.framebuffers->layers;
    if (staged == nullptr || bytes * std::size_t(layers) > kMostStagedBytes)
        return false;
    const std::uint64_t version = atlas.version(*at.framebuffers);
    if (staged->version != version) {
        staged->bytes.resize(bytes * std::size_t(layers));
        const ReadFormat format = readFormat(modality, compact);
        glGetTextureSubImage(at.framebuffers->texture(targetOf(modality)), 0, 0, 0, 0, width, height, layers,
                             format.format, format.type, GLsizei(staged->bytes.size()), staged->bytes.data());
        staged->version = version;
    }
    std::memcpy(destination, staged->bytes.data() + bytes * std::size_t(at.layer), bytes);
    return true;
}

std::optional<std::uint64_t> RenderTarget::read(Frame& frame) {
    Slot* slot = dueSlot();
    if (slot == nullptr)
        return std::nullopt;
    frame.retain(slot->modalities); // reuses buffers across frames of the same size
    frame.frameNumber = slot->frameNumber;
    frame.width = slot->width();
    frame.height = slot->height();
    std::vector<OutputView> views;
    for (Modality modality : slot->modalities.list()) {
        ImageBuffer& image = frame.prepare(modality, slot->width(), slot->height());
        views.push_back({modality, image.bytes.data(), image.bytes.size()});
    }
    readViews(*slot, views);
    dropFence(*slot);
    lastRead_ = slot;
    return frame.frameNumber;
}

void RenderTarget::checkViews(const Slot& slot, std::span<const OutputView> views) {
    for (const OutputView& view : views) {
        SP_CHECK(slot.modalities.contains(view.modality), InvalidArgument, "RenderTarget::read(): frame ",
                 slot.frameNumber, " was not rendered with modality '", modalityName(view.modality), "'");
        const std::size_t expected = modalityByteSize(view.modality, slot.width(), slot.height());
        SP_CHECK(view.data != nullptr && view.size == expected, InvalidArgument,
                 "RenderTarget::read(): the view for '", modalityName(view.modality), "' has ", view.size,
                 " bytes, expected ", expected, " (", slot.height(), "x", slot.width(), "x",
                 modalityInfo(view.modality).channels, " ", dtypeName(modalityInfo(view.modality).dtype),
                 ")");
    }
}

std::optional<std::uint64_t> RenderTarget::readAgain(std::span<const OutputView> views) {
    if (lastRead_ == nullptr)
        return std::nullopt;
    checkViews(*lastRead_, views);
    // A frame read straight from the framebuffers (latency 0) is read from them again, as they hold it
    // until the next submit; a staged one from the slot's pixel-buffer objects, which hold it until the
    // slot is reused.
    readViews(*lastRead_, views);
    return lastRead_->frameNumber;
}

std::optional<std::uint64_t> RenderTarget::read(std::span<const OutputView> views) {
    // Validate against the frame that would be read before waiting or writing anything.
    if (submitted_ > std::uint64_t(latency_))
        checkViews(slots_[(submitted_ - latency_) % slots_.size()], views);
    Slot* slot = dueSlot();
    if (slot == nullptr)
        return std::nullopt;
    readViews(*slot, views);
    const std::uint64_t number = slot->frameNumber;
    dropFence(*slot);
    lastRead_ = slot;
    return number;
}

std::optional<std::uint64_t> RenderTarget::render(const Scene& scene, const Camera& camera, Frame& frame) {
    submit(scene, camera);
    return read(frame);
}

} // namespace sp::render
