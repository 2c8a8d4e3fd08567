#include "core/pybind/object_ref.h"

#include <unordered_map>

namespace sp::pybind {

namespace {
AccessCheck gAccessCheck = nullptr;
// The root of the generated classes (UObject's), borrowed like every class here.
PyTypeObject* gRootClass = nullptr;

struct Wrapper {
    WrapFn wrap;
    py::handle pythonClass; // borrowed: pybind11 classes live as long as their module
};

std::unordered_map<const reflect::TypeInfo*, Wrapper>& wrappers() {
    static std::unordered_map<const reflect::TypeInfo*, Wrapper> table;
    return table;
}

const Wrapper* findWrapper(const reflect::TypeInfo& type) {
    for (const reflect::TypeInfo* t = &type; t; t = t->parent)
        if (auto it = wrappers().find(t); it != wrappers().end())
            return &it->second;
    return nullptr;
}
} // namespace

void setAccessCheck(AccessCheck check) {
    gAccessCheck = check;
}

void checkAccess(reflect::ObjectBase& object, std::string_view context) {
    if (gAccessCheck)
        gAccessCheck(object, context);
}

void registerWrapper(const reflect::TypeInfo& type, WrapFn wrap, py::handle pythonClass) {
    wrappers()[&type] = Wrapper{wrap, pythonClass};
    if (!type.parent)
        gRootClass = reinterpret_cast<PyTypeObject*>(pythonClass.ptr());
}

const RefBase& selfRef(PyObject* self) {
    auto* instance = reinterpret_cast<py::detail::instance*>(self);
    // Simple layout (one bound C++ base, as every generated class has): the value pointer is stored inline.
    void* value = instance->simple_layout ? instance->simple_value_holder[0]
                                          : py::detail::values_and_holders(instance).begin()->value_ptr();
    if (!value)
        throw py::type_error(std::string("'") + Py_TYPE(self)->tp_name +
                             "' object was never initialised: a subclass's __init__ must call its base's");
    // Every Ref<C> is a RefBase with no data of its own (the generated bindings assert it), so the value's
    // address is its RefBase's.
    return *static_cast<const RefBase*>(value);
}

const RefBase* nativeRef(py::handle object) {
    if (!gRootClass || !PyObject_TypeCheck(object.ptr(), gRootClass))
        return nullptr;
    return &selfRef(object.ptr());
}

py::object wrapObject(const reflect::ObjectBase* object) {
    if (!object)
        return py::none();
    const Wrapper* wrapper = findWrapper(object->GetClass());
    if (!wrapper)
        throw py::type_error("spear: no Python class is registered for '" + object->GetClass().name + "'");
    return wrapper->wrap(object->GetHandle());
}

std::string describeHandle(reflect::ObjectHandle handle, const char* pythonClass) {
    const reflect::ObjectBase* object = reflect::ObjectTable::find(handle);
    if (!object)
        return std::string("<") + pythonClass + " (destroyed) " + reflect::toString(handle) + ">";
    return "<" + object->GetDebugName() + " " + reflect::toString(handle) + ">";
}

py::object pythonClassOf(const reflect::TypeInfo& type) {
    const Wrapper* wrapper = findWrapper(type);
    if (!wrapper)
        throw py::type_error("spear: no Python class is registered for '" + type.name + "'");
    return py::reinterpret_borrow<py::object>(wrapper->pythonClass);
}

} // namespace sp::pybind
