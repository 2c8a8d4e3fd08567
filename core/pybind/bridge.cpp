#include "core/pybind/bridge.h"

#include <structmember.h>

#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

namespace sp::pybind {

reflect::DType dtypeOf(const py::array& array, std::string_view context) {
    const py::dtype dt = array.dtype();
    const char kind = dt.kind();
    const auto size = dt.itemsize();
    using reflect::DType;
    // The byte order is not checked here: arrayFromNumpy() converts a non-native array first.
    if (kind == 'b')
        return DType::Bool;
    if (kind == 'u')
        return size == 1   ? DType::UInt8
               : size == 2 ? DType::UInt16
               : size == 4 ? DType::UInt32
                           : DType::UInt64;
    if (kind == 'i')
        return size == 1 ? DType::Int8 : size == 2 ? DType::Int16 : size == 4 ? DType::Int32 : DType::Int64;
    if (kind == 'f' && size != 16)
        return size == 2 ? DType::Float16 : size == 4 ? DType::Float32 : DType::Float64;
    SP_THROW(InvalidArgument, context, ": unsupported array dtype '", dt.attr("name").cast<std::string>(),
             "'");
}

reflect::ArrayValue arrayFromNumpy(const py::array& array, reflect::DType dtype, std::string_view context) {
    const reflect::DType actual = dtypeOf(array, context);
    SP_CHECK(actual == dtype, InvalidArgument, context, " must have dtype ", reflect::dtypeName(dtype),
             ", got ", reflect::dtypeName(actual));
    // Copied once, so that C++ sees native, C-ordered, writable elements: non-contiguous inputs (slices,
    // transposes), big-endian ones (whose bytes C++ would misread) and read-only ones (an SpFunc may write
    // into its inputs). Over RPC every array is a copy in shared memory anyway.
    py::array contiguous = py::array::ensure(array, py::array::c_style);
    if (contiguous.dtype().byteorder() == '>')
        contiguous = contiguous.attr("astype")(contiguous.dtype().attr("newbyteorder")("="));
    else if (!contiguous.writeable())
        contiguous = contiguous.attr("copy")();
    reflect::ArrayValue value;
    value.dtype = dtype;
    for (py::ssize_t i = 0; i < contiguous.ndim(); ++i)
        value.shape.push_back(contiguous.shape(i));
    // C++ sizes the array from its shape alone: the shape's bytes (checked, never wrapped around) must be
    // the buffer's.
    const size_t bytes = reflect::checkedByteSize(dtype, value.shape, context);
    SP_CHECK(bytes == size_t(contiguous.nbytes()), InvalidArgument, context, ": array of shape ",
             std::string(py::str(contiguous.attr("shape"))), " holds ", contiguous.nbytes(), " bytes, not ",
             bytes);
    value.data = contiguous.mutable_data();
    // The numpy array owns the bytes; release it under the GIL whenever the last C++ user lets go.
    auto* keepAlive = new py::object(std::move(contiguous));
    value.owner = std::shared_ptr<void>(keepAlive, [](void* p) {
        py::gil_scoped_acquire gil;
        delete static_cast<py::object*>(p);
    });
    return value;
}

py::array arrayToNumpy(const reflect::ArrayValue& value) {
    static const char* const kFormats[] = {"?",  "u1", "i1", "u2", "i2", "u4",
                                           "i4", "u8", "i8", "f2", "f4", "f8"};
    // Built once: making a numpy dtype from a string costs more than the rest of this function. Never freed,
    // so that no Python object is released after the interpreter is gone.
    static py::dtype* const kDTypes = [] {
        auto* dtypes = new py::dtype[std::size(kFormats)];
        for (size_t i = 0; i < std::size(kFormats); ++i)
            dtypes[i] = py::dtype(kFormats[i]);
        return dtypes;
    }();
    const py::dtype& dt = kDTypes[size_t(value.dtype)];
    std::vector<py::ssize_t> shape(value.shape.begin(), value.shape.end());
    if (!value.data) // an empty result still has the right dtype
        return py::array(dt, std::vector<py::ssize_t>(shape.empty() ? 1 : shape.size(), 0));
    auto* owner = new std::shared_ptr<void>(value.owner);
    py::capsule capsule(owner, [](void* p) { delete static_cast<std::shared_ptr<void>*>(p); });
    return py::array(dt, shape, value.data, capsule);
}

py::object pythonClassFor(const reflect::TypeInfo& type) {
    if (!type.isDataDefined()) {
        // The API's class (spear.ADefaultPawn), as a class reference over RPC decodes to; the bound class
        // where no API module names it.
        static const py::object* const lookup =
            new py::object(apiAttribute("spear._rpc_types", "api_lookup"));
        py::object found = (*lookup)(type.name);
        return found.is_none() ? pythonClassOf(type) : found;
    }
    // Never released: a static py::object would be, after Python has shut down (a crash at exit).
    static const py::object* const blueprintClass =
        new py::object(apiAttribute("spear._blueprint", "blueprint_class"));
    return (*blueprintClass)(type.name, type.nativeClass().name);
}

py::object apiAttribute(const char* module, const char* name) {
    return py::module_::import(module).attr(name);
}

SlotStruct::SlotStruct(const char* module, const char* name, std::initializer_list<const char*> fields)
    : cls_(apiAttribute(module, name)), names_(fields) {
    if (!PyType_Check(cls_.ptr()))
        return;
    auto* type = reinterpret_cast<PyTypeObject*>(cls_.ptr());
    std::vector<Py_ssize_t> offsets;
    for (const char* field : names_) {
        // The class's own member descriptor for the field: a slot holding any object.
        PyObject* descriptor = PyDict_GetItemString(type->tp_dict, field); // borrowed
        if (!descriptor || !Py_IS_TYPE(descriptor, &PyMemberDescr_Type))
            return;
        const PyMemberDef* member = reinterpret_cast<PyMemberDescrObject*>(descriptor)->d_member;
        if (member->type != T_OBJECT_EX || (member->flags & READONLY))
            return;
        offsets.push_back(member->offset);
    }
    offsets_ = std::move(offsets);
}

bool SlotStruct::holds(py::handle src) const {
    const int result = PyObject_IsInstance(src.ptr(), cls_.ptr());
    if (result < 0)
        throw py::error_already_set();
    return result == 1;
}

py::object SlotStruct::get(py::handle src, std::size_t i) const {
    if (offsets_.empty())
        return src.attr(names_[i]);
    PyObject* value = *reinterpret_cast<PyObject**>(reinterpret_cast<char*>(src.ptr()) + offsets_[i]);
    if (!value) {
        PyErr_Format(PyExc_AttributeError, "'%s' object has no attribute '%s'", Py_TYPE(src.ptr())->tp_name,
                     names_[i]);
        throw py::error_already_set();
    }
    return py::reinterpret_borrow<py::object>(value);
}

py::object SlotStruct::fill(py::object* fields, std::size_t count) const {
    auto* type = reinterpret_cast<PyTypeObject*>(cls_.ptr());
    // Allocated empty (every slot null, as before __init__), then each slot given its field, as __init__'s
    // assignments would.
    auto object = py::reinterpret_steal<py::object>(type->tp_alloc(type, 0));
    if (!object)
        throw py::error_already_set();
    for (std::size_t i = 0; i < count; ++i)
        *reinterpret_cast<PyObject**>(reinterpret_cast<char*>(object.ptr()) + offsets_[i]) =
            fields[i].release().ptr();
    return object;
}

py::object enumMember(const py::object& cls, const py::object& members, int64_t value) {
    const auto key = py::reinterpret_steal<py::object>(PyLong_FromLongLong(value));
    if (!key)
        throw py::error_already_set();
    if (PyObject* member = PyDict_GetItemWithError(members.ptr(), key.ptr())) // borrowed
        return py::reinterpret_borrow<py::object>(member);
    if (PyErr_Occurred())
        throw py::error_already_set();
    return cls(value);
}

const py::object& PyCall::resultTuple(const reflect::ResultTupleDesc& tuple) {
    // Keyed by the body's descriptor (one static per function), used with the GIL held (an import inside
    // apiAttribute may let another thread in, which at worst looks a class up twice). The classes are never
    // released: a py::object freed after Python has shut down would crash at exit.
    static auto* const classes = new std::unordered_map<const reflect::ResultTupleDesc*, const py::object*>();
    const py::object*& found = (*classes)[&tuple];
    if (!found)
        found = new py::object(apiAttribute(tuple.apiModule, tuple.owner).attr(tuple.name));
    return *found;
}

bool loadClassArg(py::handle src, ClassArg& value) {
    if (src.is_none()) {
        value.name.clear();
        value.asset.clear();
        return true;
    }
    if (PyUnicode_Check(src.ptr())) {
        value.name = src.cast<std::string>();
        value.asset.clear();
        return !value.name.empty();
    }
    if (PyType_Check(src.ptr()) && py::hasattr(src, "__sp_class__")) {
        value.name = src.attr("__sp_class__").cast<std::string>();
        value.asset =
            py::hasattr(src, "__sp_asset__") ? src.attr("__sp_asset__").cast<std::string>() : std::string();
        return true;
    }
    return false;
}

void useBareTypeName(py::handle pythonClass) {
    auto* type = reinterpret_cast<PyTypeObject*>(pythonClass.ptr());
    if (const char* dot =
            std::strrchr(type->tp_name, '.')) // the rest of pybind11's string, which it never frees
        type->tp_name = dot + 1;
}

void nameProperties(py::handle pythonClass) {
    const py::dict members = pythonClass.attr("__dict__");
    for (auto [name, member] : members)
        if (PyObject_TypeCheck(member.ptr(), &PyProperty_Type))
            member.attr("__set_name__")(pythonClass, name);
}

py::handle missingArgument() {
    // A private object nobody else can pass; never freed, so it outlives the interpreter's teardown.
    static PyObject* const missing = [] {
        py::gil_scoped_acquire gil;
        return py::object(py::module_::import("builtins").attr("object")()).release().ptr();
    }();
    return missing;
}

namespace {
std::string plural(size_t count, const char* word) {
    return std::to_string(count) + " " + word + (count == 1 ? "" : "s");
}
} // namespace

void checkCall(std::string_view function, const PyCallArgs& args,
               std::span<const reflect::ParamDesc> params) {
    const bool method = args.method;
    const py::args& positional = args.positional;
    const py::kwargs& extra = args.extra;
    // In the order CPython checks a call: unexpected keywords, then positional arguments, then missing ones.
    for (auto item : extra)
        throw py::type_error(std::string(function) + " got an unexpected keyword argument '" +
                             py::str(item.first).cast<std::string>() + "'");
    size_t given = 0;
    std::vector<std::string> missing;
    for (std::size_t i = 0; i < params.size(); ++i) {
        const bool present = !isMissing(*args.values[i]);
        given += present;
        if (params[i].required && !present)
            missing.push_back(std::string("'") + params[i].name + "'");
    }
    if (!positional.empty()) {
        const size_t takes = method ? 1 : 0;
        const size_t count = positional.size() + takes;
        std::string message = std::string(function) + " takes " + std::to_string(takes) +
                              " positional argument" + (takes == 1 ? "" : "s") + " but " +
                              std::to_string(count);
        if (given)
            message += std::string(" positional argument") + (count == 1 ? "" : "s") + " (and " +
                       plural(given, "keyword-only argument") + ")";
        throw py::type_error(message + (count == 1 && !given ? " was given" : " were given"));
    }
    if (missing.empty())
        return;
    std::string names = missing[0];
    for (size_t i = 1; i < missing.size(); ++i)
        names += (missing.size() > 2 ? ", " : " ") + std::string(i + 1 == missing.size() ? "and " : "") +
                 missing[i];
    throw py::type_error(std::string(function) + " missing " +
                         plural(missing.size(), "required keyword-only argument") + ": " + names);
}

} // namespace sp::pybind
