#include "core/pybind/fast_call.h"

namespace sp::pybind {

const py::args& noPositional() {
    static const py::args* const empty = new py::args();
    return *empty;
}

const py::kwargs& noKeywords() {
    static const py::kwargs* const empty = new py::kwargs();
    return *empty;
}

const RefBase& selfRef(PyObject* cls, PyObject* self) {
    if (!PyObject_TypeCheck(self, reinterpret_cast<PyTypeObject*>(cls)))
        throw py::type_error(std::string("descriptor for '") + reinterpret_cast<PyTypeObject*>(cls)->tp_name +
                             "' objects doesn't apply to a '" + Py_TYPE(self)->tp_name + "' object");
    return selfRef(self);
}

void installMethod(py::handle cls, const char* name, PyMethodDef& def) {
    auto descriptor = py::reinterpret_steal<py::object>(
        PyDescr_NewMethod(reinterpret_cast<PyTypeObject*>(cls.ptr()), &def));
    if (!descriptor)
        throw py::error_already_set();
    py::setattr(cls, name, descriptor);
}

void installStatic(py::handle cls, const char* name, PyMethodDef& def) {
    auto function = py::reinterpret_steal<py::object>(PyCFunction_NewEx(&def, nullptr, nullptr));
    if (!function)
        throw py::error_already_set();
    auto method = py::reinterpret_steal<py::object>(PyStaticMethod_New(function.ptr()));
    if (!method)
        throw py::error_already_set();
    py::setattr(cls, name, method);
}

void installProperty(py::handle cls, const char* name, PyMethodDef& get, PyMethodDef* set, const char* doc) {
    // Bound to the class (the builtin's `self`), which each accessor checks its object against.
    auto getter = py::reinterpret_steal<py::object>(PyCFunction_NewEx(&get, cls.ptr(), nullptr));
    if (!getter)
        throw py::error_already_set();
    py::object setter = py::none();
    if (set) {
        setter = py::reinterpret_steal<py::object>(PyCFunction_NewEx(set, cls.ptr(), nullptr));
        if (!setter)
            throw py::error_already_set();
    }
    auto property = py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyProperty_Type));
    py::setattr(cls, name, property(getter, setter, py::none(), doc));
}

} // namespace sp::pybind
