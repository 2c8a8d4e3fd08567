#pragma once
// Bridge<T>: how a C++ parameter or result type travels through a generated pybind11 binding.
// Bridge<T>::Py is the type pybind11 converts from Python; in() turns it into T (resolving handles and
// class names, checking dtypes); out() turns a T into a Python object. Plain values use pybind11's own
// casters (and the generated ones for reflected structs and enums).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "core/base/error.h"
#include "core/pybind/object_ref.h"
#include "core/pybind/value_convert.h"
#include "core/reflect/class_ref.h"
#include "core/reflect/codec.h"
#include "core/reflect/registry.h"
#include "core/reflect/sp_array.h"

#pragma GCC visibility push(default)
namespace sp::pybind {

// A class argument as Python passes it: a class object carrying __sp_class__, or a class name. The name
// is resolved by Bridge::in(), where the calling function is known for the error message.
struct ClassArg {
    std::string name;  // empty for None
    std::string asset; // a generated blueprint class's asset (__sp_asset__), loaded on first use
    const reflect::TypeInfo* resolve(std::string_view context) const {
        return name.empty() ? nullptr : &reflect::Registry::get().getClass(name, context, asset);
    }
};

// The Python class that stands for `type`: its registered class, or for a blueprint (a class defined by data,
// core/world/blueprint.h) a subclass of its native class's API class carrying __sp_class__ = its name.
py::object pythonClassFor(const reflect::TypeInfo& type);

template <typename T, typename = void> struct Bridge {
    using Py = T;
    static T in(Py value, std::string_view) { return value; }
    static py::object out(const T& value) { return py::cast(value); }
};

inline int anyObject(PyObject*) {
    return 1;
}
// A Python argument taken as it is, for Bridge<T>::in() to check; also built from a C++ default value
// (the generated bindings spell defaults as static_cast<Bridge<T>::Py>(value)).
class PyArg : public py::object {
  public:
    PYBIND11_OBJECT_DEFAULT(PyArg, object, anyObject)
    PyArg(bool value) : py::object(py::bool_(value)) {}
    template <typename T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
    PyArg(T value) : py::object(py::int_(value)) {}
};

// Integers and bools are checked as the RPC server checks them (reflect::ValueCodec), with the same
// messages: pybind11 alone would take True for an int (bool is an int subclass in Python) and 1 for a
// bool. Anything with __index__ (a numpy integer) still passes for an int, range-checked.
template <typename T> struct Bridge<T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>>> {
    using Py = PyArg;
    static T in(const Py& value, std::string_view context) {
        if (!PyBool_Check(value.ptr()) && PyIndex_Check(value.ptr())) {
            const auto index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
            if (!index)
                throw py::error_already_set();
            int overflow = 0;
            const long long number = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
            SP_CHECK(overflow == 0, InvalidArgument, context,
                     " is out of range: ", std::string(py::str(index)));
            return reflect::ValueCodec<T>::decode(reflect::Value(int64_t(number)), context);
        }
        return reflect::ValueCodec<T>::decode(toValue(value, context), context); // refused, named as over RPC
    }
    static py::object out(T value) { return py::int_(value); }
};
template <> struct Bridge<bool> {
    using Py = PyArg;
    static bool in(const Py& value, std::string_view context) {
        if (PyBool_Check(value.ptr()))
            return value.ptr() == Py_True;
        if (std::string_view(Py_TYPE(value.ptr())->tp_name) == "numpy.bool_")
            return value.cast<bool>();
        return reflect::ValueCodec<bool>::decode(toValue(value, context), context);
    }
    static py::object out(bool value) { return py::bool_(value); }
};

template <typename T> struct Bridge<T*, std::enable_if_t<std::is_base_of_v<reflect::ObjectBase, T>>> {
    using Py = Ref<T>*;
    static T* in(Py value, std::string_view context) {
        return value ? value->template get<T>(context) : nullptr;
    }
    static py::object out(const T* value) { return wrapObject(value); }
};

template <> struct Bridge<const UClass*> {
    using Py = ClassArg;
    static const UClass* in(Py value, std::string_view context) { return value.resolve(context); }
    static py::object out(const UClass* value) { return value ? pythonClassFor(*value) : py::none(); }
};

template <typename T> struct Bridge<TSubclassOf<T>> {
    using Py = ClassArg;
    static TSubclassOf<T> in(Py value, std::string_view context) {
        const UClass* type = value.resolve(context);
        SP_CHECK(!type || type->isChildOf(T::StaticClass()), InvalidArgument, context, ": class '",
                 type->name, "' does not derive from ", T::StaticClass().name);
        return TSubclassOf<T>(type);
    }
    static py::object out(const TSubclassOf<T>& value) { return Bridge<const UClass*>::out(value.Get()); }
};

template <typename T> struct Bridge<std::vector<T>> {
    using Py = std::vector<typename Bridge<T>::Py>;
    static std::vector<T> in(Py value, std::string_view context) {
        std::vector<T> result;
        result.reserve(value.size());
        for (auto& item : value)
            result.push_back(Bridge<T>::in(std::move(item), context));
        return result;
    }
    static py::object out(const std::vector<T>& value) {
        py::list result(value.size());
        for (size_t i = 0; i < value.size(); ++i)
            result[i] = Bridge<T>::out(value[i]);
        return result;
    }
};

template <typename T> struct Bridge<std::map<std::string, T>> {
    using Py = std::map<std::string, typename Bridge<T>::Py>;
    static std::map<std::string, T> in(Py value, std::string_view context) {
        std::map<std::string, T> result;
        for (auto& [key, item] : value)
            result.emplace(key, Bridge<T>::in(std::move(item), context));
        return result;
    }
    static py::object out(const std::map<std::string, T>& value) {
        py::dict result;
        for (const auto& [key, item] : value)
            result[py::str(key)] = Bridge<T>::out(item);
        return result;
    }
};

// The dtype of a numpy array; throws InvalidArgument for dtypes that cannot cross (complex, object, ...).
reflect::DType dtypeOf(const py::array& array, std::string_view context);

// numpy <-> ArrayValue without copying: the array keeps the numpy buffer alive and vice versa.
reflect::ArrayValue arrayFromNumpy(const py::array& array, reflect::DType dtype, std::string_view context);
py::array arrayToNumpy(const reflect::ArrayValue& value);

template <typename T> struct Bridge<reflect::SpArray<T>> {
    using Py = py::array;
    static reflect::SpArray<T> in(Py value, std::string_view context) {
        reflect::SpArray<T> result;
        result.assign(arrayFromNumpy(value, reflect::DTypeOf<T>::value, context), context);
        return result;
    }
    static py::object out(const reflect::SpArray<T>& value) { return arrayToNumpy(value.value()); }
};

// Fills `value` from None, a class name, or a class carrying __sp_class__; false for anything else.
// (Defined out of line here, not in the caster: pybind11's namespace is hidden in every shared object.)
bool loadClassArg(py::handle src, ClassArg& value);

// Looks up a class of the generated API module (structs, enums, result tuples); cached by the caller.
py::object apiAttribute(const char* module, const char* name);

} // namespace sp::pybind
#pragma GCC visibility pop

namespace pybind11::detail {

template <> struct type_caster<sp::pybind::ClassArg> {
    PYBIND11_TYPE_CASTER(sp::pybind::ClassArg, const_name("type | str"));
    bool load(handle src, bool) { return sp::pybind::loadClassArg(src, value); }
    static handle cast(const sp::pybind::ClassArg&, return_value_policy, handle) { return none().release(); }
};

} // namespace pybind11::detail
