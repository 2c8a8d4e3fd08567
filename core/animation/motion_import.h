#pragma once
// A human-object motion sequence straight from an animated file (glTF 2.0, FBX where assimp reads it): one
// clip of a file that holds a skinned character and the rigid objects it handles, each animated node moved
// by that clip, sampled at a frame rate. The character's bones come out in its component's space (as
// USkeletalMeshComponent poses them from the same file); an object's transform is its node's, in the
// file's space turned into spear's axes (metres, Z up), which is the world when the character stands at
// the origin. Pure data: no world, no GL.

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace sp::animation {

struct ImportedMotion {
    std::string clip;
    double fps = 0.0;
    int frames = 0;                                    // frame f shows the clip at f / fps seconds
    std::vector<std::string> boneNames;                // the character's skeleton, in its order
    std::vector<std::vector<Eigen::Affine3d>> bones;   // [frame][bone], component space
    std::vector<std::string> objectNames;              // rigid nodes with a mesh that the clip moves
    std::vector<std::vector<Eigen::Affine3d>> objects; // [frame][object]
};

// Most frames one import samples (a 60 fps clip of 4.6 hours): beyond it a mistaken rate would fill memory.
inline constexpr int kMostMotionFrames = 1'000'000;

// Reads clip `clip` of the file at `path` (found as every asset is; "" takes the file's only clip) at `fps`
// frames per second, from 0 to the clip's end inclusive. Throws sp::NotFound naming the path (no such file)
// or the clip and those there are; sp::InvalidArgument when the file has no skeleton or no clip, when fps
// is not a positive finite number or asks for more than kMostMotionFrames, or when a clip names a node the
// file does not have.
ImportedMotion importMotion(const std::string& path, const std::string& clip, double fps);

} // namespace sp::animation
