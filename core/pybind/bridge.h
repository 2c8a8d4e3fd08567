#pragma once
// Bridge<T>: how a C++ parameter or result type travels through a generated pybind11 binding.
// Every argument arrives as a PyArg (any Python object); Bridge<T>::in() turns it into T (resolving
// handles and class names, checking dtypes) and refuses what the RPC server would refuse, with the server's
// message; out() turns a T into a Python object. Plain values use pybind11's own casters where they agree
// with the server (and the generated ones for reflected structs and enums).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/base/error.h"
#include "core/pybind/object_ref.h"
#include "core/pybind/value_convert.h"
#include "core/reflect/class_ref.h"
#include "core/reflect/codec.h"
#include "core/reflect/invoke.h"
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

// The Python class that stands for `type`: the API module's class of its name (spear.ADefaultPawn, what a
// class reference decodes to over RPC too; its bound class when no API module has one), or for a blueprint (a
// class defined by data, core/scene/blueprint.h) a subclass of its native class's API class carrying
// __sp_class__ = its name.
py::object pythonClassFor(const reflect::TypeInfo& type);

// Fills `value` from None, a class name, or a class carrying __sp_class__; false for anything else.
// (Defined out of line here, not in the caster: pybind11's namespace is hidden in every shared object.)
bool loadClassArg(py::handle src, ClassArg& value);

inline int anyObject(PyObject*) {
    return 1;
}
// A Python argument taken as it is, for Bridge<T>::in() to convert. Every parameter and property value of
// a generated binding arrives as one, so that pybind11 never refuses an argument with its own message.
class PyArg : public py::object {
  public:
    PYBIND11_OBJECT_DEFAULT(PyArg, object, anyObject)
};

// What both transports do with a value pybind11 would not take: decode it as the RPC server decodes what
// the client sends (toValue() is the client's encoding, ValueCodec the server's decoding). That accepts
// exactly what the server accepts and otherwise throws the server's InvalidArgument, word for word.
template <typename T> T decodeAsServer(py::handle value, std::string_view context) {
    return reflect::ValueCodec<T>::decode(toValue(value, context), context);
}

// The fast path for values pybind11's caster takes (T's generated caster for structs and enums); the
// server's decoding for the rest. A caster that throws (a struct with a bad field) is answered the same way.
template <typename T> T convertArgument(py::handle value, std::string_view context) {
    py::detail::make_caster<T> caster;
    bool loaded = false;
    try {
        loaded = caster.load(value, true);
    } catch (const py::cast_error&) {
    } catch (const py::error_already_set&) {
    } catch (const InvalidArgument&) {
    }
    if (loaded)
        return py::detail::cast_op<T>(std::move(caster));
    return decodeAsServer<T>(value, context);
}

template <typename T, typename = void> struct Bridge {
    using Py = PyArg;
    static T in(const Py& value, std::string_view context) { return convertArgument<T>(value, context); }
    static py::object out(const T& value) { return py::cast(value); }
};

// Strings: str only (pybind11 would also take bytes, which the RPC client cannot send as a str).
template <> struct Bridge<std::string> {
    using Py = PyArg;
    static std::string in(const Py& value, std::string_view context) {
        if (PyUnicode_Check(value.ptr()))
            return value.cast<std::string>();
        return decodeAsServer<std::string>(value, context);
    }
    static py::object out(const std::string& value) { return py::str(value); }
};

// Floats take float and int, as the server does; pybind11 alone would take True (bool is an int subclass)
// and anything with __float__.
template <typename T> struct Bridge<T, std::enable_if_t<std::is_floating_point_v<T>>> {
    using Py = PyArg;
    static T in(const Py& value, std::string_view context) {
        if (PyFloat_Check(value.ptr()))
            return T(PyFloat_AS_DOUBLE(value.ptr()));
        return decodeAsServer<T>(value, context);
    }
    static py::object out(T value) { return py::float_(double(value)); }
};

