#include "core/pybind/value_convert.h"

#include <pybind11/numpy.h>

#include "core/base/error.h"
#include "core/pybind/bridge.h"
#include "core/pybind/object_ref.h"
#include "core/reflect/registry.h"

namespace sp::pybind {

using reflect::Value;

namespace {
// A list, a tuple or any other collections.abc.Sequence but text and bytes: what the generated API takes
// where it asks for a Sequence (a list of objects, typed covariantly), as the RPC client does.
bool isSequence(py::handle object) {
    if (PyList_Check(object.ptr()) || PyTuple_Check(object.ptr()))
        return true;
    if (PyUnicode_Check(object.ptr()) || PyBytes_Check(object.ptr()) || PyByteArray_Check(object.ptr()))
        return false;
    // Never released, like the others here: a static py::object would be, after Python has shut down.
    static const py::object* const sequence =
        new py::object(py::module_::import("collections.abc").attr("Sequence"));
    return py::isinstance(object, *sequence);
}

Value toValueAt(py::handle object, std::string_view context, int depth);

// Lists, tuples, dicts and dataclasses recurse: each level costs a C++ stack frame, and a Python list
// nested 100,000 deep is a few lines of Python, so the depth is bounded (as over RPC: value_msgpack.cpp).
void checkDepth(int depth, std::string_view context) {
    SP_CHECK(depth < reflect::kMaxValueDepth, InvalidArgument, context,
             ": a value has lists or dicts nested deeper than ", reflect::kMaxValueDepth, " levels");
}
} // namespace

reflect::ObjectHandle localHandle(py::handle object, std::string_view context) {
    if (const RefBase* ref = nativeRef(object)) // one of this process's objects: no attribute lookups
        return ref->handle;
    SP_CHECK(!py::hasattr(object, "_sp_client"), InvalidArgument, context, ": ",
             std::string(py::str(object.get_type().attr("__name__"))),
             " belongs to another engine (a different spear.Instance)");
    auto handle = object.attr("_sp_handle").cast<std::pair<uint32_t, uint32_t>>();
    return reflect::ObjectHandle{handle.first, handle.second};
}

reflect::Value toValue(py::handle object, std::string_view context) {
    return toValueAt(object, context, 0);
}

namespace {
Value toValueAt(py::handle object, std::string_view context, int depth) {
    if (object.is_none())
        return Value();
    if (PyBool_Check(object.ptr()))
        return Value(object.cast<bool>());
    if (PyLong_Check(object.ptr())) {
        int overflow = 0;
        const long long number = PyLong_AsLongLongAndOverflow(object.ptr(), &overflow);
        SP_CHECK(overflow == 0, InvalidArgument, context, ": integer ", std::string(py::str(object)),
                 " is too large"); // as the RPC client refuses it: 64 bits at most
        // An IntEnum keeps its enum's name: an enum parameter takes only its own enum (as over RPC). Never
        // freed, like every Python object kept here: none may be released after the interpreter is gone.
        static const py::object* const intEnum = new py::object(py::module_::import("enum").attr("IntEnum"));
        if (!PyLong_CheckExact(object.ptr()) && py::isinstance(object, *intEnum))
            return Value(reflect::EnumValue{py::str(object.get_type().attr("__name__")), int64_t(number)});
        return Value(int64_t(number));
    }
    if (PyFloat_Check(object.ptr()))
        return Value(object.cast<double>());
    if (PyUnicode_Check(object.ptr()))
        return Value(object.cast<std::string>());
    if (py::isinstance<py::array>(object)) {
        py::array array = py::reinterpret_borrow<py::array>(object);
        // Any supported dtype; the check against the expected one happens where the registry knows it.
        return Value(arrayFromNumpy(array, dtypeOf(array, context), context));
    }
    // A numpy scalar (numpy.float32(1.5), numpy.int64(3)) is the Python number it holds, as the RPC client
    // sends it.
    static const py::object* const numpyScalar = new py::object(py::module_::import("numpy").attr("generic"));
    if (py::isinstance(object, *numpyScalar))
        return toValueAt(object.attr("item")(), context, depth);
    // Lists, tuples and dicts before the attribute probes below: a failed lookup raises (and formats) an
    // AttributeError.
    const auto list = [&] {
        checkDepth(depth, context);
        Value::List items;
        for (auto item : object)
            items.push_back(toValueAt(item, context, depth + 1));
        return Value(std::move(items));
    };
    if (PyList_Check(object.ptr()) || PyTuple_Check(object.ptr()))
        return list();
    if (PyDict_Check(object.ptr())) {
        checkDepth(depth, context);
        Value::Dict items;
        for (auto [key, item] : py::reinterpret_borrow<py::dict>(object)) {
            SP_CHECK(PyUnicode_Check(key.ptr()), InvalidArgument, context, ": dict keys must be str");
            items.emplace(key.cast<std::string>(), toValueAt(item, context, depth + 1));
        }
        return Value(std::move(items));
    }
    if (const RefBase* ref = nativeRef(object))
        return Value(ref->handle);
    if (py::hasattr(object, "_sp_handle"))
        return Value(localHandle(object, context));
    if (PyType_Check(object.ptr()) && py::hasattr(object, "__sp_class__"))
        return Value(reflect::ClassName{object.attr("__sp_class__").cast<std::string>(),
                                        py::hasattr(object, "__sp_asset__")
                                            ? object.attr("__sp_asset__").cast<std::string>()
                                            : std::string()});
    if (py::hasattr(object, "__dataclass_fields__") && py::hasattr(object, "__sp_class__")) {
        checkDepth(depth, context);
        // Never released, like the others here: a static py::object would be, after Python has shut down.
        static const py::object* const dataclassFields =
            new py::object(py::module_::import("dataclasses").attr("fields"));
        Value::Dict fields;
        for (auto field : (*dataclassFields)(object)) { // excludes the ClassVar __sp_class__
            py::object name = field.attr("name");
            fields.emplace(name.cast<std::string>(), toValueAt(object.attr(name), context, depth + 1));
        }
        return Value(std::move(fields));
    }
    if (isSequence(object)) // any other sequence (collections.abc.Sequence)
        return list();
    SP_THROW(InvalidArgument, context, ": cannot pass a value of type '",
             std::string(py::str(object.get_type().attr("__name__"))), "'");
}

// Untyped fallback, for values whose declared type is not recorded (a struct field the registry does not
// know).
py::object generic(const Value& value, const char* apiModule) {
    return std::visit(
        [&](const auto& v) -> py::object {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>)
                return py::none();
            else if constexpr (std::is_same_v<T, reflect::ObjectHandle>)
                return wrapObject(reflect::ObjectTable::find(v));
            else if constexpr (std::is_same_v<T, reflect::ClassName>)
                return pythonClassFor(reflect::Registry::get().getClass(v.name, "fromValue()"));
            else if constexpr (std::is_same_v<T, reflect::ArrayValue>)
                return arrayToNumpy(v);
            else if constexpr (std::is_same_v<T, reflect::EnumValue>)
                return apiAttribute(apiModule, v.type.c_str())(v.value);
            else if constexpr (std::is_same_v<T, Value::List>) {
                py::list list;
                for (const auto& item : v)
                    list.append(generic(item, apiModule));
                return list;
            } else if constexpr (std::is_same_v<T, Value::Dict>) {
                py::dict dict;
                for (const auto& [key, item] : v)
                    dict[py::str(key)] = generic(item, apiModule);
                return dict;
            } else
                return py::cast(v);
        },
        value.storage());
}
} // namespace

