// The committed humanoid through assimp: skeleton, skin, clips; and the files it must refuse.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "core/animation/body_parts.h"
#include "core/animation/skeletal_import.h"
#include "core/base/error.h"

namespace sp::animation {
namespace {

const std::string kHumanoid = std::string(SPEAR_SOURCE_DIR) + "/assets/characters/humanoid.glb";

TEST(SkeletalImport, ReadsTheHumanoidsSkeletonSkinAndClips) {
    const auto data = importSkeletalMesh(kHumanoid);
    const Skeleton& s = data->skeleton;
    ASSERT_EQ(s.size(), 18u);
    EXPECT_EQ(s.names[0], "root");
    EXPECT_EQ(s.parents[0], -1);
    const int pelvis = s.find("pelvis"), head = s.find("head"), calf = s.find("calf_l");
    ASSERT_GE(pelvis, 0);
    ASSERT_GE(head, 0);
    EXPECT_EQ(s.parents[std::size_t(pelvis)], 0);
    EXPECT_EQ(s.names[std::size_t(s.parents[std::size_t(calf)])], "thigh_l");
    // In spear's axes (Z up): the joints where the script put them.
    const auto bind = s.componentSpace(s.bindLocal);
    EXPECT_TRUE(bind[std::size_t(head)].translation().isApprox(Eigen::Vector3d(0, 0, 1.57), 1e-5));
    EXPECT_TRUE(bind[std::size_t(calf)].translation().isApprox(Eigen::Vector3d(0, 0.10, 0.50), 1e-5));
    // glTF's Y-up axes are taken out of every bone, not only the top one: the file's unrotated bones are
    // unrotated here (a camera on the head looks forward, +Z up).
    EXPECT_TRUE(bind[std::size_t(head)].linear().isIdentity(1e-6));
    EXPECT_TRUE(s.rootTransform.matrix().isIdentity(1e-12));
    // The bind pose's bounds, found once at import (read every frame by physics): every vertex, feet to head.
    Eigen::Vector3f lowest, highest;
    data->mesh.mesh.bounds(lowest, highest);
    EXPECT_TRUE(data->bindBounds.min().isApprox(lowest.cast<double>()) &&
                data->bindBounds.max().isApprox(highest.cast<double>()));
    EXPECT_NEAR(data->bindBounds.min().z(), 0.0, 0.05);
    EXPECT_GT(data->bindBounds.max().z(), 1.57);
    // Every vertex blends at most a bone and its parent (the script blends across joints only), so no weight
    // went to the wrong vertex (Debian's assimp misplaces the weights of a glTF mesh's later primitives when
    // they share vertex arrays: the script writes one set per primitive).
    for (std::size_t v = 0; v < data->skin.bones.size(); ++v) {
        const auto& bones = data->skin.bones[v];
        const auto& weights = data->skin.weights[v];
        for (int j = 1; j < kMaxInfluences; ++j)
            if (weights[j] > 0.0f) {
                ASSERT_TRUE(s.parents[bones[j]] == bones[0] || s.parents[bones[0]] == bones[j])
                    << "vertex " << v << ": " << s.names[bones[0]] << " and " << s.names[bones[j]];
            }
    }
    // The bind pose skins every vertex onto itself.
    const auto matrices = skinningMatrices(bind, s.inverseBind);
    std::vector<Eigen::Vector3f> positions, normals;
    skin(data->mesh.mesh.positions, data->mesh.mesh.normals, data->skin, matrices, positions, normals);
    for (std::size_t v = 0; v < positions.size(); ++v)
        ASSERT_LT((positions[v] - data->mesh.mesh.positions[v]).norm(), 1e-5f) << v;
    // A standing figure about 1.8 m tall, feet on the ground; one submesh per material.
    Eigen::Vector3f min, max;
    data->mesh.mesh.bounds(min, max);
    EXPECT_NEAR(min.z(), 0.0f, 0.02f);
    EXPECT_NEAR(max.z(), 1.785f, 0.02f);
    EXPECT_EQ(data->mesh.mesh.submeshCount(), 4u);
    // Each material's primitive brings only the vertices its triangles use (the file has 2,568).
    EXPECT_LE(data->mesh.mesh.positions.size(), 2568u + 200u);
    EXPECT_EQ(data->mesh.materials.size(), 4u);
    ASSERT_EQ(data->clips.size(), 3u);
    ASSERT_NE(data->findClip("walk"), nullptr);
    EXPECT_NEAR(data->findClip("walk")->duration, 1.1, 1e-3);
    EXPECT_NEAR(data->findClip("run")->duration, 0.7, 1e-3);
    EXPECT_NEAR(data->findClip("idle")->duration, 3.0, 1e-3);
    // Walking swings the left thigh: its foot leaves the bind pose.
    const Pose walking = data->findClip("walk")->sample(s, 0.275); // a quarter cycle: stride at its widest
    const auto posed = s.componentSpace(walking);
    const int foot = s.find("foot_l");
    EXPECT_GT((posed[std::size_t(foot)].translation() - bind[std::size_t(foot)].translation()).norm(), 0.1);
    // The same file again: the cached import.
    EXPECT_EQ(importSkeletalMesh(kHumanoid).get(), data.get());
}

TEST(BodyParts, EveryTriangleGoesToTheBoneWeighingMostOnItsCorners) {
    const auto data = importSkeletalMesh(kHumanoid);
    const render::MeshData& mesh = data->mesh.mesh;
    const BodyPartMesh parts = splitByBodyPart(mesh, data->skin);
    EXPECT_EQ(parts.mesh.positions.size(), mesh.positions.size()); // the same vertices, so the same skinning
    EXPECT_EQ(parts.mesh.indices.size(), mesh.indices.size());
    ASSERT_EQ(parts.materialOfSlot.size(), parts.mesh.submeshCount());
    // Every bone that carries skin has a part (the root and the pelvis's joint to it may carry none).
    std::set<int> bones(parts.boneOfSlot.begin(), parts.boneOfSlot.end());
    for (const char* name :
         {"head", "hand_l", "hand_r", "foot_l", "foot_r", "calf_l", "upperarm_r", "spine_02"})
        EXPECT_TRUE(bones.count(data->skeleton.find(name))) << name;
    // The head's triangles are all above the neck; the left foot's on the left (+Y), near the ground.
    for (std::size_t slot = 0; slot < parts.mesh.submeshCount(); ++slot) {
        const render::Submesh& submesh = parts.mesh.submeshes[slot];
        const std::string& bone = data->skeleton.names[std::size_t(parts.boneOfSlot[slot])];
        for (std::uint32_t i = submesh.firstIndex; i < submesh.firstIndex + submesh.indexCount; ++i) {
            const Eigen::Vector3f& p = parts.mesh.positions[parts.mesh.indices[i]];
            if (bone == "head") {
                ASSERT_GT(p.z(), 1.5f);
            }
            if (bone == "foot_l") {
                ASSERT_TRUE(p.y() > 0.0f && p.z() < 0.2f) << p.transpose();
            }
        }
    }
}

TEST(BodyParts, EveryComponentOfAnAssetSharesOneSplitWhileItIsHeld) {
    const auto data = importSkeletalMesh(kHumanoid);
    auto first = sharedBodyParts(data);
    EXPECT_EQ(sharedBodyParts(data), first); // a crowd's characters: made once
    EXPECT_EQ(first->mesh.indices.size(), data->mesh.mesh.indices.size());
    // Another asset (a copy of the same data) gets its own, even with the first one's split still held.
    const auto other = std::make_shared<const SkeletalMeshData>(*data);
    EXPECT_NE(sharedBodyParts(other), first);
    // Once nothing holds a split, the next request makes it again (the cache keeps neither alive).
    std::weak_ptr<const BodyPartMesh> gone = first;
    first.reset();
    EXPECT_TRUE(gone.expired());
    EXPECT_NE(sharedBodyParts(data), nullptr);
}

TEST(SkeletalImport, ClipsFromAFileMatchTheSkeletonByName) {
    const auto data = importSkeletalMesh(kHumanoid);
    const std::vector<AnimClip> clips = importAnimations(kHumanoid, data->skeleton);
    EXPECT_EQ(clips.size(), 3u);
    Skeleton other = data->skeleton;
    other.names[std::size_t(other.find("thigh_l"))] = "LeftUpLeg";
    try {
        importAnimations(kHumanoid, other);
        FAIL() << "a clip for another skeleton was accepted";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("'thigh_l', which the skeleton does not have"),
                  std::string::npos)
            << error.what();
    }
}

TEST(SkeletalImport, AFileWithoutASkinOrNoFileIsAClearError) {
    const auto folder = std::filesystem::temp_directory_path() / "spear_skeletal_import_test";
    std::filesystem::create_directories(folder);
    const std::string obj = (folder / "triangle.obj").string();
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    try {
        importSkeletalMesh(obj);
        FAIL() << "a mesh without a skin was accepted";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find("has no skeleton"), std::string::npos) << error.what();
    }
    EXPECT_THROW(importSkeletalMesh((folder / "missing.glb").string()), NotFound);
    std::filesystem::remove_all(folder);
}

} // namespace
} // namespace sp::animation