// Integers and bools are checked as the RPC server checks them (reflect::ValueCodec), with the same
// messages: pybind11 alone would take True for an int (bool is an int subclass in Python) and 1 for a
// bool. Anything with __index__ (a numpy integer) still passes for an int, range-checked.
template <typename T> struct Bridge<T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>>> {
    using Py = PyArg;
    static T in(const Py& value, std::string_view context) {
        if (!PyBool_Check(value.ptr()) && PyIndex_Check(value.ptr())) {
            const auto index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
            if (!index) { // an object whose __index__ fails (an array of several numbers): refused as the
                          // server would
                PyErr_Clear();
                return decodeAsServer<T>(value, context);
            }
            int overflow = 0;
            const long long number = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
            if (overflow) // past 64 bits: refused as the RPC client refuses it
                return decodeAsServer<T>(index, context);
            return reflect::ValueCodec<T>::decode(reflect::Value(int64_t(number)), context);
        }
        return decodeAsServer<T>(value, context); // refused, named as over RPC
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
        return decodeAsServer<bool>(value, context);
    }
    static py::object out(bool value) { return py::bool_(value); }
};

template <typename T> struct Bridge<T*, std::enable_if_t<std::is_base_of_v<reflect::ObjectBase, T>>> {
    using Py = PyArg;
    static T* in(const Py& value, std::string_view context) {
        if (value.is_none())
            return nullptr;
        py::detail::make_caster<Ref<T>> caster;
        if (caster.load(value, false))
            return py::detail::cast_op<Ref<T>&>(caster).template get<T>(context);
        return decodeAsServer<T*>(value, context); // another class's object: named as the server names it
    }
    static py::object out(const T* value) { return wrapObject(value); }
};

template <> struct Bridge<const UClass*> {
    using Py = PyArg;
    static const UClass* in(const Py& value, std::string_view context) {
        ClassArg arg;
        if (loadClassArg(value, arg))
            return arg.resolve(context);
        return decodeAsServer<const UClass*>(value, context);
    }
    static py::object out(const UClass* value) { return value ? pythonClassFor(*value) : py::none(); }
};

template <typename T> struct Bridge<TSubclassOf<T>> {
    using Py = PyArg;
    static TSubclassOf<T> in(const Py& value, std::string_view context) {
        ClassArg arg;
        if (!loadClassArg(value, arg))
            return decodeAsServer<TSubclassOf<T>>(value, context);
        const UClass* type = arg.resolve(context);
        SP_CHECK(!type || type->isChildOf(T::StaticClass()), InvalidArgument, context, ": class '",
                 type->name, "' does not derive from ", T::StaticClass().name);
        return TSubclassOf<T>(type);
    }
    static py::object out(const TSubclassOf<T>& value) { return Bridge<const UClass*>::out(value.Get()); }
};

// Containers convert element by element; when an element is refused, the server's decoding of the whole
// value says which one ("AActor.Tags[2] must be a str, got int 3"). unlessRefused runs such a conversion
// (which returns nullopt for a container it does not take) and gives nullopt when an element was refused
// too: InvalidArgument, NotFound or StaleObject, never InvalidState (outside a frame), which is not about the
// value.
template <typename Convert> auto unlessRefused(Convert&& convert) -> decltype(convert()) {
    try {
        return convert();
    } catch (const InvalidArgument&) {
    } catch (const NotFound&) {
    } catch (const StaleObject&) {
    }
    return std::nullopt;
}

template <typename T> struct Bridge<std::vector<T>> {
    using Py = PyArg;
    static std::vector<T> in(const Py& value, std::string_view context) {
        if (PyList_Check(value.ptr()) || PyTuple_Check(value.ptr()))
            if (auto result = unlessRefused([&] {
                    std::vector<T> items;
                    items.reserve(py::len(value));
                    for (py::handle item : value)
                        items.push_back(Bridge<T>::in(py::reinterpret_borrow<PyArg>(item), context));
                    return std::optional(std::move(items));
                }))
                return std::move(*result);
        return decodeAsServer<std::vector<T>>(value, context);
    }
    static py::object out(const std::vector<T>& value) {
        py::list result(value.size());
        for (size_t i = 0; i < value.size(); ++i)
            result[i] = Bridge<T>::out(value[i]);
        return result;
    }
};

