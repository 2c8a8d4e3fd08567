#include "core/pybind/errors.h"

#include "core/base/error.h"

namespace sp::pybind {

namespace py = ::pybind11;

namespace {
void raise(const char* className, const std::exception& e) {
    // spear.errors is pure Python so that the RPC client raises the very same classes.
    py::object cls = py::module_::import("spear.errors").attr(className);
    PyErr_SetString(cls.ptr(), e.what());
}
} // namespace

void registerErrorTranslator() {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const Error& e) {
            raise(pythonErrorClass(e), e);
        }
    });
}

} // namespace sp::pybind
