#pragma once
// A generation-checked handle to a body in a PhysicsWorld. Components hold these instead of pointers; a
// handle whose body was removed is detected (sp::StaleObject) and never dereferenced.

#include <compare>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>

namespace sp::physics {

// Identifies one body of one PhysicsWorld: the slot index and the generation of that slot.
struct BodyId {
    static constexpr uint32_t kInvalidIndex = std::numeric_limits<uint32_t>::max();

    // Slot of the body in its world.
    uint32_t index = kInvalidIndex;
    // Bumped each time the slot's body is removed, so old ids become stale.
    uint32_t generation = 0;

    // The id that never names a body (also the value of a default-constructed BodyId).
    static constexpr BodyId invalid() { return BodyId{}; }

    // True unless this is the invalid id; says nothing about whether the body still exists.
    constexpr bool isSet() const { return index != kInvalidIndex; }

    friend constexpr bool operator==(const BodyId&, const BodyId&) = default;
    // An order (by slot, then generation) for keeping ids in sorted containers.
    friend constexpr auto operator<=>(const BodyId&, const BodyId&) = default;
};

// Writes "index:generation" ("3:1"), or "invalid" for BodyId::invalid(); used in error messages.
std::ostream& operator<<(std::ostream& out, const BodyId& id);

} // namespace sp::physics

template <> struct std::hash<sp::physics::BodyId> {
    size_t operator()(const sp::physics::BodyId& id) const noexcept {
        return std::hash<uint64_t>{}((uint64_t(id.generation) << 32) | id.index);
    }
};