template <typename T> struct Bridge<std::map<std::string, T>> {
    using Py = PyArg;
    static std::map<std::string, T> in(const Py& value, std::string_view context) {
        if (PyDict_Check(value.ptr()))
            if (auto result = unlessRefused([&]() -> std::optional<std::map<std::string, T>> {
                    std::map<std::string, T> items;
                    for (auto [key, item] : py::reinterpret_borrow<py::dict>(value)) {
                        if (!PyUnicode_Check(key.ptr()))
                            return std::nullopt;
                        items.emplace(py::cast<std::string>(key),
                                      Bridge<T>::in(py::reinterpret_borrow<PyArg>(item), context));
                    }
                    return items;
                }))
                return std::move(*result);
        return decodeAsServer<std::map<std::string, T>>(value, context);
    }
    static py::object out(const std::map<std::string, T>& value) {
        py::dict result;
        for (const auto& [key, item] : value)
            result[py::str(key)] = Bridge<T>::out(item);
        return result;
    }
};

// Calls: a generated function's entry point (fast_call.h) takes whatever Python passes and sorts keywords
// into its parameters, missingArgument() where one is left out; a call that does not fit is refused here
// (checkCall) with the TypeError Python itself raises for the RPC proxy's signature (same words), and a
// left-out parameter takes its C++ default in the binding, as the registry does for an RPC call.
py::handle missingArgument();
inline bool isMissing(const PyArg& value) {
    return value.ptr() == missingArgument().ptr();
}

// What a generated function binding received: its parameters (missingArgument() where left out), in order,
// and what Python passed beside them.
struct PyCallArgs {
    const py::args& positional;
    const py::kwargs& extra;
    std::span<const PyArg* const> values;
    bool method; // called on an object (Python counts self)
};
// `function` is the context ("AActor.SetActorLocation()").
void checkCall(std::string_view function, const PyCallArgs& args, std::span<const reflect::ParamDesc> params);

// The in-process boundary of a generated call body (see sp::reflect::ValueCall, the registry's): arguments
// arrive as PyArgs and convert through Bridge<T>, results leave as Python objects.
class PyCall {
  public:
    using Args = const PyCallArgs&;
    using Result = py::object;
    using Input = PyArg; // a property setter's value

    PyCall(Args args, std::string_view context, std::span<const reflect::ParamDesc> params)
        : args_(args), params_(params) {
        checkCall(context, args, params);
    }
    bool given(std::size_t index) const { return !isMissing(*args_.values[index]); }
    template <typename T> T arg(std::size_t index) const {
        return Bridge<T>::in(*args_.values[index], params_[index].context);
    }
    // The object a function is called on: resolved only after the call's checks, as over RPC, where the
    // proxy's Python signature refuses a bad call before the server sees the object.
    template <typename T> static T* object(const RefBase& self, std::string_view context) {
        return self.get<T>(context);
    }
    template <typename T> static T input(const PyArg& value, std::string_view context) {
        return Bridge<T>::in(value, context);
    }
    template <typename T, typename V> static py::object result(const V& value) {
        return Bridge<T>::out(value);
    }
    static py::object none() { return py::none(); }
    template <typename... T>
    static py::object outputs(const reflect::ResultTupleDesc& tuple, const reflect::Output<T>&... fields) {
        return resultTuple(tuple)(py::arg(fields.name) = Bridge<T>::out(fields.value)...);
    }

  private:
    // The generated NamedTuple class, looked up once per function.
    static const py::object& resultTuple(const reflect::ResultTupleDesc& tuple);

    const PyCallArgs& args_;
    std::span<const reflect::ParamDesc> params_;
};

// Python's own messages about an object ("'AActor' object has no attribute 'X'") name its type by tp_name,
// which pybind11 sets to "module.Class"; the RPC proxies are Python classes named "Class". The bare name
// makes both transports say the same.
void useBareTypeName(py::handle pythonClass);

