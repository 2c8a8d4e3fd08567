// A motion read from the committed humanoid's file: the bones of each frame are the clip's pose at that
// frame's time; the file moves no rigid object; bad rates and clips are refused naming them. (A file with
// objects: tests/python/test_motion.py, which writes one.)
#include <gtest/gtest.h>

#include <string>

#include "core/animation/motion_import.h"
#include "core/animation/skeletal_import.h"
#include "core/base/error.h"

namespace sp::animation {
namespace {

const std::string kWalker = std::string(SPEAR_SOURCE_DIR) + "/assets/characters/humanoid.glb";

template <typename Error> std::string importError(double fps, const std::string& clip) {
    try {
        importMotion(kWalker, clip, fps);
    } catch (const Error& error) {
        return error.what();
    }
    return "(nothing thrown)";
}

TEST(MotionImport, EachFrameIsTheClipsPoseAtItsTime) {
    const ImportedMotion motion = importMotion(kWalker, "walk", 10.0);
    const std::shared_ptr<const SkeletalMeshData> humanoid = importSkeletalMesh(kWalker);
    const AnimClip& walk = *humanoid->findClip("walk");
    EXPECT_EQ(motion.clip, "walk");
    EXPECT_EQ(motion.frames, int(walk.duration * 10.0 + 1e-9) + 1); // both ends
    EXPECT_EQ(motion.boneNames, humanoid->skeleton.names);
    EXPECT_TRUE(motion.objectNames.empty());
    ASSERT_EQ(motion.bones.size(), std::size_t(motion.frames));
    for (int f = 0; f < motion.frames; ++f) {
        const std::vector<Eigen::Affine3d> expected =
            humanoid->skeleton.componentSpace(walk.sample(humanoid->skeleton, f / 10.0));
        for (std::size_t b = 0; b < expected.size(); ++b)
            EXPECT_TRUE(motion.bones[std::size_t(f)][b].isApprox(expected[b], 1e-12)) << f << " " << b;
    }
}

TEST(MotionImport, BadRatesAndClipsAreRefusedNamingThem) {
    EXPECT_EQ(importError<InvalidArgument>(0.0, "walk"),
              "importMotion(): FrameRate must be a positive number of frames per second, got 0");
    EXPECT_NE(importError<InvalidArgument>(1e12, "walk").find("more than 1000000"), std::string::npos);
    EXPECT_EQ(importError<NotFound>(30.0, "jump"),
              "importMotion(): '" + kWalker + "' has no clip 'jump' (it has 'idle', 'walk', 'run')");
    EXPECT_NE(
        importError<InvalidArgument>(30.0, "").find("has 3 clips ('idle', 'walk', 'run'): name the one"),
        std::string::npos);
}

} // namespace
} // namespace sp::animation
