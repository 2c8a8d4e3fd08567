#include "core/physics/mobility.h"

#include <ostream>

namespace sp::physics {

std::ostream& operator<<(std::ostream& out, Mobility mobility) {
    switch (mobility) {
    case Mobility::Static:
        return out << "Static";
    case Mobility::Movable:
        return out << "Movable";
    }
    return out << "Mobility(" << int(mobility) << ')';
}

} // namespace sp::physics
