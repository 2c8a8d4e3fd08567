#pragma once
// Formatting and checking helpers for error messages.

#include <cmath>
#include <ostream>

#include <Eigen/Core>

#include "core/base/error.h"

namespace sp::physics::detail {

// Streams a vector as "(x, y, z)": SP_THROW(..., "scale ", Vec{scale}, " must be > 0").
struct Vec {
    const Eigen::Vector3d& v;
};

inline std::ostream& operator<<(std::ostream& out, const Vec& vec) {
    return out << '(' << vec.v.x() << ", " << vec.v.y() << ", " << vec.v.z() << ')';
}

// Throws sp::InvalidArgument "<function>: <name> <value> must be <range>" unless value is finite and ok:
// checkField(fn, "radius", r, r > 0.0, "> 0").
inline void checkField(const char* function, const char* name, double value, bool ok, const char* range) {
    SP_CHECK(std::isfinite(value) && ok, InvalidArgument, function, ": ", name, ' ', value, " must be ",
             range);
}

} // namespace sp::physics::detail
