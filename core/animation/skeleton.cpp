#include "core/animation/skeleton.h"

#include <cmath>
#include <unordered_set>

#include "core/base/error.h"

namespace sp::animation {

Eigen::Affine3d BoneTransform::matrix() const {
    Eigen::Affine3d m = Eigen::Affine3d::Identity();
    m.translation() = translation;
    m.linear() = rotation.normalized().toRotationMatrix() * scale.asDiagonal();
    return m;
}

BoneTransform BoneTransform::fromMatrix(const Eigen::Affine3d& matrix, const char* function) {
    SP_CHECK(matrix.matrix().allFinite(), InvalidArgument, function, "(): a bone transform is not finite");
    BoneTransform out;
    out.translation = matrix.translation();
    Eigen::Matrix3d linear = matrix.linear();
    for (int axis = 0; axis < 3; ++axis) {
        out.scale[axis] = linear.col(axis).norm();
        SP_CHECK(out.scale[axis] > 1e-12, InvalidArgument, function,
                 "(): a bone transform scales an axis to zero");
        linear.col(axis) /= out.scale[axis];
    }
    if (linear.determinant() < 0.0) { // a mirror: carried by the scale, so that the rest is a rotation
        out.scale.x() = -out.scale.x();
        linear.col(0) = -linear.col(0);
    }
    // The nearest rotation (the columns may be a little off orthogonal: a sheared or rounded matrix).
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(linear, Eigen::ComputeFullU | Eigen::ComputeFullV);
    out.rotation = Eigen::Quaterniond(svd.matrixU() * svd.matrixV().transpose()).normalized();
    return out;
}

BoneTransform interpolate(const BoneTransform& a, const BoneTransform& b, double weight) {
    BoneTransform out;
    out.translation = a.translation + weight * (b.translation - a.translation);
    out.scale = a.scale + weight * (b.scale - a.scale);
    out.rotation = a.rotation.slerp(weight, b.rotation).normalized(); // Eigen's slerp takes the shorter arc
    return out;
}

int Skeleton::find(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name)
            return int(i);
    return -1;
}

void Skeleton::validate(const char* function) const {
    SP_CHECK(!names.empty(), InvalidArgument, function, "(): a skeleton needs at least one bone");
    SP_CHECK(parents.size() == names.size() && bindLocal.size() == names.size() &&
                 inverseBind.size() == names.size(),
             InvalidArgument, function, "(): a skeleton of ", names.size(), " bones has ", parents.size(),
             " parents, ", bindLocal.size(), " bind transforms and ", inverseBind.size(), " inverse binds");
    std::unordered_set<std::string> seen;
    for (std::size_t i = 0; i < names.size(); ++i) {
        SP_CHECK(!names[i].empty() && seen.insert(names[i]).second, InvalidArgument, function,
                 "(): bone names must be unique and not empty, got '", names[i], "' twice or empty");
        SP_CHECK(parents[i] >= -1 && parents[i] < int(i), InvalidArgument, function, "(): bone '", names[i],
                 "' has parent ", parents[i], ", which is not a bone before it");
    }
}

std::vector<Eigen::Affine3d> Skeleton::componentSpace(std::span<const BoneTransform> local) const {
    SP_CHECK(local.size() == size(), InvalidArgument, "Skeleton::componentSpace(): a pose of ", local.size(),
             " bones for a skeleton of ", size());
    std::vector<Eigen::Affine3d> out(size());
    for (std::size_t i = 0; i < size(); ++i)
        out[i] = (parents[i] < 0 ? rootTransform : out[std::size_t(parents[i])]) * local[i].matrix();
    return out;
}

Pose Skeleton::localFromComponent(std::span<const Eigen::Affine3d> component, const char* function) const {
    SP_CHECK(component.size() == size(), InvalidArgument, function, "(): ", component.size(),
             " bone transforms for a skeleton of ", size(), " bones");
    Pose out(size());
    for (std::size_t i = 0; i < size(); ++i) {
        const Eigen::Affine3d& parent = parents[i] < 0 ? rootTransform : component[std::size_t(parents[i])];
        out[i] = BoneTransform::fromMatrix(parent.inverse() * component[i], function);
    }
    return out;
}

} // namespace sp::animation
