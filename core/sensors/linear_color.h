#pragma once
// A reflected colour as the renderer takes it: linear RGB, alpha dropped.

#include <Eigen/Core>

#include "core/world/math.h"

namespace sp::sensors {

inline Eigen::Vector3f rgb(const FLinearColor& color) {
    return {color.R, color.G, color.B};
}

} // namespace sp::sensors
