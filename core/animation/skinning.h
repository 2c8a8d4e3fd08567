#pragma once
// Linear blend skinning: each vertex moved by the weighted sum of up to four bones' skinning matrices
// (bone's transform in the pose times its inverse bind transform), its normal by the same sum's linear part.
// Once per posed mesh per frame, on the CPU: every pass and view of the rasteriser, and the path tracer,
// then draw the same deformed vertices (see core/animation/README.md for why not in a vertex shader).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sp::animation {

inline constexpr int kMaxInfluences = 4;

// Per vertex: up to four bones and their weights (summing to 1; unused slots weigh 0).
struct SkinWeights {
    std::vector<std::array<std::uint16_t, kMaxInfluences>> bones;
    std::vector<std::array<float, kMaxInfluences>> weights;

    // Checks sizes (`vertices`), bone indices (< `boneCount`) and weights (finite, >= 0, sum 1 within
    // 1e-3); throws sp::InvalidArgument "<function>(): <what>".
    void validate(std::size_t vertices, std::size_t boneCount, const char* function) const;
};

// The matrices skinning applies: componentSpace[i] * inverseBind[i], as floats.
std::vector<Eigen::Matrix4f> skinningMatrices(std::span<const Eigen::Affine3d> componentSpace,
                                              std::span<const Eigen::Affine3d> inverseBind);

// Deforms `positions` and `normals` (the bind pose, mesh space) into `outPositions` and `outNormals`
// (resized). Normals are renormalised; a vertex whose weights sum to 0 stays where it is.
void skin(std::span<const Eigen::Vector3f> positions, std::span<const Eigen::Vector3f> normals,
          const SkinWeights& weights, std::span<const Eigen::Matrix4f> matrices,
          std::vector<Eigen::Vector3f>& outPositions, std::vector<Eigen::Vector3f>& outNormals);

} // namespace sp::animation
