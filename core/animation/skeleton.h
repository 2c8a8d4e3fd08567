#pragma once
// A skeleton: bones in a tree (parents before their children), each with its transform relative to its
// parent in the reference (bind) pose and the inverse of its bind-pose transform in the mesh's space, which
// skinning needs. Pure data and math, no GL, no world.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace sp::animation {

// A bone's transform relative to its parent: scale, then rotation, then translation (as UE's FTransform and
// glTF's TRS).
struct BoneTransform {
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();

    Eigen::Affine3d matrix() const;
    // The transform of `matrix` (its linear part a rotation times a positive scale along the axes; shear is
    // dropped). Throws sp::InvalidArgument naming `function` when it is not finite or scales an axis to 0.
    static BoneTransform fromMatrix(const Eigen::Affine3d& matrix, const char* function);
};

// The transform halfway `weight` from `a` to `b`: translations and scales interpolated linearly, rotations
// along the shorter arc (spherical). weight 0 is `a`, 1 is `b`.
BoneTransform interpolate(const BoneTransform& a, const BoneTransform& b, double weight);

// A full pose: one local transform per bone of a skeleton.
using Pose = std::vector<BoneTransform>;

struct Skeleton {
    std::vector<std::string> names;
    std::vector<int> parents;                 // parents[i] < i; -1 for a bone at the top
    Pose bindLocal;                           // each bone relative to its parent in the bind pose
    std::vector<Eigen::Affine3d> inverseBind; // mesh space -> the bone's space in the bind pose
    // Above the bones at the top: their parent's transform in the mesh's space (a file's own root node, its
    // axis convention).
    Eigen::Affine3d rootTransform = Eigen::Affine3d::Identity();

    std::size_t size() const { return names.size(); }
    // The bone's index, -1 when there is none of that name.
    int find(const std::string& name) const;
    // Checks the tree and the sizes; throws sp::InvalidArgument "<function>(): <what>".
    void validate(const char* function) const;

    // Each bone's transform in the mesh's (component's) space for the pose `local` (size() transforms).
    std::vector<Eigen::Affine3d> componentSpace(std::span<const BoneTransform> local) const;
    // The local pose whose componentSpace() is `component` (size() transforms).
    Pose localFromComponent(std::span<const Eigen::Affine3d> component, const char* function) const;
};

} // namespace sp::animation
