#include "core/reflect/value.h"

#include <algorithm>
#include <array>
#include <sstream>

#include "core/base/error.h"
#include "core/reflect/registry.h"
#include "core/reflect/type_info.h"

namespace sp::reflect {

namespace {
struct DTypeDesc {
    DType dtype;
    std::string_view name;
    size_t size;
};
constexpr std::array<DTypeDesc, 12> kDTypes{{{DType::Bool, "bool", 1},
                                             {DType::UInt8, "uint8", 1},
                                             {DType::Int8, "int8", 1},
                                             {DType::UInt16, "uint16", 2},
                                             {DType::Int16, "int16", 2},
                                             {DType::UInt32, "uint32", 4},
                                             {DType::Int32, "int32", 4},
                                             {DType::UInt64, "uint64", 8},
                                             {DType::Int64, "int64", 8},
                                             {DType::Float16, "float16", 2},
                                             {DType::Float32, "float32", 4},
                                             {DType::Float64, "float64", 8}}};
} // namespace

std::string toString(ObjectHandle handle) {
    return std::to_string(handle.index) + ":" + std::to_string(handle.generation);
}

std::string_view dtypeName(DType dtype) {
    return kDTypes[size_t(dtype)].name;
}
size_t dtypeSize(DType dtype) {
    return kDTypes[size_t(dtype)].size;
}

DType dtypeFromName(std::string_view name) {
    for (const auto& desc : kDTypes)
        if (desc.name == name)
            return desc.dtype;
    SP_THROW(InvalidArgument, "dtypeFromName(): unsupported dtype '", name, "'");
}

std::string shapeText(const std::vector<int64_t>& shape, bool negativeIsAny) {
    std::string text = "(";
    for (size_t i = 0; i < shape.size(); ++i)
        text +=
            (i ? ", " : "") + (negativeIsAny && shape[i] < 0 ? std::string("*") : std::to_string(shape[i]));
    return text + (shape.size() == 1 ? ",)" : ")");
}

int64_t checkedElementCount(const std::vector<int64_t>& shape, std::string_view context) {
    for (int64_t extent : shape)
        SP_CHECK(extent >= 0, InvalidArgument, context, ": array shape ", shapeText(shape),
                 " has a negative extent ", extent);
    // A zero extent makes the array empty whatever the others are (as in numpy).
    if (std::find(shape.begin(), shape.end(), int64_t(0)) != shape.end())
        return 0;
    int64_t count = 1;
    for (int64_t extent : shape)
        SP_CHECK(!__builtin_mul_overflow(count, extent, &count), InvalidArgument, context, ": array shape ",
                 shapeText(shape), " has more elements than fit in 64 bits");
    return count;
}

size_t checkedByteSize(DType dtype, const std::vector<int64_t>& shape, std::string_view context) {
    int64_t bytes = 0;
    SP_CHECK(!__builtin_mul_overflow(checkedElementCount(shape, context), int64_t(dtypeSize(dtype)), &bytes),
             InvalidArgument, context, ": array shape ", shapeText(shape), " of ", dtypeName(dtype),
             " holds more bytes than fit in 64 bits");
    return size_t(bytes);
}

int64_t ArrayValue::elementCount() const {
    return checkedElementCount(shape, "ArrayValue::elementCount()");
}

size_t ArrayValue::byteSize() const {
    return checkedByteSize(dtype, shape, "ArrayValue::byteSize()");
}

std::string_view Value::kindName() const {
    if (const EnumValue* entry = tryAs<EnumValue>())
        return entry->type;
    static constexpr std::array<std::string_view, std::variant_size_v<Storage>> names{
        "None", "bool", "int", "float", "str", "object", "class", "list", "dict", "ndarray", "enum"};
    return names[storage_.index()];
}

std::string Value::repr() const {
    std::ostringstream out;
    std::visit(
        [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>)
                out << "None";
            else if constexpr (std::is_same_v<T, bool>)
                out << (v ? "True" : "False");
            else if constexpr (std::is_same_v<T, int64_t> || std::is_same_v<T, double>)
                out << v;
            else if constexpr (std::is_same_v<T, std::string>)
                out << "'" << (v.size() > 40 ? v.substr(0, 40) + "..." : v) << "'";
            else if constexpr (std::is_same_v<T, ObjectHandle>)
                out << "<object " << toString(v) << ">";
            else if constexpr (std::is_same_v<T, ClassName>)
                out << "<class '" << v.name << "'>";
            else if constexpr (std::is_same_v<T, List>)
                out << "[... " << v.size() << " items]";
            else if constexpr (std::is_same_v<T, Dict>) {
                out << "{";
                bool first = true;
                for (const auto& [key, item] : v) {
                    out << (first ? "" : ", ") << "'" << key << "': " << item.repr();
                    first = false;
                }
                out << "}";
            } else if constexpr (std::is_same_v<T, EnumValue>) {
                const EnumInfo* info = Registry::get().findEnum(v.type);
                const std::string_view entry = info ? info->nameOf(v.value) : std::string_view();
                if (entry.empty())
                    out << v.type << "(" << v.value << ")";
                else
                    out << v.type << "." << entry;
            } else if constexpr (std::is_same_v<T, ArrayValue>) {
                out << "<ndarray " << dtypeName(v.dtype) << " (";
                for (size_t i = 0; i < v.shape.size(); ++i)
                    out << (i ? ", " : "") << v.shape[i];
                out << ")>";
            }
        },
        storage_);
    return out.str();
}

bool operator==(const ArrayValue& a, const ArrayValue& b) {
    if (a.dtype != b.dtype || a.shape != b.shape)
        return false;
    const auto* x = static_cast<const char*>(a.data);
    return std::equal(x, x + a.byteSize(), static_cast<const char*>(b.data));
}

bool operator==(const Value& a, const Value& b) {
    return a.storage_ == b.storage_;
}

} // namespace sp::reflect
