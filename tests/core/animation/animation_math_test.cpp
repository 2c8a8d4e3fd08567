// Skeletons, clip sampling, blending and linear blend skinning against their formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/animation/anim_clip.h"
#include "core/animation/skeleton.h"
#include "core/animation/skinning.h"
#include "core/base/error.h"

namespace sp::animation {
namespace {

// A chain of two bones: "upper" at the origin, "lower" 1 m above it, no rotation in the bind pose.
Skeleton chain() {
    Skeleton s;
    s.names = {"upper", "lower"};
    s.parents = {-1, 0};
    s.bindLocal.resize(2);
    s.bindLocal[1].translation = {0, 0, 1};
    const auto bind = s.componentSpace(s.bindLocal);
    s.inverseBind = {bind[0].inverse(), bind[1].inverse()};
    return s;
}

Eigen::Quaterniond aboutZ(double angle) {
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
}
Eigen::Quaterniond aboutY(double angle) {
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
}

TEST(Skeleton, ComponentSpaceChainsParentsAndRootTransform) {
    Skeleton s = chain();
    s.rootTransform.translation() = Eigen::Vector3d(5, 0, 0);
    Pose pose = s.bindLocal;
    pose[0].rotation = aboutY(std::numbers::pi / 2); // the chain turned to lie along +X
    const auto component = s.componentSpace(pose);
    EXPECT_TRUE(component[1].translation().isApprox(Eigen::Vector3d(6, 0, 0), 1e-12));
    const Pose back = s.localFromComponent(component, "test");
    for (std::size_t i = 0; i < 2; ++i)
        EXPECT_TRUE(back[i].matrix().isApprox(pose[i].matrix(), 1e-12)) << i;
}

TEST(Skeleton, ValidateRefusesAParentAfterItsChildAndDuplicateNames) {
    Skeleton s = chain();
    s.parents = {1, -1};
    EXPECT_THROW(s.validate("test"), InvalidArgument);
    s = chain();
    s.names = {"a", "a"};
    EXPECT_THROW(s.validate("test"), InvalidArgument);
    EXPECT_EQ(chain().find("lower"), 1);
    EXPECT_EQ(chain().find("missing"), -1);
}

TEST(Skinning, OneBoneRotatedMovesItsVertexWhereTheFormulaSays) {
    const Skeleton s = chain();
    Pose pose = s.bindLocal;
    const double angle = 0.7;
    pose[1].rotation = aboutY(angle); // "lower" bends about Y at its joint (0, 0, 1)
    const auto matrices = skinningMatrices(s.componentSpace(pose), s.inverseBind);
    // Vertex 0 follows "upper" only, vertex 1 "lower" only, vertex 2 both halves.
    const std::vector<Eigen::Vector3f> positions = {{0.1f, 0, 0.5f}, {0, 0, 2}, {0, 0, 2}};
    const std::vector<Eigen::Vector3f> normals = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
    SkinWeights weights;
    weights.bones = {{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}};
    weights.weights = {{1, 0, 0, 0}, {1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}};
    weights.validate(3, 2, "test");
    std::vector<Eigen::Vector3f> outPositions, outNormals;
    skin(positions, normals, weights, matrices, outPositions, outNormals);
    EXPECT_TRUE(outPositions[0].isApprox(positions[0], 1e-6f));
    // R_y(a) (0, 0, 1) = (sin a, 0, cos a), about the joint at z = 1.
    const Eigen::Vector3f rotated(float(std::sin(angle)), 0.0f, float(1.0 + std::cos(angle)));
    EXPECT_TRUE(outPositions[1].isApprox(rotated, 1e-5f));
    EXPECT_TRUE(
        outNormals[1].isApprox(Eigen::Vector3f(float(std::cos(angle)), 0, float(-std::sin(angle))), 1e-5f));
    // Linear blend: the average of the two bones' images of the vertex.
    EXPECT_TRUE(outPositions[2].isApprox((positions[2] + rotated) / 2.0f, 1e-5f));
    EXPECT_NEAR(outNormals[2].norm(), 1.0f, 1e-6f);
}

TEST(Skinning, WeightsAreValidated) {
    SkinWeights weights;
    weights.bones = {{0, 0, 0, 0}};
    weights.weights = {{0.5f, 0, 0, 0}};
    EXPECT_THROW(weights.validate(1, 2, "test"), InvalidArgument); // sum 0.5
    weights.weights = {{1, 0, 0, 0}};
    weights.bones = {{7, 0, 0, 0}};
    EXPECT_THROW(weights.validate(1, 2, "test"), InvalidArgument); // no bone 7
    weights.bones = {{1, 0, 0, 0}};
    EXPECT_NO_THROW(weights.validate(1, 2, "test"));
    EXPECT_THROW(weights.validate(2, 2, "test"), InvalidArgument); // sizes
}

AnimClip turning(const Skeleton& s) {
    AnimClip clip;
    clip.name = "turn";
    clip.duration = 2.0;
    BoneTrack track;
    track.bone = 1;
    track.rotations.times = {0.0, 1.0, 2.0};
    track.rotations.values = {Eigen::Quaterniond::Identity(), aboutZ(std::numbers::pi / 2),
                              aboutZ(std::numbers::pi)};
    track.translations.times = {0.0, 2.0};
    track.translations.values = {{0, 0, 1}, {0, 0, 3}};
    clip.tracks.push_back(track);
    clip.validate(s, "test");
    return clip;
}

TEST(AnimClip, SamplesBetweenKeysBySlerpAndLerp) {
    const Skeleton s = chain();
    const AnimClip clip = turning(s);
    const Pose quarter = clip.sample(s, 0.5);
    EXPECT_NEAR(quarter[1].rotation.angularDistance(aboutZ(std::numbers::pi / 4)), 0.0, 1e-9);
    EXPECT_TRUE(quarter[1].translation.isApprox(Eigen::Vector3d(0, 0, 1.5), 1e-12));
    EXPECT_NEAR(clip.sample(s, 1.5)[1].rotation.angularDistance(aboutZ(3 * std::numbers::pi / 4)), 0.0, 1e-9);
    // Before the first key and after the last: the end keys. An untracked bone keeps its bind pose.
    EXPECT_NEAR(clip.sample(s, -1.0)[1].rotation.angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-12);
    EXPECT_TRUE(clip.sample(s, 9.0)[1].translation.isApprox(Eigen::Vector3d(0, 0, 3), 1e-12));
    EXPECT_TRUE(clip.sample(s, 0.5)[0].matrix().isApprox(s.bindLocal[0].matrix()));
}

TEST(AnimClip, BlendOfWeightZeroAndOneIsEachPose) {
    const Skeleton s = chain();
    const AnimClip clip = turning(s);
    const Pose a = clip.sample(s, 0.3), b = clip.sample(s, 1.7);
    for (double w : {0.0, 1.0}) {
        const Pose blended = blend(a, b, w);
        const Pose& expected = w == 0.0 ? a : b;
        for (std::size_t i = 0; i < s.size(); ++i)
            EXPECT_TRUE(blended[i].matrix().isApprox(expected[i].matrix(), 1e-12)) << w << " " << i;
    }
    const Pose half = blend(a, b, 0.5);
    EXPECT_NEAR(half[1].rotation.angularDistance(clip.sample(s, 1.0)[1].rotation), 0.0, 1e-9);
}

TEST(AnimClip, ValidateRefusesUnsortedKeysAndUnknownBones) {
    const Skeleton s = chain();
    AnimClip clip = turning(s);
    clip.tracks[0].rotations.times = {0.0, 2.0, 1.0};
    EXPECT_THROW(clip.validate(s, "test"), InvalidArgument);
    clip = turning(s);
    clip.tracks[0].bone = 5;
    EXPECT_THROW(clip.validate(s, "test"), InvalidArgument);
    clip = turning(s);
    clip.tracks[0].translations.values[1].x() = std::nan("");
    EXPECT_THROW(clip.validate(s, "test"), InvalidArgument);
}

} // namespace
} // namespace sp::animation
