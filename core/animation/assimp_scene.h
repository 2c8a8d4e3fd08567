#pragma once
// What skeletal_import.cpp and motion_import.cpp both read from an assimp scene: a file found and checked,
// its axes turned into spear's, its matrices, and its clips for a skeleton. Internal to sp::animation.

#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/animation/anim_clip.h"
#include "core/animation/skeleton.h"

struct aiNode;
struct aiScene;

namespace sp::animation::detail {

// The file `userPath` names, found as every asset is; throws sp::NotFound naming it when there is none.
std::string resolveFile(const std::string& userPath, const char* function);

// The file's axes turned into spear's (render::isYUpFormat()): every transform read from it is conjugated by
// this (axes * m * axes^-1), not only the top one, so a node the file leaves unrotated is unrotated in spear.
Eigen::Affine3d axesOf(const std::string& path);

// A node's transform relative to its parent, in spear's axes.
Eigen::Affine3d nodeMatrix(const aiNode& node, const Eigen::Affine3d& axes);

// The nodes of `nodes` (each below the file's root, and each one's parent among them unless it is the root's
// child) as a tree to pose: parents before children, in the file's order, each with its transform as its bind
// pose and an identity inverse bind; the root node's transform above them. `order`, when given, receives the
// nodes in the tree's order.
Skeleton treeOf(const aiScene& scene, const std::set<const aiNode*>& nodes, const Eigen::Affine3d& axes,
                const char* function, std::vector<const aiNode*>* order = nullptr);

// The file's clips for `skeleton`, matched by node name; a channel of a node that is not a bone of it is an
// error with `strict` (a separate animation file), else left out.
std::vector<AnimClip> readClips(const aiScene& scene, const Skeleton& skeleton, const Eigen::Affine3d& axes,
                                bool strict, const std::string& userPath, const char* function);

} // namespace sp::animation::detail
