// Latency 0, 1, 2: read() returns the frame submitted `latency` submits earlier, nothing while priming,
// each frame once; readAgain() reads that frame again until the next submit; reads into caller memory
// check sizes before writing.

#include <algorithm>
#include <cstring>
#include <string_view>

#include "core/render/image_buffer.h"
#include "gl_fixture.h"
#include "test_scenes.h"

namespace sp::render::test {
namespace {

class RenderLatencyGlTest : public GlTest, public ::testing::WithParamInterface<int> {
  protected:
    void SetUp() override {
        mesh_ = scene_.addMesh(primitives::box({6, 6, 6}));
        material_ = scene_.addMaterial(Material{});
        instance_ = scene_.addInstance({mesh_, {material_}, {1}});
        camera_ = cameraLookingAt({-6, 0, 0}, {0, 0, 0}, 8, 8);
    }
    // Frame k shows the box with object id 1000 + k.
    std::uint64_t submitFrame(RenderTarget& target, std::uint64_t k) {
        scene_.setInstance(instance_, {mesh_, {material_}, {std::uint32_t(1000 + k)}});
        return target.submit(scene_, camera_);
    }
    Scene scene_;
    MeshId mesh_;
    MaterialId material_;
    InstanceId instance_;
    Camera camera_;
};

TEST_P(RenderLatencyGlTest, ReadReturnsTheFrameLatencySubmitsEarlier) {
    const int latency = GetParam();
    RenderTarget target(renderer(), {Modality::ObjectIds, Modality::Depth}, latency);
    Frame frame;
    for (std::uint64_t k = 1; k <= 6; ++k) {
        ASSERT_EQ(submitFrame(target, k), k);
        std::optional<std::uint64_t> got = target.read(frame);
        if (k <= std::uint64_t(latency)) {
            EXPECT_FALSE(got.has_value()) << "priming: no frame " << int(k) - latency;
            continue;
        }
        ASSERT_TRUE(got.has_value());
        EXPECT_EQ(*got, k - latency);
        EXPECT_EQ(frame.frameNumber, k - latency);
        EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(4, 4), 1000 + k - latency);
        EXPECT_FALSE(target.read(frame).has_value()) << "a frame is read once";
    }
}

TEST_P(RenderLatencyGlTest, UnreadFramesAreDroppedNotQueued) {
    const int latency = GetParam();
    RenderTarget target(renderer(), {Modality::ObjectIds}, latency);
    for (std::uint64_t k = 1; k <= 5; ++k)
        submitFrame(target, k);
    Frame frame;
    ASSERT_EQ(target.read(frame), 5u - latency);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(4, 4), 1000 + 5 - latency);
}

TEST_P(RenderLatencyGlTest, ReadsIntoCallerMemory) {
    const int latency = GetParam();
    RenderTarget target(renderer(), {Modality::ObjectIds, Modality::FinalColor}, latency);
    std::vector<std::uint32_t> ids(8 * 8, 0xdeadbeef);
    std::vector<std::uint8_t> color(8 * 8 * 4);
    const OutputView views[] = {{Modality::ObjectIds, ids.data(), ids.size() * 4},
                                {Modality::FinalColor, color.data(), color.size()}};
    for (std::uint64_t k = 1; k <= std::uint64_t(latency) + 1; ++k) {
        submitFrame(target, k);
        std::optional<std::uint64_t> got = target.read(views);
        if (k <= std::uint64_t(latency)) {
            EXPECT_FALSE(got.has_value());
            EXPECT_EQ(ids[0], 0xdeadbeef) << "priming leaves caller memory untouched";
        } else {
            EXPECT_EQ(got, 1u);
            EXPECT_EQ(ids[4 * 8 + 4], 1001u);
            EXPECT_EQ(ids[0], 1001u); // the box fills the view
            EXPECT_EQ(color[3], 255);
        }
    }
}

TEST_P(RenderLatencyGlTest, TheLastFrameReadCanBeReadAgainUntilTheNextSubmit) {
    const int latency = GetParam();
    RenderTarget target(renderer(), {Modality::ObjectIds}, latency);
    std::vector<std::uint32_t> ids(8 * 8, 0), again(8 * 8, 0);
    const OutputView view[] = {{Modality::ObjectIds, ids.data(), ids.size() * 4}};
    const OutputView viewAgain[] = {{Modality::ObjectIds, again.data(), again.size() * 4}};
    for (std::uint64_t k = 1; k <= std::uint64_t(latency) + 2; ++k) {
        submitFrame(target, k);
        EXPECT_FALSE(target.readAgain(viewAgain).has_value()) << "nothing read since the submit";
        const std::optional<std::uint64_t> got = target.read(view);
        if (!got)
            continue; // priming
        // Frames submitted after it do not change what is read again (the ring keeps the frame).
        EXPECT_EQ(target.readAgain(viewAgain), got);
        EXPECT_EQ(again, ids);
        EXPECT_EQ(again[4 * 8 + 4], 1000 + *got);
        EXPECT_EQ(target.readAgain(viewAgain), got) << "as often as asked";
    }
    std::vector<std::uint32_t> small(4);
    const OutputView wrong[] = {{Modality::ObjectIds, small.data(), small.size() * 4}};
    EXPECT_THROW(target.readAgain(wrong), InvalidArgument);
}

