#include "core/animation/skinning.h"

#include <cmath>

#include "core/base/error.h"

namespace sp::animation {

void SkinWeights::validate(std::size_t vertices, std::size_t boneCount, const char* function) const {
    SP_CHECK(bones.size() == vertices && weights.size() == vertices, InvalidArgument, function,
             "(): ", bones.size(), " bone sets and ", weights.size(), " weight sets for ", vertices,
             " vertices");
    for (std::size_t v = 0; v < vertices; ++v) {
        float sum = 0.0f;
        for (int k = 0; k < kMaxInfluences; ++k) {
            SP_CHECK(std::isfinite(weights[v][k]) && weights[v][k] >= 0.0f, InvalidArgument, function,
                     "(): vertex ", v, " has weight ", weights[v][k]);
            SP_CHECK(weights[v][k] == 0.0f || bones[v][k] < boneCount, InvalidArgument, function,
                     "(): vertex ", v, " names bone ", bones[v][k], " of a skeleton of ", boneCount);
            sum += weights[v][k];
        }
        SP_CHECK(std::abs(sum - 1.0f) <= 1e-3f, InvalidArgument, function, "(): vertex ", v,
                 "'s weights sum to ", sum, ", not 1");
    }
}

std::vector<Eigen::Matrix4f> skinningMatrices(std::span<const Eigen::Affine3d> componentSpace,
                                              std::span<const Eigen::Affine3d> inverseBind) {
    SP_CHECK(componentSpace.size() == inverseBind.size(), InvalidArgument,
             "skinningMatrices(): ", componentSpace.size(), " bone transforms and ", inverseBind.size(),
             " inverse binds");
    std::vector<Eigen::Matrix4f> out(componentSpace.size());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = (componentSpace[i] * inverseBind[i]).matrix().cast<float>();
    return out;
}

void skin(std::span<const Eigen::Vector3f> positions, std::span<const Eigen::Vector3f> normals,
          const SkinWeights& weights, std::span<const Eigen::Matrix4f> matrices,
          std::vector<Eigen::Vector3f>& outPositions, std::vector<Eigen::Vector3f>& outNormals) {
    SP_CHECK(normals.size() == positions.size() && weights.bones.size() == positions.size(), InvalidArgument,
             "skin(): ", positions.size(), " positions, ", normals.size(), " normals, ", weights.bones.size(),
             " weight sets");
    outPositions.resize(positions.size());
    outNormals.resize(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) {
        Eigen::Matrix<float, 3, 4> m = Eigen::Matrix<float, 3, 4>::Zero();
        float total = 0.0f;
        for (int k = 0; k < kMaxInfluences; ++k) {
            const float w = weights.weights[v][k];
            if (w == 0.0f)
                continue;
            m += w * matrices[weights.bones[v][k]].topRows<3>();
            total += w;
        }
        if (total == 0.0f) {
            outPositions[v] = positions[v];
            outNormals[v] = normals[v];
            continue;
        }
        outPositions[v] = m.leftCols<3>() * positions[v] + m.col(3);
        const Eigen::Vector3f n = m.leftCols<3>() * normals[v];
        const float length = n.norm();
        outNormals[v] = length > 0.0f ? Eigen::Vector3f(n / length) : normals[v];
    }
}

} // namespace sp::animation
