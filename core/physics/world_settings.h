#pragma once

#include <Eigen/Core>

namespace sp::physics {

// Construction parameters of a PhysicsWorld.
struct WorldSettings {
    // Gravity acceleration in m/s^2 (Z up).
    Eigen::Vector3d gravity{0.0, 0.0, -9.81};
    // Length of one simulation substep in seconds. step(dt) runs as many whole substeps as fit in the
    // accumulated time; 1/240 s keeps resting contacts within a fraction of a millimetre and divides
    // 1/30, 1/60 and 1/120 s frames exactly.
    double fixedTimeStep = 1.0 / 240.0;
    // Constraint solver iterations per substep; more gives stiffer stacks at a linear cost.
    int solverIterations = 10;
};

} // namespace sp::physics
