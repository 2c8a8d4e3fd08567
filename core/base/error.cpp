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

void rethrowWithPrefix(const std::string& prefix) {
    try {
        throw;
    } catch (const StaleObject& error) {
        throw StaleObject(prefix + error.what());
    } catch (const NotFound& error) {
        throw NotFound(prefix + error.what());
    } catch (const InvalidArgument& error) {
        throw InvalidArgument(prefix + error.what());
    } catch (const InvalidState& error) {
        throw InvalidState(prefix + error.what());
    } catch (const Error& error) {
        throw Error(prefix + error.what());
    }
}

} // namespace sp
