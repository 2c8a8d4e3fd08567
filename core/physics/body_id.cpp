#include "core/physics/body_id.h"

#include <ostream>

namespace sp::physics {

std::ostream& operator<<(std::ostream& out, const BodyId& id) {
    if (!id.isSet())
        return out << "invalid";
    return out << id.index << ':' << id.generation;
}

} // namespace sp::physics