// Gives each property of the class its name (property.__set_name__, which a class body would have called),
// so that Python's "property 'RootComponent' of 'AActor' object has no setter" names it as over RPC.
void nameProperties(py::handle pythonClass);

// The dtype of a numpy array; throws InvalidArgument for dtypes that cannot cross (complex, object, ...).
reflect::DType dtypeOf(const py::array& array, std::string_view context);

// numpy <-> ArrayValue without copying: the array keeps the numpy buffer alive and vice versa.
reflect::ArrayValue arrayFromNumpy(const py::array& array, reflect::DType dtype, std::string_view context);
py::array arrayToNumpy(const reflect::ArrayValue& value);

template <typename T> struct Bridge<reflect::SpArray<T>> {
    using Py = PyArg;
    static reflect::SpArray<T> in(const Py& value, std::string_view context) {
        if (!py::isinstance<py::array>(value)) // a list is not converted: over RPC it arrives as a list
            return decodeAsServer<reflect::SpArray<T>>(value, context);
        reflect::SpArray<T> result;
        result.assign(
            arrayFromNumpy(py::reinterpret_borrow<py::array>(value), reflect::DTypeOf<T>::value, context),
            context);
        return result;
    }
    static py::object out(const reflect::SpArray<T>& value) { return arrayToNumpy(value.value()); }
};

// Looks up a class of the generated API module (structs, enums, result tuples); cached by the caller.
py::object apiAttribute(const char* module, const char* name);

// A reflected struct's generated class (a dataclass with __slots__), whose fields are read and written in
// their slots (each field's member descriptor gives its offset in the object), as its attribute access and
// __init__ would, without their name lookups and the call: the struct a typed call returns or takes costs a
// few stores instead of a Python function call (bench/bench_calls.py). A class whose fields are not all plain
// object slots (one changed by hand, or another Python) is used through its attributes and constructor.
class SlotStruct {
  public:
    // The class `name` of `module`, with its fields in declaration order (the constructor's order).
    SlotStruct(const char* module, const char* name, std::initializer_list<const char*> fields);
    // Whether `src` is an instance of the class (or of a subclass); an error isinstance raises propagates,
    // as pybind11's isinstance() does.
    bool holds(py::handle src) const;
    // Field `i` of an instance; AttributeError, as attribute access, when it is unset.
    py::object get(py::handle src, std::size_t i) const;
    // A new instance with the fields `values`, in declaration order.
    template <typename... Values> py::object make(Values&&... values) const {
        if constexpr (sizeof...(Values) == 0) {
            return cls_();
        } else {
            if (offsets_.empty())
                return cls_(std::forward<Values>(values)...);
            py::object fields[] = {asObject(std::forward<Values>(values))...};
            return fill(fields, sizeof...(Values));
        }
    }

  private:
    template <typename V> static py::object asObject(V&& value) {
        if constexpr (std::is_base_of_v<py::handle, std::decay_t<V>>)
            return py::reinterpret_borrow<py::object>(value);
        else
            return py::cast(std::forward<V>(value));
    }
    py::object fill(py::object* fields, std::size_t count) const;
    py::object cls_;
    std::vector<const char*> names_;
    std::vector<Py_ssize_t> offsets_; // of each field's slot; empty: through attributes and the constructor
};

// The member of the enum class `cls` whose value is `value`, found in `members` (the class's
// _value2member_map_, cached by the caller): a dict lookup instead of a call of the class, whose
// EnumMeta.__call__ costs a typed enum read a few hundred nanoseconds. A value the enum lacks is left to the
// call, which raises as it always has.
py::object enumMember(const py::object& cls, const py::object& members, int64_t value);

} // namespace sp::pybind
#pragma GCC visibility pop

namespace pybind11::detail {

template <> struct type_caster<sp::pybind::ClassArg> {
    PYBIND11_TYPE_CASTER(sp::pybind::ClassArg, const_name("type | str"));
    bool load(handle src, bool) { return sp::pybind::loadClassArg(src, value); }
    static handle cast(const sp::pybind::ClassArg&, return_value_policy, handle) { return none().release(); }
};

} // namespace pybind11::detail
