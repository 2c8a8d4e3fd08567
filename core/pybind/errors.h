#pragma once
// Maps the engine's C++ error types to the Python exception classes of spear.errors, in one place.

#include <pybind11/pybind11.h>

namespace sp::pybind {

void registerErrorTranslator();

} // namespace sp::pybind
