#pragma once
// Walking characters on Bullet's kinematic character controller: an upright cylinder of the capsule's
// radius and height, moved by the walk velocity it is given, sliding along walls, climbing steps up to its
// step height and slopes up to its steepest walkable slope, falling with the world's gravity and jumping.
// (A cylinder rather than a capsule: Bullet's controller slides a rounded bottom up over any edge below
// its centre, climbing steps far above the step height.) It is kinematic: bodies do not push it, and it
// stops them as a wall would. Rays and overlap queries do not see it.

#include <Eigen/Core>

namespace sp::physics {

struct CharacterDesc {
    double radius = 0.35;    // capsule radius in metres (> 0)
    double halfHeight = 0.9; // half the capsule's height, hemispheres included, in metres (> radius)
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); // the capsule's centre in the world
    double stepHeight = 0.45;                           // the highest step it walks up, metres (>= 0)
    double maxSlopeDegrees = 44.765;                    // the steepest slope it walks up, degrees in (0, 90)
    double jumpSpeed = 4.2;                             // upward speed of a jump, m/s (>= 0)

    bool operator==(const CharacterDesc&) const = default;
};

} // namespace sp::physics
