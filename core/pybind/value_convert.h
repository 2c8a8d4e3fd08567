#pragma once
// Conversion between Python objects and registry Values, for the dynamic API (call_function,
// get_property, set_property by name) that works beside the typed one through the same registry.

#include <pybind11/pybind11.h>

#include <string_view>

#include "core/reflect/type_code.h"
#include "core/reflect/value.h"

#pragma GCC visibility push(default)
namespace sp::pybind {

namespace py = ::pybind11;

// None, bool, int (and IntEnum), float, str, list/tuple, dict, numpy arrays, the generated struct
// dataclasses, engine objects and classes (anything with __sp_class__).
reflect::Value toValue(py::handle object, std::string_view context);

// The handle of an engine object of this process (anything with `_sp_handle`); an object of an engine over
// RPC has one too, which means something to its server only, and is refused naming `context`.
reflect::ObjectHandle localHandle(py::handle object, std::string_view context);

// `type` is the value's declared type as the registry records it; it decides which struct dataclass to
// build. Null: not recorded (the value alone decides).
py::object fromValue(const reflect::Value& value, const reflect::TypeCode* type, const char* apiModule);

} // namespace sp::pybind
#pragma GCC visibility pop
