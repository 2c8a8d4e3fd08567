#pragma once
// A camera's render target with asynchronous readback: a ring of latency + 1 slots, each holding one
// pixel-buffer object per modality and a fence.
//
// Latency semantics (frames are numbered 1, 2, ... by submit()):
//   - latency 0: read() after submit() number k returns frame k (rendered and read in the same call);
//   - latency N: read() after submit() number k returns frame k - N, so the GPU has N frames of slack;
//   - priming: while k <= N there is no frame k - N, and read() returns std::nullopt without touching
//     the outputs; a frame is returned at most once (a second read() before the next submit() returns
//     std::nullopt); a frame never read is dropped when its slot is reused N + 1 submits later.
// Each slot remembers the size and modalities it was rendered with, so camera size or modality changes
// take effect from the next submit while earlier frames are still read back as they were rendered.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/render/camera.h"
#include "core/render/derived_images.h"
#include "core/render/framebuffer_atlas.h"
#include "core/render/image_buffer.h"
#include "core/render/modality.h"
#include "core/render/scene.h"

namespace sp::render {

class Framebuffers;
class Renderer;

class RenderTarget {
  public:
    static constexpr int kMaxLatency = 2;

    // Throws sp::InvalidArgument for a latency outside [0, 2] or an empty modality set.
    RenderTarget(Renderer& renderer, ModalitySet modalities, int latency = 0);
    ~RenderTarget();
    RenderTarget(const RenderTarget&) = delete;
    RenderTarget& operator=(const RenderTarget&) = delete;

    // Renders the passes the modalities need and queues their readback; returns the frame number.
    std::uint64_t submit(const Scene& scene, const Camera& camera);
    // One target's frame of a batch.
    struct Submission {
        RenderTarget* target = nullptr;
        const Scene* scene = nullptr;
        const Camera* camera = nullptr;
    };
    // Submits a frame of each target (of one renderer, each at most once) as one batch (Renderer::render):
    // the same frames as one submit() each, in fewer jobs for the driver. Returns their frame numbers.
    static std::vector<std::uint64_t> submitAll(std::span<const Submission> submissions);
    // Reads the frame due (see the header comment) into `frame`, allocating one buffer per modality;
    // returns its frame number, or std::nullopt while priming or when it was already read.
    std::optional<std::uint64_t> read(Frame& frame);
    // Same, into caller memory: one view per modality to read (a subset of the frame's modalities), each
    // exactly modalityByteSize() bytes. Throws sp::InvalidArgument for a wrong size or a modality the
    // frame was not rendered with, before anything is written.
    std::optional<std::uint64_t> read(std::span<const OutputView> views);
    // Reads the frame the last read() returned once more, into caller memory (checked as read(views)
    // checks); possible until the next submit(), std::nullopt otherwise. Lets a reader hand out fresh
    // memory for a second look at a frame instead of keeping the first copy.
    std::optional<std::uint64_t> readAgain(std::span<const OutputView> views);
    // submit() then read(frame).
    std::optional<std::uint64_t> render(const Scene& scene, const Camera& camera, Frame& frame);

    void setModalities(ModalitySet modalities);
    const ModalitySet& modalities() const { return modalities_; }
    int latency() const { return latency_; }
    std::uint64_t submittedFrames() const { return submitted_; }

