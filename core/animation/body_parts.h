#pragma once
// Body-part segmentation of a skinned mesh: its triangles regrouped into one submesh per (material, bone), a
// triangle going to the bone with the most weight over its three corners. The vertices are the mesh's own, in
// the same order, so the skinned positions apply unchanged; the renderer gives every submesh its own object
// id, so object_ids tells the body parts apart.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/animation/skeletal_import.h"
#include "core/animation/skinning.h"
#include "core/render/mesh_data.h"

namespace sp::animation {

struct BodyPartMesh {
    render::MeshData mesh;                     // the mesh with its submeshes regrouped
    std::vector<std::uint32_t> materialOfSlot; // per submesh: the source mesh's submesh (material slot)
    std::vector<int> boneOfSlot;               // per submesh: the bone whose body part it is
};

// `mesh` (validated) split by `skin`'s dominant bones; submeshes ordered by material slot, then bone index.
BodyPartMesh splitByBodyPart(const render::MeshData& mesh, const SkinWeights& skin);

// `asset`'s mesh split by body part, made once and shared while anything holds it: every character of a crowd
// drawn with body-part ids uses the same split (a few milliseconds each for the humanoid before).
std::shared_ptr<const BodyPartMesh> sharedBodyParts(const std::shared_ptr<const SkeletalMeshData>& asset);

} // namespace sp::animation
