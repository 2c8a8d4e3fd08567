#include "core/pybind/bridge.h"

#include <cstring>

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
    if (!type.isDataDefined())
        return pythonClassOf(type);
    static const py::object blueprintClass = apiAttribute("spear._blueprint", "blueprint_class");
    return blueprintClass(type.name, type.nativeClass().name);
}

py::object apiAttribute(const char* module, const char* name) {
    return py::module_::import(module).attr(name);
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

} // namespace sp::pybind
