#pragma once
// How generated functions and properties are installed on their Python classes: as CPython's own method
// descriptors and builtin functions with the vectorcall convention (METH_FASTCALL | METH_KEYWORDS), not
// through pybind11's dispatcher. pybind11's dispatcher suits overloads; a generated function has exactly one
// signature and converts every argument itself (Bridge<T>), so what the dispatcher did per call (the
// argument vectors it allocates, the `*args` tuple and `**kwargs` dict, the type lookups by type_index, the
// caster of `self`) was most of a typed call's cost: `GetName()` was 2.4x a bare pybind11 call.
//
// What a caller sees is unchanged: the same docstrings (signature line first), properties that are Python
// `property` objects, static functions that are `staticmethod`s, the same TypeError for a call that does not
// fit (checkCall), and C++ exceptions translated by pybind11's registered translators.

#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <type_traits>

#include "core/pybind/bridge.h"
#include "core/pybind/object_ref.h"

#pragma GCC visibility push(default)
namespace sp::pybind {

// An empty tuple and dict for PyCallArgs when a call brings nothing beyond its parameters (never freed, so
// that nothing is released after the interpreter is gone).
const py::args& noPositional();
const py::kwargs& noKeywords();

// The handle of `self` (selfRef(PyObject*) in object_ref.h), checked against `cls` first: a property's
// accessors can be called directly, with anything.
const RefBase& selfRef(PyObject* cls, PyObject* self);

// The Python error for the C++ exception being handled, through pybind11's translators (the module's own
// first, then the global ones, as pybind11's dispatcher does). Call inside a catch block.
inline void raiseActiveException() {
    try {
        throw;
    } catch (py::error_already_set& error) {
        error.restore();
        return;
    } catch (...) {
    }
    if (py::detail::apply_exception_translators(
            py::detail::get_local_internals().registered_exception_translators))
        return;
    if (py::detail::apply_exception_translators(py::detail::get_internals().registered_exception_translators))
        return;
    PyErr_SetString(PyExc_SystemError, "an exception escaped every exception translator");
}

// One generated function's parameters: their names (interned once, so that a keyword from a call site, which
// Python interns too, usually matches by pointer) and the vectorcall that sorts arguments into them.
template <std::size_t N> class Parameters {
  public:
    void name(const std::array<const char*, N>& names) {
        for (std::size_t i = 0; i < N; ++i)
            names_[i] = PyUnicode_InternFromString(names[i]); // kept for the module's lifetime
    }

    // Calls body(PyCallArgs) with the arguments of a vectorcall. What fits the parameters (keywords only)
    // goes straight in; anything else (a positional argument, an unknown keyword) is collected as a tuple
    // and a dict for checkCall, which raises the TypeError Python would.
    template <typename Body>
    py::object call(PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames, bool method,
                    Body&& body) const {
        std::array<PyArg, N> values;
        std::array<const PyArg*, N> pointers;
        for (std::size_t i = 0; i < N; ++i) {
            values[i] = py::reinterpret_borrow<PyArg>(missingArgument());
            pointers[i] = &values[i];
        }
        const Py_ssize_t keywords = kwnames ? PyTuple_GET_SIZE(kwnames) : 0;
        bool unknown = false;
        for (Py_ssize_t k = 0; k < keywords; ++k) {
            const std::size_t slot = find(PyTuple_GET_ITEM(kwnames, k));
            if (slot == N)
                unknown = true;
            else
                values[slot] = py::reinterpret_borrow<PyArg>(args[nargs + k]);
        }
        if (nargs == 0 && !unknown)
            return body(PyCallArgs{noPositional(), noKeywords(), pointers, method});
        py::args positional = py::reinterpret_steal<py::args>(PyTuple_New(nargs));
        for (Py_ssize_t i = 0; i < nargs; ++i)
            PyTuple_SET_ITEM(positional.ptr(), i, py::handle(args[i]).inc_ref().ptr());
        py::kwargs extra;
        for (Py_ssize_t k = 0; k < keywords; ++k)
            if (find(PyTuple_GET_ITEM(kwnames, k)) == N)
                extra[PyTuple_GET_ITEM(kwnames, k)] = py::handle(args[nargs + k]);
        return body(PyCallArgs{positional, extra, pointers, method});
    }

  private:
    std::size_t find(PyObject* keyword) const {
        for (std::size_t i = 0; i < N; ++i)
            if (names_[i] == keyword)
                return i;
        for (std::size_t i = 0; i < N; ++i)
            if (PyUnicode_Compare(names_[i], keyword) == 0)
                return i;
        return N;
    }

    std::array<PyObject*, N> names_{};
};

// A generated function body: Body is the type of a lambda without captures (default-constructible), so each
// function gets its own entry point and PyMethodDef.
template <typename Body, std::size_t N> struct Method {
    static inline Parameters<N> parameters;
    static inline PyMethodDef def{};

    static PyObject* onObject(PyObject* self, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames) {
        try {
            const RefBase& ref = selfRef(self);
            return parameters
                .call(args, nargs, kwnames, true,
                      [&ref](const PyCallArgs& call) { return Body{}(ref, call); })
                .release()
                .ptr();
        } catch (...) {
            raiseActiveException();
            return nullptr;
        }
    }
    static PyObject* onClass(PyObject*, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames) {
        try {
            return parameters.call(args, nargs, kwnames, false, Body{}).release().ptr();
        } catch (...) {
            raiseActiveException();
            return nullptr;
        }
    }
};

void installMethod(py::handle cls, const char* name, PyMethodDef& def);
void installStatic(py::handle cls, const char* name, PyMethodDef& def);

// cls.<name>(*, params...): body(const RefBase& self, const PyCallArgs&) -> py::object.
template <typename Body, std::size_t N>
void defMethod(py::handle cls, const char* name, const std::array<const char*, N>& params, Body,
               const char* doc) {
    using M = Method<Body, N>;
    M::parameters.name(params);
    M::def = PyMethodDef{name, reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&M::onObject)),
                         METH_FASTCALL | METH_KEYWORDS, doc};
    installMethod(cls, name, M::def);
}