TEST_P(RenderLatencyGlTest, IdsReadTheSameThroughTheComputeCopyAsThroughTheDriver) {
    // The compute copy runs by default on hardware only (Renderer::packIdsOnGpu()), so it is forced here;
    // a size that is not a multiple of the copy's 16 x 16 work groups, and a view with background in it.
    const int latency = GetParam();
    camera_ = cameraLookingAt({-20, 0, 0}, {0, 0, 0}, 37, 21);
    const bool byDefault = renderer().packIdsOnGpu();
    std::vector<std::uint32_t> frames[2][2]; // [compute][object, material] ids of the frame read
    for (int compute = 0; compute < 2; ++compute) {
        renderer().setPackIdsOnGpu(compute == 1);
        RenderTarget target(renderer(), {Modality::ObjectIds, Modality::MaterialIds, Modality::Depth},
                            latency);
        for (std::uint64_t k = 1; k <= std::uint64_t(latency) + 1; ++k)
            submitFrame(target, k);
        Frame frame;
        ASSERT_EQ(target.read(frame), 1u);
        for (int i = 0; i < 2; ++i) {
            std::span<const std::uint32_t> ids =
                frame.get(i == 0 ? Modality::ObjectIds : Modality::MaterialIds).as<std::uint32_t>();
            frames[compute][i].assign(ids.begin(), ids.end());
        }
        EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(18, 10), 1001u) << "compute " << compute;
        EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(0, 0), 0u) << "background, compute " << compute;
        // Read again into caller memory (latency 0 copies from the framebuffers once more).
        std::vector<std::uint32_t> again(37 * 21, 0xdeadbeef);
        const OutputView view[] = {{Modality::MaterialIds, again.data(), again.size() * 4}};
        EXPECT_EQ(target.readAgain(view), 1u);
        EXPECT_EQ(again, frames[compute][1]);
    }
    renderer().setPackIdsOnGpu(byDefault);
    EXPECT_EQ(frames[1][0], frames[0][0]);
    EXPECT_EQ(frames[1][1], frames[0][1]);
}

INSTANTIATE_TEST_SUITE_P(Latency, RenderLatencyGlTest, ::testing::Values(0, 1, 2));

using RenderTargetGlTest = RenderLatencyGlTest;

TEST_F(RenderTargetGlTest, CallerMemoryOfTheWrongSizeIsRejectedBeforeWriting) {
    RenderTarget target(renderer(), {Modality::Depth}, 0);
    submitFrame(target, 1);
    std::vector<float> depth(10, -1.0f);
    const OutputView tooSmall[] = {{Modality::Depth, depth.data(), depth.size() * 4}};
    try {
        target.read(tooSmall);
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(),
                     "RenderTarget::read(): the view for 'depth' has 40 bytes, expected 256 (8x8x1 float32)");
    }
    EXPECT_EQ(depth[0], -1.0f);
    const OutputView notRendered[] = {{Modality::Normal, depth.data(), depth.size() * 4}};
    EXPECT_THROW(target.read(notRendered), InvalidArgument);
    // The frame is still there for a correct read.
    std::vector<float> full(64);
    const OutputView good[] = {{Modality::Depth, full.data(), full.size() * 4}};
    EXPECT_EQ(target.read(good), 1u);
    EXPECT_NEAR(full[4 * 8 + 4], 3.0f, 1e-4f); // camera 6 m from the centre of a 6 m box
}

TEST_F(RenderTargetGlTest, FramesKeepTheSizeTheyWereRenderedWith) {
    // Latency 1 alternates two slots; a slot whose next frame has another size gets new readback buffers.
    RenderTarget target(renderer(), {Modality::Depth, Modality::ObjectIds}, 1);
    submitFrame(target, 1); // 8 x 8
    camera_.params.width = 4;
    camera_.params.height = 2;
    submitFrame(target, 2);
    Frame frame;
    ASSERT_EQ(target.read(frame), 1u);
    EXPECT_EQ(frame.get(Modality::Depth).width, 8);
    submitFrame(target, 3); // 4 x 2 into frame 1's 8 x 8 slot
    ASSERT_EQ(target.read(frame), 2u);
    EXPECT_EQ(frame.get(Modality::Depth).width, 4);
    EXPECT_EQ(frame.get(Modality::Depth).height, 2);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(2, 1), 1002u);
    camera_.params.width = 8;
    camera_.params.height = 8;
    submitFrame(target, 4); // 8 x 8 into frame 2's 4 x 2 slot
    ASSERT_EQ(target.read(frame), 3u);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(2, 1), 1003u);
    submitFrame(target, 5);
    ASSERT_EQ(target.read(frame), 4u);
    EXPECT_EQ(frame.get(Modality::Depth).width, 8);
    EXPECT_NEAR(frame.get(Modality::Depth).at(4, 4), 3.0f, 1e-4f);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(4, 4), 1004u);
}

