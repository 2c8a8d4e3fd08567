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
        } catch (const py::error_already_set&) {
            throw; // a Python error on its way back: pybind11 restores it
        } catch (const std::bad_alloc&) {
            throw; // MemoryError
        } catch (const py::builtin_exception&) {
            throw; // pybind11's own (cast errors and the like): its translator maps them
        } catch (const std::exception& e) {
            // Anything else engine or plugin code throws: SpearError, as the RPC server reports it.
            raise("SpearError", e);
        }
    });
}

} // namespace sp::pybind
