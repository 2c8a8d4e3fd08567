// The committed humanoid through assimp: skeleton, skin, clips; and the files it must refuse.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
