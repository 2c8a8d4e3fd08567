#pragma once
// Skinned meshes and their animation clips from files, through assimp (glTF 2.0 skins; FBX and the other
// formats assimp reads skins from): the mesh in its bind pose with its materials, the skeleton, up to four
// bone weights per vertex, and every clip the file holds.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/animation/anim_clip.h"
#include "core/animation/skeleton.h"
#include "core/animation/skinning.h"
#include "core/render/mesh_import.h"

namespace sp::animation {

struct SkeletalMeshData {
    render::ImportedMesh mesh; // the bind pose, in the mesh's space (spear's axes), one submesh per material
    Skeleton skeleton;
    SkinWeights skin; // one entry per vertex of `mesh`
    std::vector<AnimClip> clips;
    // The bind pose's bounds in the mesh's space, found once at import: a component's local bounds are read
    // every frame (physics, world bounds), and a character has thousands of vertices.
    Eigen::AlignedBox3d bindBounds;

    const AnimClip* findClip(const std::string& name) const;
};

// Reads a skinned mesh file, found as every asset is (core/base/asset_path.h). Throws sp::NotFound naming the
// path when there is no such file, sp::InvalidArgument when assimp cannot read it, when it holds no triangles
// or no skin ("has no skeleton": import it as a static mesh). A file read before comes from a cache while it
// keeps its size and modification time.
std::shared_ptr<const SkeletalMeshData> importSkeletalMesh(const std::string& path);

// The clips of an animation file (a skinned mesh file, or one with only a skeleton and its animations) for
// `skeleton`, matched by bone name. Throws sp::InvalidArgument naming the bone when a clip animates a bone
// `skeleton` does not have (an animation made for another skeleton), or when the file has no clip.
std::vector<AnimClip> importAnimations(const std::string& path, const Skeleton& skeleton);

} // namespace sp::animation
