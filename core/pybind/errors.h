#pragma once
// Maps the engine's C++ error types to the Python exception classes of spear.errors, in one place.

#include <pybind11/pybind11.h>

#pragma GCC visibility push(default)
namespace sp::pybind {

void registerErrorTranslator();

} // namespace sp::pybind
#pragma GCC visibility pop
