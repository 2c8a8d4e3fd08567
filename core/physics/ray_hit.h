#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "core/physics/body_id.h"

namespace sp::physics {

// Where a ray first meets one body.
struct RayHit {
    // The body that was hit.
    BodyId body;
    // That body's BodyDesc::tag, so the caller can map the hit back to its owner.
    uint64_t tag = 0;
    // Hit point in world coordinates, metres.
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    // Unit surface normal at the hit point in world coordinates, facing the ray's origin side.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    // Position of the hit along the ray: point = from + fraction * (to - from), in [0, 1].
    double fraction = 0.0;
};

} // namespace sp::physics
