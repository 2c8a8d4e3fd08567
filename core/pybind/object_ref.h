#pragma once
// How engine objects appear in Python in-process: every reflected class C is a pybind11 class over
// Ref<C>, a generation-checked handle (never a pointer), with the same inheritance as C. Generated code
// specialises Ref<C> for each class; resolving a Ref checks that the object is alive and that the call
// is allowed now (inside a frame), so a stale handle raises instead of crashing the engine.

#include <pybind11/pybind11.h>

#include <string_view>

#include "core/reflect/object_base.h"
#include "core/reflect/type_info.h"

// spear_pybind is a shared library used by every pybind11 module (the engine's and each plugin's).
// pybind11 declares its namespace hidden, which would hide every function taking a pybind11 type, so
// this API is made visible explicitly.
#pragma GCC visibility push(default)
namespace sp::pybind {

namespace py = ::pybind11;

// Checks whether `object` may be used now; throws (e.g. InvalidState outside a frame). Installed by the
// engine module; the default allows everything.
using AccessCheck = void (*)(reflect::ObjectBase& object, std::string_view context);
void setAccessCheck(AccessCheck check);
void checkAccess(reflect::ObjectBase& object, std::string_view context);

struct RefBase {
    reflect::ObjectHandle handle;

    RefBase() = default;
    explicit RefBase(reflect::ObjectHandle h) : handle(h) {}

    reflect::ObjectBase& resolve(std::string_view context) const {
        reflect::ObjectBase& object = reflect::ObjectTable::resolve(handle, context);
        checkAccess(object, context);
        return object;
    }
    template <typename T> T* get(std::string_view context) const {
        return static_cast<T*>(&resolve(context));
    }
};

// Specialised by generated code: template <> struct Ref<AActor> : Ref<UObject> { ... };
template <typename T> struct Ref;

// The handle of `self`, an instance of a generated class (whose C++ value is a Ref<C>: a RefBase and nothing
// else), read from the pybind11 instance. Throws TypeError for an instance whose C++ value was never made (a
// subclass that skipped __init__). The caller knows `self` is such an instance (a method descriptor checked).
const RefBase& selfRef(PyObject* self);
// The handle of `object` if it is an instance of the generated classes (their root class's), without a Python
// attribute lookup; nullptr for anything else (an RPC proxy, a number, ...).
const RefBase* nativeRef(py::handle object);

// Python wrappers: the most derived registered pybind11 class for an object's runtime class.
using WrapFn = py::object (*)(reflect::ObjectHandle);
void registerWrapper(const reflect::TypeInfo& type, WrapFn wrap, py::handle pythonClass);
py::object wrapObject(const reflect::ObjectBase* object);
// The Python class registered for `type` (or its nearest registered parent).
py::object pythonClassOf(const reflect::TypeInfo& type);

template <typename T> py::object makeWrapper(reflect::ObjectHandle handle) {
    return py::cast(Ref<T>(handle), py::return_value_policy::move);
}

// repr, equality and hashing by handle, and `_sp_handle` for the dynamic API; on the root class only.
std::string describeHandle(reflect::ObjectHandle handle, const char* pythonClass);
// spear.futures.ImmediateCaller, looked up once: importing it on every call_async / send_async cost as much
// as the call it wraps. Never released, so that no Python object is freed after the interpreter is gone.
inline py::handle immediateCaller() {
    static const py::object* const type =
        new py::object(py::module_::import("spear.futures").attr("ImmediateCaller"));
    return *type;
}

template <typename R> void bindObjectBasics(py::class_<R>& cls) {
    cls.def_property_readonly("_sp_handle", [](const R& self) {
        return std::make_pair(self.handle.index, self.handle.generation);
    });
    cls.def("__eq__", [](const R& self, py::handle other) {
        if (!py::hasattr(other, "_sp_handle") || py::hasattr(other, "_sp_client")) // an RPC engine's object
            return false;
        return other.attr("_sp_handle").cast<std::pair<uint32_t, uint32_t>>() ==
               std::make_pair(self.handle.index, self.handle.generation);
    });
    cls.def("__hash__", [](const R& self) {
        return py::hash(py::make_tuple(self.handle.index, self.handle.generation));
    });
    cls.def("__repr__", [](py::handle self) {
        const auto& ref = self.cast<const R&>();
        return describeHandle(ref.handle,
                              py::str(self.get_type().attr("__name__")).cast<std::string>().c_str());
    });
    cls.def(
        "is_valid", [](const R& self) { return reflect::ObjectTable::find(self.handle) != nullptr; },
        "True while the object exists; False once it was destroyed.");
    // In-process, asynchronous calls run at once and return resolved futures (spear.futures).
    cls.def_property_readonly(
        "call_async", [](py::object self) { return immediateCaller()(self); },
        "The same functions, asynchronous: each returns a Future.");
    cls.def_property_readonly(
        "send_async", [](py::object self) { return immediateCaller()(self, true); },
        "The same functions, fire and forget.");
}

} // namespace sp::pybind
#pragma GCC visibility pop
