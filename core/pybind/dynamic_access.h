#pragma once
// The dynamic API beside the typed one: functions and properties by name, through the same registry
// invokers that the RPC server uses.

#include <pybind11/pybind11.h>

namespace sp::pybind {

// Adds call_function, get_property, set_property and the class queries to `m`. `apiModule` names the
// generated Python module whose structs and enums results are built from.
void bindDynamicAccess(pybind11::module_& m, const char* apiModule);

} // namespace sp::pybind
