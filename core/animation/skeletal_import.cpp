#include "core/animation/skeletal_import.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>

#include "core/animation/assimp_scene.h"
#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/base/regular_file.h"
#include "core/render/assimp_reading.h"

namespace sp::animation {
namespace detail {
namespace {

Eigen::Affine3d toEigen(const aiMatrix4x4& m) {
    Eigen::Matrix4d out;
    out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
    return Eigen::Affine3d(out);
}

Eigen::Affine3d conjugate(const Eigen::Affine3d& axes, const Eigen::Affine3d& m) {
    return axes * m * axes.inverse();
}

} // namespace

Eigen::Affine3d axesOf(const std::string& path) {
    Eigen::Affine3d axes = Eigen::Affine3d::Identity();
    if (render::isYUpFormat(path))
        axes.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0; // (x, y, z) -> (x, -z, y)
    return axes;
}

Eigen::Affine3d nodeMatrix(const aiNode& node, const Eigen::Affine3d& axes) {
    return conjugate(axes, toEigen(node.mTransformation));
}

std::string resolveFile(const std::string& userPath, const char* function) {
    const std::string path = resolveUserPath(findAsset(userPath), function, "mesh file");
    SP_CHECK(std::filesystem::exists(path) && !std::filesystem::is_directory(path), NotFound, function,
             "(): no such file '", userPath, "'");
    checkRegularFile(path, function, "mesh file");
    return path;
}

Skeleton treeOf(const aiScene& scene, const std::set<const aiNode*>& nodes, const Eigen::Affine3d& axes,
                const char* function, std::vector<const aiNode*>* order) {
    Skeleton tree;
    tree.rootTransform = nodeMatrix(*scene.mRootNode, axes);
    std::map<const aiNode*, int> index;
    std::vector<const aiNode*> stack;
    for (unsigned c = scene.mRootNode->mNumChildren; c-- > 0;)
        stack.push_back(scene.mRootNode->mChildren[c]);
    while (!stack.empty()) { // depth first, children in the file's order
        const aiNode* node = stack.back();
        stack.pop_back();
        if (!nodes.count(node))
            continue;
        index[node] = int(tree.names.size());
        if (order != nullptr)
            order->push_back(node);
        tree.names.push_back(node->mName.C_Str());
        tree.parents.push_back(node->mParent == scene.mRootNode ? -1 : index.at(node->mParent));
        tree.bindLocal.push_back(BoneTransform::fromMatrix(nodeMatrix(*node, axes), function));
        tree.inverseBind.push_back(Eigen::Affine3d::Identity());
        for (unsigned c = node->mNumChildren; c-- > 0;)
            stack.push_back(node->mChildren[c]);
    }
    return tree;
}

std::vector<AnimClip> readClips(const aiScene& scene, const Skeleton& skeleton, const Eigen::Affine3d& axes,
                                bool strict, const std::string& userPath, const char* function) {
    const Eigen::Matrix3d linear = axes.linear();
    const Eigen::Quaterniond turn(linear);
    std::vector<AnimClip> clips;
    std::set<std::string> names;
    for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
        const aiAnimation& animation = *scene.mAnimations[a];
        AnimClip clip;
        clip.name = animation.mName.length > 0 ? animation.mName.C_Str() : "clip" + std::to_string(a);
        SP_CHECK(names.insert(clip.name).second, InvalidArgument, function, "(): '", userPath,
                 "' has two clips named '", clip.name, "'");
        const double ticks = animation.mTicksPerSecond > 0.0 ? animation.mTicksPerSecond : 25.0;
        clip.duration = animation.mDuration / ticks;
        for (unsigned c = 0; c < animation.mNumChannels; ++c) {
            const aiNodeAnim& channel = *animation.mChannels[c];
            BoneTrack track;
            track.bone = skeleton.find(channel.mNodeName.C_Str());
            if (track.bone < 0) {
                SP_CHECK(!strict, InvalidArgument, function, "(): clip '", clip.name, "' of '", userPath,
                         "' animates bone '", channel.mNodeName.C_Str(),
                         "', which the skeleton does not have: it was made for another skeleton");
                continue;
            }
            for (unsigned k = 0; k < channel.mNumPositionKeys; ++k) {
                const aiVectorKey& key = channel.mPositionKeys[k];
                track.translations.times.push_back(key.mTime / ticks);
                track.translations.values.push_back(
                    linear * Eigen::Vector3d(key.mValue.x, key.mValue.y, key.mValue.z));
            }
            for (unsigned k = 0; k < channel.mNumRotationKeys; ++k) {
                const aiQuatKey& key = channel.mRotationKeys[k];
                track.rotations.times.push_back(key.mTime / ticks);
                Eigen::Quaterniond rotation(key.mValue.w, key.mValue.x, key.mValue.y, key.mValue.z);
                if (rotation.norm() > 0.0) // a zero one stays zero, for validate() to refuse
                    rotation = turn * rotation.normalized() * turn.conjugate();
                track.rotations.values.push_back(rotation);
            }
            for (unsigned k = 0; k < channel.mNumScalingKeys; ++k) {
                const aiVectorKey& key = channel.mScalingKeys[k];
                track.scales.times.push_back(key.mTime / ticks);
                track.scales.values.push_back(linear.cwiseAbs() *
                                              Eigen::Vector3d(key.mValue.x, key.mValue.y, key.mValue.z));
            }
            clip.tracks.push_back(std::move(track));
        }
        clip.validate(skeleton, function);
        clips.push_back(std::move(clip));
    }
    return clips;
}

} // namespace detail

