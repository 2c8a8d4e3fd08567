#pragma once
// Conversions between the public Eigen types and Bullet's. Internal: only core/physics/*.cpp include
// this, because it pulls in Bullet (built with BT_USE_DOUBLE_PRECISION, so no precision is lost).

#include <Eigen/Geometry>
#include <LinearMath/btTransform.h>

namespace sp::physics::detail {

inline btVector3 toBullet(const Eigen::Vector3d& v) {
    return btVector3(v.x(), v.y(), v.z());
}

inline Eigen::Vector3d toEigen(const btVector3& v) {
    return Eigen::Vector3d(v.x(), v.y(), v.z());
}

inline btTransform toBullet(const Eigen::Isometry3d& pose) {
    const Eigen::Quaterniond q(pose.linear());
    return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), toBullet(pose.translation()));
}

inline Eigen::Isometry3d toEigen(const btTransform& transform) {
    const btQuaternion q = transform.getRotation();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).toRotationMatrix();
    pose.translation() = toEigen(transform.getOrigin());
    return pose;
}

} // namespace sp::physics::detail
