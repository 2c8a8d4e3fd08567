#pragma once
// Value: the type-erased currency of the registry. Dynamic calls (call_function, get/set_property by
// name) and the RPC server pass arguments and results as Values; the registry's invokers convert them
// to and from real C++ types (see codec.h), checking every conversion.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sp::reflect {

// A generation-checked reference to an engine object. Index 0 is the null handle.
struct ObjectHandle {
    uint32_t index = 0;
    uint32_t generation = 0;

    bool isNull() const { return index == 0; }
    friend bool operator==(const ObjectHandle&, const ObjectHandle&) = default;
    friend auto operator<=>(const ObjectHandle&, const ObjectHandle&) = default;
};

std::string toString(ObjectHandle handle);

// A reference to a reflected class by name (UClass* / TSubclassOf<T> across the boundary).
struct ClassName {
    std::string name;
    std::string asset = {}; // a blueprint's asset file, loaded when the class is not registered yet
    friend bool operator==(const ClassName&, const ClassName&) = default;
};

// An entry of a reflected enum, with the enum's name: over both transports an enum argument must be a value
// of that enum (the Python IntEnum), not a bare int, so the value carries which enum it belongs to.
struct EnumValue {
    std::string type;
    int64_t value = 0;
    friend bool operator==(const EnumValue&, const EnumValue&) = default;
};

// Element types of arrays; the names match numpy's.
enum class DType : uint8_t {
    Bool,
    UInt8,
    Int8,
    UInt16,
    Int16,
    UInt32,
    Int32,
    UInt64,
    Int64,
    Float16,
    Float32,
    Float64
};

std::string_view dtypeName(DType dtype);
size_t dtypeSize(DType dtype);
DType dtypeFromName(std::string_view name); // throws InvalidArgument for an unknown name

// The number of elements, and of bytes, of an array of this shape. Throws InvalidArgument naming `context`
// for a negative extent or a size past INT64_MAX: a shape sent by a client, such as
// (1537228672809129302, 3), would otherwise wrap around to a small product and pass any size check.
int64_t checkedElementCount(const std::vector<int64_t>& shape, std::string_view context);
size_t checkedByteSize(DType dtype, const std::vector<int64_t>& shape, std::string_view context);

// A shape as Python writes it, "(2, 3)" or "(4,)"; with negativeIsAny, a negative extent is a pattern's "any
// size" and is written "*".
std::string shapeText(const std::vector<int64_t>& shape, bool negativeIsAny = false);

// How deeply lists and dicts may nest in a Value built from outside (a Python object, a msgpack message).
// Converting them recurses, so an unbounded depth lets a 20 KB message overflow the stack; no engine type
// comes near this.
inline constexpr int kMaxValueDepth = 64;

// A dense, C-ordered n-dimensional array that shares ownership of its bytes.
struct ArrayValue {
    DType dtype = DType::Float64;
    std::vector<int64_t> shape;
    std::shared_ptr<void> owner; // keeps `data` alive
    void* data = nullptr;

    // Both throw InvalidArgument for a shape whose size does not fit (see checkedElementCount).
    int64_t elementCount() const;
    size_t byteSize() const;

    // Equal when dtype, shape and bytes are equal.
    friend bool operator==(const ArrayValue& a, const ArrayValue& b);
};

class Value {
  public:
    using List = std::vector<Value>;
    using Dict = std::map<std::string, Value>;
    using Storage = std::variant<std::monostate, bool, int64_t, double, std::string, ObjectHandle, ClassName,
                                 List, Dict, ArrayValue, EnumValue>;

    Value() = default;
    Value(bool v) : storage_(v) {}
    Value(int64_t v) : storage_(v) {}
    Value(double v) : storage_(v) {}
    Value(std::string v) : storage_(std::move(v)) {}
    Value(const char* v) : storage_(std::string(v)) {}
    Value(ObjectHandle v) : storage_(v) {}
    Value(ClassName v) : storage_(std::move(v)) {}
    Value(List v) : storage_(std::move(v)) {}
    Value(Dict v) : storage_(std::move(v)) {}
    Value(ArrayValue v) : storage_(std::move(v)) {}
    Value(EnumValue v) : storage_(std::move(v)) {}

    bool isNone() const { return std::holds_alternative<std::monostate>(storage_); }
    template <typename T> bool is() const { return std::holds_alternative<T>(storage_); }
    template <typename T> const T& as() const { return std::get<T>(storage_); }
    template <typename T> T& as() { return std::get<T>(storage_); }
    template <typename T> const T* tryAs() const { return std::get_if<T>(&storage_); }

    const Storage& storage() const { return storage_; }

    // The kind of value held, as a Python-flavoured word for error messages: "int", "str", "dict", ...; an
    // enum's value is named by its enum.
    std::string_view kindName() const;
    // A short printable form for error messages (long strings and containers are abbreviated).
    std::string repr() const;

    friend bool operator==(const Value& a, const Value& b);

  private:
    Storage storage_;
};

} // namespace sp::reflect