py::object fromValue(const Value& value, const reflect::TypeCode* type, const char* apiModule) {
    if (value.isNone())
        return py::none();
    if (const auto* handle = value.tryAs<reflect::ObjectHandle>())
        return wrapObject(reflect::ObjectTable::find(*handle));
    const bool container = type && type->isContainer();
    if (const auto* list = value.tryAs<Value::List>(); list && container) {
        py::list result;
        for (const auto& item : *list)
            result.append(fromValue(item, &type->elementType(), apiModule));
        return result;
    }
    if (const auto* dict = value.tryAs<Value::Dict>(); dict && container) {
        py::dict result;
        for (const auto& [key, item] : *dict)
            result[py::str(key)] = fromValue(item, &type->elementType(), apiModule);
        return result;
    }
    if (const auto* fields = value.tryAs<Value::Dict>();
        fields && type && type->kind == reflect::TypeCode::Kind::Struct) {
        const reflect::TypeInfo& info = reflect::Registry::get().getStruct(type->name, "fromValue()");
        py::dict kwargs;
        for (const auto& [key, item] : *fields) {
            const reflect::PropertyInfo* property = info.findProperty(key);
            kwargs[py::str(key)] = fromValue(item, property ? &property->type : nullptr, apiModule);
        }
        return apiAttribute(apiModule, info.name.c_str())(**kwargs);
    }
    return generic(value, apiModule);
}

} // namespace sp::pybind