namespace {
using detail::axesOf;
using detail::conjugate;
using detail::nodeMatrix;
using detail::readClips;
using detail::toEigen;
using detail::treeOf;

// The skeleton: every node that is a bone of some mesh, and every node above one (below the file's root),
// parents before children, in the file's order.
Skeleton readSkeleton(const aiScene& scene, const Eigen::Affine3d& axes, const std::string& userPath) {
    std::set<std::string> boneNames;
    for (unsigned m = 0; m < scene.mNumMeshes; ++m)
        for (unsigned b = 0; b < scene.mMeshes[m]->mNumBones; ++b)
            boneNames.insert(scene.mMeshes[m]->mBones[b]->mName.C_Str());
    SP_CHECK(!boneNames.empty(), InvalidArgument, "importSkeletalMesh(): '", userPath,
             "' has no skeleton (no mesh in it is skinned); show it with a UStaticMeshComponent");
    std::set<const aiNode*> marked;
    for (const std::string& name : boneNames) {
        const aiNode* node = scene.mRootNode->FindNode(name.c_str());
        SP_CHECK(node != nullptr, InvalidArgument, "importSkeletalMesh(): '", userPath, "' skins to bone '",
                 name, "', which is no node of the file");
        for (; node != nullptr && node != scene.mRootNode; node = node->mParent)
            marked.insert(node);
    }
    Skeleton skeleton = treeOf(scene, marked, axes, "importSkeletalMesh");
    // A bone's inverse bind transform is the file's, in spear's axes; a node above the bones gets the inverse
    // of where the bind pose puts it (no vertex follows it).
    const std::vector<Eigen::Affine3d> bind = skeleton.componentSpace(skeleton.bindLocal);
    for (std::size_t i = 0; i < skeleton.size(); ++i)
        skeleton.inverseBind[i] = bind[i].inverse();
    for (unsigned m = 0; m < scene.mNumMeshes; ++m)
        for (unsigned b = 0; b < scene.mMeshes[m]->mNumBones; ++b) {
            const aiBone* bone = scene.mMeshes[m]->mBones[b];
            skeleton.inverseBind[std::size_t(skeleton.find(bone->mName.C_Str()))] =
                conjugate(axes, toEigen(bone->mOffsetMatrix));
        }
    skeleton.validate("importSkeletalMesh");
    return skeleton;
}

std::shared_ptr<const SkeletalMeshData> readSkeletalMesh(const std::string& path,
                                                         const std::string& userPath) {
    Assimp::Importer importer;
    std::vector<std::string> filesRead;
    const aiScene* scene = render::readWithAssimp(
        importer, path, userPath,
        aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
            aiProcess_LimitBoneWeights | aiProcess_FlipUVs | aiProcess_SortByPType,
        filesRead, "importSkeletalMesh");
    const Eigen::Affine3d axes = axesOf(path);
    auto out = std::make_shared<SkeletalMeshData>();
    out->skeleton = readSkeleton(*scene, axes, userPath);
    render::MeshData& mesh = out->mesh.mesh;
    mesh.name = std::filesystem::path(path).stem().string();
    const Eigen::Matrix3f linear = axes.linear().cast<float>();
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh& source = *scene->mMeshes[m];
        // A mesh no bone deforms is a rigid object beside the character (a prop a motion file moves by its
        // own node, motion_import.h), not part of it: drawn by the first bone, ignoring its node, it would
        // float where the file does not put it.
        if (!(source.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || source.mNumBones == 0)
            continue;
        const auto base = std::uint32_t(mesh.positions.size());
        // Each vertex's bones, heaviest first (at most four: aiProcess_LimitBoneWeights), weights summing
        // to 1.
        std::vector<std::vector<std::pair<float, std::uint16_t>>> influences(source.mNumVertices);
        for (unsigned b = 0; b < source.mNumBones; ++b) {
            const aiBone& bone = *source.mBones[b];
            const auto index = std::uint16_t(out->skeleton.find(bone.mName.C_Str()));
            for (unsigned w = 0; w < bone.mNumWeights; ++w)
                if (bone.mWeights[w].mVertexId < source.mNumVertices && bone.mWeights[w].mWeight > 0.0f)
                    influences[bone.mWeights[w].mVertexId].push_back({bone.mWeights[w].mWeight, index});
        }
        for (unsigned v = 0; v < source.mNumVertices; ++v) {
            const aiVector3D& p = source.mVertices[v];
            mesh.positions.push_back(linear * Eigen::Vector3f(p.x, p.y, p.z));
            const aiVector3D n = source.HasNormals() ? source.mNormals[v] : aiVector3D(0, 0, 1);
            mesh.normals.push_back(linear * Eigen::Vector3f(n.x, n.y, n.z));
            const aiVector3D uv =
                source.HasTextureCoords(0) ? source.mTextureCoords[0][v] : aiVector3D(0, 0, 0);
            mesh.uvs.push_back({uv.x, uv.y});
            auto& list = influences[v];
            std::sort(list.begin(), list.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
            list.resize(std::min<std::size_t>(list.size(), kMaxInfluences));
            float total = 0.0f;
            for (const auto& [weight, bone] : list)
                total += weight;
            std::array<std::uint16_t, kMaxInfluences> bones{};
            std::array<float, kMaxInfluences> weights{};
            if (total > 0.0f)
                for (std::size_t k = 0; k < list.size(); ++k) {
                    bones[k] = list[k].second;
                    weights[k] = list[k].first / total;
                }
            else
                weights[0] = 1.0f; // not skinned: it follows the first bone
            out->skin.bones.push_back(bones);
            out->skin.weights.push_back(weights);
        }
        render::Submesh submesh{std::uint32_t(mesh.indices.size()), 0};
        for (unsigned f = 0; f < source.mNumFaces; ++f) {
            const aiFace& face = source.mFaces[f];
            if (face.mNumIndices != 3)
                continue;
            for (unsigned k = 0; k < 3; ++k)
                mesh.indices.push_back(base + face.mIndices[k]);
            submesh.indexCount += 3;
        }
        if (submesh.indexCount == 0)
            continue;
        mesh.submeshes.push_back(submesh);
        out->mesh.materials.push_back(render::importMaterial(
            *scene, source.mMaterialIndex, std::filesystem::path(path).parent_path(), filesRead));
    }
    SP_CHECK(!mesh.submeshes.empty(), InvalidArgument, "importSkeletalMesh(): '", userPath,
             "' contains no triangles");
    mesh.validate("importSkeletalMesh");
    out->skin.validate(mesh.positions.size(), out->skeleton.size(), "importSkeletalMesh");
    out->clips = readClips(*scene, out->skeleton, axes, false, userPath, "importSkeletalMesh");
    Eigen::Vector3f min, max;
    mesh.bounds(min, max);
    out->bindBounds = {min.cast<double>(), max.cast<double>()};
    return out;
}

} // namespace

const AnimClip* SkeletalMeshData::findClip(const std::string& name) const {
    for (const AnimClip& clip : clips)
        if (clip.name == name)
            return &clip;
    return nullptr;
}

std::shared_ptr<const SkeletalMeshData> importSkeletalMesh(const std::string& userPath) {
    const std::string path = detail::resolveFile(userPath, "importSkeletalMesh");
    // Each component showing a character would otherwise read its file again.
    struct Cached {
        std::filesystem::file_time_type modified;
        std::uintmax_t size = 0;
        std::shared_ptr<const SkeletalMeshData> data;
    };
    static std::mutex mutex;
    static std::map<std::string, Cached> cache;
    const auto modified = std::filesystem::last_write_time(path);
    const auto size = std::filesystem::file_size(path);
    {
        std::lock_guard lock(mutex);
        const auto it = cache.find(path);
        if (it != cache.end() && it->second.modified == modified && it->second.size == size)
            return it->second.data;
    }
    std::shared_ptr<const SkeletalMeshData> data = readSkeletalMesh(path, userPath);
    std::lock_guard lock(mutex);
    cache[path] = {modified, size, data};
    return data;
}

std::vector<AnimClip> importAnimations(const std::string& userPath, const Skeleton& skeleton) {
    const std::string path = detail::resolveFile(userPath, "importAnimations");
    Assimp::Importer importer;
    std::vector<std::string> filesRead;
    const aiScene* scene = render::readWithAssimp(importer, path, userPath, 0, filesRead, "importAnimations");
    std::vector<AnimClip> clips =
        readClips(*scene, skeleton, axesOf(path), true, userPath, "importAnimations");
    SP_CHECK(!clips.empty(), InvalidArgument, "importAnimations(): '", userPath, "' has no animation clip");
    return clips;
}

} // namespace sp::animation
