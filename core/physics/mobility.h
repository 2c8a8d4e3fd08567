#pragma once

#include <iosfwd>

namespace sp::physics {

// Whether a body may move at all. A Movable body is either simulated (dynamic: gravity, forces and
// contacts move it) or not (kinematic: only setPose moves it, and it pushes simulated bodies aside).
enum class Mobility {
    // Never moves; costs nothing while other bodies rest on it.
    Static,
    // May move, by simulation or by setPose.
    Movable,
};

// Writes "Static" or "Movable".
std::ostream& operator<<(std::ostream& out, Mobility mobility);

} // namespace sp::physics
