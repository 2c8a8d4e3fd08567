#pragma once
// Formatting helpers for error messages.

#include <ostream>

#include <Eigen/Core>

namespace sp::physics::detail {

// Streams a vector as "(x, y, z)": SP_THROW(..., "scale ", Vec{scale}, " must be > 0").
struct Vec {
    const Eigen::Vector3d& v;
};

inline std::ostream& operator<<(std::ostream& out, const Vec& vec) {
    return out << '(' << vec.v.x() << ", " << vec.v.y() << ", " << vec.v.z() << ')';
}

} // namespace sp::physics::detail
