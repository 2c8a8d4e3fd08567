#include "core/pybind/dynamic_access.h"

#include <pybind11/stl.h>

#include "core/base/error.h"
#include "core/pybind/object_ref.h"
#include "core/pybind/value_convert.h"
#include "core/reflect/property_path.h"
#include "core/reflect/registry.h"

namespace sp::pybind {

namespace py = ::pybind11;
using reflect::Value;

reflect::ObjectBase& resolveHandle(py::handle object, std::string_view context) {
    if (const RefBase* ref = nativeRef(object))
        return reflect::ObjectTable::resolve(ref->handle, context);
    SP_CHECK(py::hasattr(object, "_sp_handle"), InvalidArgument, context,
             ": expected an engine object, got '", std::string(py::str(object.get_type().attr("__name__"))),
             "'");
    return reflect::ObjectTable::resolve(localHandle(object, context), context);
}

reflect::ObjectBase& resolveArgument(py::handle object, std::string_view context) {
    reflect::ObjectBase& resolved = resolveHandle(object, context);
    checkAccess(resolved, context);
    return resolved;
}

namespace {} // namespace

void bindDynamicAccess(py::module_& m, const char* apiModule) {
    m.def(
        "call_function",
        [apiModule](py::handle uobject, const std::string& function, py::dict args) -> py::object {
            const std::string context = "call_function('" + function + "')";
            reflect::ObjectBase& object = resolveArgument(uobject, context);
            const reflect::TypeInfo& type = object.GetObjectClass(); // a blueprint's functions too
            const reflect::FunctionInfo* info = type.findFunction(function);
            SP_CHECK(info, NotFound, context, ": class '", type.name, "' has no function '", function, "'");
            // Converted as one dict, so that arguments nest as deep as over RPC, where `args` is one value.
            Value converted = toValue(args, context);
            reflect::CallArgs& callArgs = converted.as<Value::Dict>();
            Value result = info->invoke(&object, callArgs);
            bool hasOut = false;
            for (const auto& param : info->params)
                hasOut = hasOut || param.isOut;
            if (!hasOut)
                return fromValue(result, &info->returnType, apiModule);
            py::dict outputs;
            for (const auto& [key, item] : result.as<Value::Dict>()) {
                const reflect::TypeCode* itemType = key == "ReturnValue" ? &info->returnType : nullptr;
                for (const auto& param : info->params)
                    if (param.name == key)
                        itemType = &param.type;
                outputs[py::str(key)] = fromValue(item, itemType, apiModule);
            }
            return outputs;
        },
        py::kw_only(), py::arg("uobject"), py::arg("function"), py::arg("args") = py::dict(),
        "Calls a reflected function by name; out-parameters come back in a dict beside 'ReturnValue'.");

    m.def(
        "get_property",
        [apiModule](py::handle uobject, const std::string& path) -> py::object {
            const std::string context = "get_property('" + path + "')";
            reflect::ObjectBase& object = resolveArgument(uobject, context);
            const reflect::PathValue found = reflect::getPath(object, path, context);
            return fromValue(found.value, &found.type, apiModule);
        },
        py::kw_only(), py::arg("uobject"), py::arg("path"),
        "Reads a reflected property by name or path (core/reflect/property_path.h: "
        "'RootComponent.RelativeLocation.Z', 'Tags[1]').");

    m.def(
        "set_property",
        [](py::handle uobject, const std::string& path, py::handle value) {
            const std::string context = "set_property('" + path + "')";
            reflect::ObjectBase& object = resolveArgument(uobject, context);
            reflect::setPath(object, path, toValue(value, context), context);
        },
        py::kw_only(), py::arg("uobject"), py::arg("path"), py::arg("value"),
        "Writes a reflected property by name or path (core/reflect/property_path.h).");

    m.def(
        "get_class_names",
        [] {
            std::vector<std::string> names;
            for (const reflect::TypeInfo* type : reflect::Registry::get().types())
                names.push_back(type->name);
            return names;
        },
        "Names of every registered class and struct, sorted.");

    m.def(
        "get_derived_class_names",
        [](const std::string& uclass) {
            const reflect::TypeInfo& base =
                reflect::Registry::get().getClass(uclass, "get_derived_class_names()");
            std::vector<std::string> names;
            for (const reflect::TypeInfo* type : reflect::Registry::get().derivedClasses(base))
                names.push_back(type->name);
            return names;
        },
        py::kw_only(), py::arg("uclass"), "Names of uclass and every class derived from it, sorted.");
}

} // namespace sp::pybind