TEST_F(RenderTargetGlTest, StagedLatencyZeroReadsTheSameBytesAsDirect) {
    // Latency 0 of a view with framebuffers of its own (over 512 x 512 pixels) queues its readback into
    // pixel-buffer objects at submit where Renderer::stagedReadback() asks for it (on a GPU by default):
    // forced both ways here, with the copy out split across 4 threads (normal: 4 MB, over the 2 MiB at
    // which parallelCopy() splits), the ids through the compute copy, then read again.
    mesh_ = scene_.addMesh(primitives::sphere(2.0f, 24, 12));
    scene_.setInstance(instance_, {mesh_, {material_}, {7}});
    scene_.addLight({});
    camera_ = cameraLookingAt({-9, 2, 1}, {0, 0, 0}, 700, 500);
    const bool stagedByDefault = renderer().stagedReadback(), packByDefault = renderer().packIdsOnGpu();
    const int threadsByDefault = renderer().readbackThreads();
    renderer().setReadbackThreads(4);
    renderer().setPackIdsOnGpu(true);
    const ModalitySet modalities{Modality::FinalColor, Modality::Depth, Modality::Normal,
                                 Modality::ObjectIds};
    const std::vector<Modality> list = modalities.list();
    std::vector<std::uint8_t> read[2][4], again[2][4];
    // Zeroed buffers of each modality's size, and the views that write into them.
    const auto viewsInto = [&](std::vector<std::uint8_t>(&buffers)[4]) {
        std::vector<OutputView> views;
        for (std::size_t m = 0; m < 4; ++m) {
            buffers[m].assign(modalityByteSize(list[m], 700, 500), 0);
            views.push_back({list[m], buffers[m].data(), buffers[m].size()});
        }
        return views;
    };
    for (int staged = 0; staged < 2; ++staged) {
        renderer().setStagedReadback(staged == 1);
        RenderTarget target(renderer(), modalities, 0);
        for (int k = 0; k < 2; ++k) { // the second frame reuses the slot's buffers
            target.submit(scene_, camera_);
            ASSERT_EQ(target.read(viewsInto(read[staged])), std::uint64_t(k + 1)) << "staged " << staged;
        }
        ASSERT_EQ(target.readAgain(viewsInto(again[staged])), 2u) << "staged " << staged;
    }
    renderer().setStagedReadback(stagedByDefault);
    renderer().setPackIdsOnGpu(packByDefault);
    renderer().setReadbackThreads(threadsByDefault);
    for (std::size_t m = 0; m < 4; ++m) {
        const std::string_view name = modalityName(list[m]);
        EXPECT_EQ(read[1][m], read[0][m]) << name;
        EXPECT_EQ(again[1][m], read[1][m]) << name << " read again";
        EXPECT_EQ(again[0][m], read[0][m]) << name << " read again, direct";
    }
    const auto idsAt = std::size_t(std::find(list.begin(), list.end(), Modality::ObjectIds) - list.begin());
    ASSERT_LT(idsAt, list.size());
    const auto* ids = reinterpret_cast<const std::uint32_t*>(read[1][idsAt].data());
    EXPECT_EQ(ids[250 * 700 + 350], 7u) << "the sphere is in the middle of the view";
    EXPECT_EQ(ids[0], 0u) << "background in the corner";
}

TEST_F(RenderTargetGlTest, BadLatencyIsRejected) {
    try {
        RenderTarget target(renderer(), {Modality::Depth}, 3);
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "RenderTarget::RenderTarget(): latency must be 0, 1 or 2 frames, got 3");
    }
    EXPECT_THROW(RenderTarget(renderer(), ModalitySet(), 0), InvalidArgument);
}

TEST_F(RenderTargetGlTest, RemovedMeshOrMaterialCannotReachTheGpu) {
    RenderTarget target(renderer(), {Modality::ObjectIds}, 0);
    Frame frame;
    target.render(scene_, camera_, frame);
    scene_.removeInstance(instance_);
    scene_.removeMesh(mesh_);
    EXPECT_THROW(scene_.addInstance({mesh_, {material_}, {1}}), StaleObject);
    target.render(scene_, camera_, frame);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(4, 4), 0u);
}

} // namespace
} // namespace sp::render::test
