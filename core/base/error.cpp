#include "core/base/error.h"

namespace sp {

const char* pythonErrorClass(const std::exception& error) {
    if (dynamic_cast<const StaleObject*>(&error))
        return "StaleObjectError";
    if (dynamic_cast<const NotFound*>(&error))
        return "NotFoundError";
    if (dynamic_cast<const InvalidArgument*>(&error))
        return "InvalidArgumentError";
    if (dynamic_cast<const InvalidState*>(&error))
        return "InvalidStateError";
    return "SpearError";
}

} // namespace sp
