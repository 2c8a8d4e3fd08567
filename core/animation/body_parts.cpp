#include "core/animation/body_parts.h"

#include <map>
#include <mutex>
#include <utility>

#include "core/base/error.h"

namespace sp::animation {

BodyPartMesh splitByBodyPart(const render::MeshData& mesh, const SkinWeights& skin) {
    SP_CHECK(skin.bones.size() == mesh.positions.size(), InvalidArgument,
             "splitByBodyPart(): ", skin.bones.size(), " weight sets for ", mesh.positions.size(),
             " vertices");
    // (material slot, bone) -> the triangles' indices, in the order the mesh has them.
    std::map<std::pair<std::uint32_t, int>, std::vector<std::uint32_t>> groups;
    for (std::size_t slot = 0; slot < mesh.submeshes.size(); ++slot) {
        const render::Submesh& submesh = mesh.submeshes[slot];
        for (std::uint32_t i = submesh.firstIndex; i + 2 < submesh.firstIndex + submesh.indexCount; i += 3) {
            std::map<int, float> weight;
            for (std::uint32_t k = 0; k < 3; ++k) {
                const std::uint32_t v = mesh.indices[i + k];
                for (int j = 0; j < kMaxInfluences; ++j)
                    if (skin.weights[v][j] > 0.0f)
                        weight[skin.bones[v][j]] += skin.weights[v][j];
            }
            int bone = 0;
            float most = -1.0f;
            for (const auto& [b, w] : weight) // ties go to the lower bone index: deterministic
                if (w > most) {
                    bone = b;
                    most = w;
                }
            auto& indices = groups[{std::uint32_t(slot), bone}];
            indices.insert(indices.end(), mesh.indices.begin() + i, mesh.indices.begin() + i + 3);
        }
    }
    BodyPartMesh out;
    out.mesh = mesh;
    out.mesh.indices.clear();
    out.mesh.submeshes.clear();
    for (const auto& [key, indices] : groups) {
        out.mesh.submeshes.push_back({std::uint32_t(out.mesh.indices.size()), std::uint32_t(indices.size())});
        out.mesh.indices.insert(out.mesh.indices.end(), indices.begin(), indices.end());
        out.materialOfSlot.push_back(key.first);
        out.boneOfSlot.push_back(key.second);
    }
    out.mesh.validate("splitByBodyPart");
    return out;
}

std::shared_ptr<const BodyPartMesh> sharedBodyParts(const std::shared_ptr<const SkeletalMeshData>& asset) {
    // By the asset's identity (its control block, not its address, which a later asset may reuse), holding
    // neither it nor its split: both go when the last component lets go of them.
    static std::mutex mutex;
    static std::map<std::weak_ptr<const SkeletalMeshData>, std::weak_ptr<const BodyPartMesh>,
                    std::owner_less<>>
        cache;
    const std::lock_guard lock(mutex);
    if (auto it = cache.find(asset); it != cache.end())
        if (auto parts = it->second.lock())
            return parts;
    std::erase_if(cache, [](const auto& entry) { return entry.first.expired() || entry.second.expired(); });
    auto parts = std::make_shared<const BodyPartMesh>(splitByBodyPart(asset->mesh.mesh, asset->skin));
    cache[asset] = parts;
    return parts;
}

} // namespace sp::animation