  private:
    struct Slot {
        std::uint64_t frameNumber = 0;
        std::uint64_t sceneUid = 0; // the scene rendered, whose statistics count the readback
        bool pending = false;
        // Its readback was queued into `buffers` at submit (else: latency 0's direct read).
        bool staged = false;
        Camera camera; // the frame's (position is computed from its depth and this camera)
        int width() const { return camera.params.width; }
        int height() const { return camera.params.height; }
        ModalitySet modalities; // as asked for (what the frame can be read as)
        ModalityPlan plan;      // rendered, and computed from those when read (planModalities())
        void* fence = nullptr;
        // The pixel-buffer objects a staged readback lands in, by modality: immutable storage in the
        // client's memory, mapped for reading once when made (persistent, coherent), so that a read copies
        // out of `mapped` without mapping each time.
        // (One more, kRecordBuffer, for Target::Record.)
        std::array<unsigned, kModalityCount + 1> buffers{};
        std::array<std::size_t, kModalityCount + 1> capacity{};
        std::array<const void*, kModalityCount + 1> mapped{};
        // What Target::Record names, when the plan looks modalities up (ModalityPlan::lookedUp).
        std::vector<DrawMaterial> materials;
    };
    static constexpr std::size_t kRecordBuffer = kModalityCount;
    // Where the frames are drawn: a layer of the renderer's shared framebuffers (FramebufferAtlas) for a
    // small view, framebuffers of its own otherwise.
    FramebufferAtlas::Place place() const;
    // After the frame is rendered: takes its slot, queues a longer ring's readback and the fence; returns the
    // frame number.
    std::uint64_t queueReadback(const Scene& scene, const Camera& camera);
    // Whether this frame's readback is queued into the slot's pixel-buffer objects at submit: always with
    // a longer ring, at latency 0 where Renderer::stagedReadback() asks for it and the view has
    // framebuffers of its own (a layer of a shared page is read with its page: readStaged()).
    bool stagesReadback() const;
    // The slot holding the frame due for reading, or null.
    Slot* dueSlot();
    void copyOut(Slot& slot, Modality modality, void* destination);
    // Filters final_color as read into `image` where the frame's camera asks for FXAA (fxaa.h).
    static void antiAlias(const Slot& slot, Modality modality, void* image);
    // Reads `views` of the slot's frame: the rendered modalities first, then those computed from them (from
    // the views just read where they hold the inputs, else from scratch reads).
    void readViews(Slot& slot, std::span<const OutputView> views);
    // Fills the views of looked-up modalities (ModalityPlan::lookedUp), and the scratch of those the
    // computed modalities need, from Target::Record and the slot's draw materials.
    void lookUp(Slot& slot, std::span<const OutputView> views);
    // The scratch image of a modality not asked for that a computed one needs, sized for the slot's frame.
    void* scratchFor(const Slot& slot, Modality modality);
    // A computed modality (slot.plan.derived) into `destination`; `read`: the views already filled.
    void derive(Slot& slot, Modality modality, void* destination, std::span<const OutputView> read);
    // Whether `modality` is read through the renderer's compute copy (Renderer::packIdsOnGpu()).
    bool packedOnGpu(Modality modality) const;
    // Reads a modality of the frame the framebuffers hold into `destination` (latency 0); from `compact`
    // targets, the normal as its octahedral coordinates (two floats a pixel).
    void readNow(Modality modality, bool compact, int width, int height, void* destination);
    // The same for a layer of a page, from the page's copy of all its layers (FramebufferAtlas::Staged);
    // false when the page is too large to copy whole.
    bool readStaged(const FramebufferAtlas::Place& at, Modality modality, bool compact, int width, int height,
                    void* destination);
    // Throws sp::InvalidArgument unless each view fits a modality `slot` was rendered with.
    static void checkViews(const Slot& slot, std::span<const OutputView> views);
    void dropFence(Slot& slot);

    Renderer& renderer_;
    ModalitySet modalities_;
    ModalityPlan plan_; // of modalities_, as the last submit made it
    int latency_;
    std::uint64_t submitted_ = 0;
    Slot* lastRead_ = nullptr; // the slot read since the last submit(), for readAgain()
    std::vector<Slot> slots_;
    std::unique_ptr<Framebuffers> framebuffers_; // a large view's own (null while it holds a layer)
    unsigned idScratch_ = 0; // latency 0's id readback: the packed channel, then copied out
    std::size_t idScratchBytes_ = 0;
    // The inputs of computed modalities that were not asked for themselves, by modality (raw bytes).
    std::array<std::vector<std::uint32_t>, kModalityCount> deriveScratch_;
    std::vector<float> normalScratch_; // latency 0's encoded normals of compact targets, before decoding
    std::vector<DrawMaterial> drawMaterials_;  // the renderer's for the frame being submitted
    std::vector<std::uint32_t> recordScratch_; // latency 0's Target::Record, before the lookups
};

} // namespace sp::render