// A static function: body(const PyCallArgs&) -> py::object, called on the class.
template <typename Body, std::size_t N>
void defStatic(py::handle cls, const char* name, const std::array<const char*, N>& params, Body,
               const char* doc) {
    using M = Method<Body, N>;
    M::parameters.name(params);
    M::def = PyMethodDef{name, reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&M::onClass)),
                         METH_FASTCALL | METH_KEYWORDS, doc};
    installStatic(cls, name, M::def);
}

// A property's accessors: Get(const RefBase&) -> py::object, Set(const RefBase&, const PyArg&).
// Each is a builtin bound to its class, which it checks `self` against (a property's fget can be called
// directly, with anything).
template <typename Get> struct Getter {
    static inline PyMethodDef def{};
    static PyObject* get(PyObject* cls, PyObject* self) {
        try {
            return Get{}(selfRef(cls, self)).release().ptr();
        } catch (...) {
            raiseActiveException();
            return nullptr;
        }
    }
};
template <typename Set> struct Setter {
    static inline PyMethodDef def{};
    static PyObject* set(PyObject* cls, PyObject* const* args, Py_ssize_t nargs) {
        try {
            if (nargs != 2) // property calls fset(self, value); anything else is a direct misuse of fset
                throw py::type_error(std::string(def.ml_name) +
                                     ": a property setter takes the object and the value");
            Set{}(selfRef(cls, args[0]), py::reinterpret_borrow<PyArg>(args[1]));
            return py::none().release().ptr();
        } catch (...) {
            raiseActiveException();
            return nullptr;
        }
    }
};

// A Python property whose getter and setter are builtin functions; the setter may be null (read-only).
void installProperty(py::handle cls, const char* name, PyMethodDef& get, PyMethodDef* set, const char* doc);

template <typename Get> void defReadonly(py::handle cls, const char* name, Get, const char* doc) {
    Getter<Get>::def = PyMethodDef{name, reinterpret_cast<PyCFunction>(&Getter<Get>::get), METH_O, doc};
    installProperty(cls, name, Getter<Get>::def, nullptr, doc);
}

template <typename Get, typename Set>
void defProperty(py::handle cls, const char* name, Get, Set, const char* doc) {
    Getter<Get>::def = PyMethodDef{name, reinterpret_cast<PyCFunction>(&Getter<Get>::get), METH_O, doc};
    Setter<Set>::def =
        PyMethodDef{name, reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&Setter<Set>::set)),
                    METH_FASTCALL, doc};
    installProperty(cls, name, Getter<Get>::def, &Setter<Set>::def, doc);
}

} // namespace sp::pybind
#pragma GCC visibility pop
