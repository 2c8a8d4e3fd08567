#pragma once
// The dynamic API beside the typed one: functions and properties by name, through the same registry
// invokers that the RPC server uses.

#include <pybind11/pybind11.h>

#include <string_view>

#include "core/reflect/object_base.h"

#pragma GCC visibility push(default)
namespace sp::pybind {

// The engine object behind a Python object (anything with `_sp_handle`), checked alive.
reflect::ObjectBase& resolveHandle(pybind11::handle object, std::string_view context);
// The same, checked usable now as well (inside a frame, for engine objects).
reflect::ObjectBase& resolveArgument(pybind11::handle object, std::string_view context);

// Adds call_function, get_property, set_property and the class queries to `m`. `apiModule` names the
// generated Python module whose structs and enums results are built from.
void bindDynamicAccess(pybind11::module_& m, const char* apiModule);

} // namespace sp::pybind
#pragma GCC visibility pop
