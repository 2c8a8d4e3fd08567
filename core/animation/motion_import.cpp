#include "core/animation/motion_import.h"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <cmath>
#include <set>

#include "core/animation/assimp_scene.h"
#include "core/animation/skeletal_import.h"
#include "core/base/error.h"
#include "core/render/assimp_reading.h"

namespace sp::animation {
namespace {

constexpr const char* kFunction = "importMotion";

bool isSkinned(const aiScene& scene, const aiNode& node) {
    for (unsigned m = 0; m < node.mNumMeshes; ++m)
        if (node.mMeshes[m] < scene.mNumMeshes && scene.mMeshes[node.mMeshes[m]]->mNumBones > 0)
            return true;
    return false;
}

std::string listed(const std::vector<AnimClip>& clips) {
    std::string out;
    for (const AnimClip& clip : clips)
        out += (out.empty() ? "'" : ", '") + clip.name + "'";
    return out;
}

// Every node of the file below its root that matters to the motion, as one tree to pose: the character's
// bones (and the nodes above them), the rigid nodes with a mesh and those above them, and every node a
// channel animates. A clip sampled on it poses them all at once, each node by its parents.
struct NodeTree {
    Skeleton tree;
    std::vector<const aiNode*> nodes; // tree.names[i] is nodes[i]'s
};

NodeTree nodeTree(const aiScene& scene, const Skeleton& character, const Eigen::Affine3d& axes) {
    std::set<const aiNode*> wanted;
    const auto want = [&](const aiNode* node) {
        for (; node != nullptr && node != scene.mRootNode; node = node->mParent)
            wanted.insert(node);
    };
    for (const std::string& bone : character.names)
        want(scene.mRootNode->FindNode(bone.c_str()));
    for (unsigned a = 0; a < scene.mNumAnimations; ++a)
        for (unsigned c = 0; c < scene.mAnimations[a]->mNumChannels; ++c)
            want(scene.mRootNode->FindNode(scene.mAnimations[a]->mChannels[c]->mNodeName));
    std::vector<const aiNode*> stack(scene.mRootNode->mChildren,
                                     scene.mRootNode->mChildren + scene.mRootNode->mNumChildren);
    while (!stack.empty()) { // every rigid mesh node, wherever it hangs
        const aiNode* node = stack.back();
        stack.pop_back();
        if (node->mNumMeshes > 0 && !isSkinned(scene, *node))
            want(node);
        stack.insert(stack.end(), node->mChildren, node->mChildren + node->mNumChildren);
    }
    NodeTree out;
    out.tree = detail::treeOf(scene, wanted, axes, kFunction, &out.nodes);
    out.tree.validate(kFunction); // two nodes of one name would leave a channel ambiguous
    return out;
}

} // namespace

ImportedMotion importMotion(const std::string& userPath, const std::string& clipName, double fps) {
    SP_CHECK(std::isfinite(fps) && fps > 0.0, InvalidArgument, kFunction, "(): FrameRate must be a positive ",
             "number of frames per second, got ", fps);
    const std::shared_ptr<const SkeletalMeshData> character = importSkeletalMesh(userPath); // NotFound, ...
    const std::string path = detail::resolveFile(userPath, kFunction);
    Assimp::Importer importer;
    std::vector<std::string> filesRead;
    const aiScene* scene = render::readWithAssimp(importer, path, userPath, 0, filesRead, kFunction);
    const Eigen::Affine3d axes = detail::axesOf(path);
    const NodeTree nodes = nodeTree(*scene, character->skeleton, axes);
    const std::vector<AnimClip> clips =
        detail::readClips(*scene, nodes.tree, axes, false, userPath, kFunction);
    SP_CHECK(!clips.empty(), InvalidArgument, kFunction, "(): '", userPath, "' has no animation clip");
    const AnimClip* clip = nullptr;
    if (clipName.empty()) {
        SP_CHECK(clips.size() == 1, InvalidArgument, kFunction, "(): '", userPath, "' has ", clips.size(),
                 " clips (", listed(clips), "): name the one to import");
        clip = &clips.front();
    } else {
        for (const AnimClip& candidate : clips)
            if (candidate.name == clipName)
                clip = &candidate;
        SP_CHECK(clip != nullptr, NotFound, kFunction, "(): '", userPath, "' has no clip '", clipName,
                 "' (it has ", listed(clips), ")");
    }
    const double frames = std::floor(clip->duration * fps + 1e-9) + 1.0;
    SP_CHECK(frames <= double(kMostMotionFrames), InvalidArgument, kFunction, "(): clip '", clip->name, "' (",
             clip->duration, " s) at ", fps, " frames per second is ", frames, " frames, more than ",
             kMostMotionFrames);

    ImportedMotion out;
    out.clip = clip->name;
    out.fps = fps;
    out.frames = int(frames);
    out.boneNames = character->skeleton.names;
    std::vector<int> boneNodes;
    for (const std::string& bone : out.boneNames)
        boneNodes.push_back(nodes.tree.find(bone));
    // The objects: rigid nodes with a mesh that the clip moves (a channel on the node or above it).
    std::vector<bool> moved(nodes.tree.size(), false);
    for (const BoneTrack& track : clip->tracks)
        moved[std::size_t(track.bone)] = true;
    std::vector<int> objectNodes;
    for (std::size_t i = 0; i < nodes.tree.size(); ++i) {
        const int parent = nodes.tree.parents[i];
        if (parent >= 0 && moved[std::size_t(parent)])
            moved[i] = true;
        const aiNode& node = *nodes.nodes[i];
        if (moved[i] && node.mNumMeshes > 0 && !isSkinned(*scene, node) &&
            character->skeleton.find(node.mName.C_Str()) < 0) {
            objectNodes.push_back(int(i));
            out.objectNames.push_back(nodes.tree.names[i]);
        }
    }
    for (int f = 0; f < out.frames; ++f) {
        const std::vector<Eigen::Affine3d> placed =
            nodes.tree.componentSpace(clip->sample(nodes.tree, f / fps));
        auto& bones = out.bones.emplace_back();
        for (const int node : boneNodes)
            bones.push_back(placed[std::size_t(node)]);
        auto& objects = out.objects.emplace_back();
        for (const int node : objectNodes)
            objects.push_back(placed[std::size_t(node)]);
    }
    return out;
}

} // namespace sp::animation
