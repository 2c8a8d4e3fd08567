#pragma once
// SpArray<T>: a named, typed n-dimensional array that crosses the Python boundary as a numpy array
// without copying where it can (in-process it views the numpy buffer; results become numpy arrays that
// own the C++ storage). The API follows the SPEAR paper's Fig. 8: getView(), setDataSource(), getPtr().

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/reflect/value.h"

namespace sp::reflect {

// IEEE half-precision storage (C++20 has no float16 type); arithmetic happens in numpy or GLSL.
struct Half {
    uint16_t bits = 0;
};

template <typename T> struct DTypeOf;
template <> struct DTypeOf<bool> { static constexpr DType value = DType::Bool; };
template <> struct DTypeOf<uint8_t> { static constexpr DType value = DType::UInt8; };
template <> struct DTypeOf<int8_t> { static constexpr DType value = DType::Int8; };
template <> struct DTypeOf<uint16_t> { static constexpr DType value = DType::UInt16; };
template <> struct DTypeOf<int16_t> { static constexpr DType value = DType::Int16; };
template <> struct DTypeOf<uint32_t> { static constexpr DType value = DType::UInt32; };
template <> struct DTypeOf<int32_t> { static constexpr DType value = DType::Int32; };
template <> struct DTypeOf<uint64_t> { static constexpr DType value = DType::UInt64; };
template <> struct DTypeOf<int64_t> { static constexpr DType value = DType::Int64; };
template <> struct DTypeOf<Half> { static constexpr DType value = DType::Float16; };
template <> struct DTypeOf<float> { static constexpr DType value = DType::Float32; };
template <> struct DTypeOf<double> { static constexpr DType value = DType::Float64; };

// What new array storage holds: zeros, or whatever was there, for a caller that writes every byte before
// the array is read (a camera's readback: zeroing 8 MB a 1080p frame only to overwrite it cost a memset and,
// on fresh pages, a page fault per 4 KiB).
enum class ArrayFill { Zeroed, Overwritten };

// Where new array storage comes from. By default the heap; the RPC server installs an allocator for
// the duration of a request that places arrays straight in shared memory, so that a camera's readback
// lands in the segment the client maps, with no copy in between.
using ArrayAllocator = ArrayValue (*)(DType dtype, const std::vector<int64_t>& shape, ArrayFill fill,
                                      void* context);

class ArrayAllocatorScope {
  public:
    ArrayAllocatorScope(ArrayAllocator allocator, void* context);
    ~ArrayAllocatorScope();
    ArrayAllocatorScope(const ArrayAllocatorScope&) = delete;
    ArrayAllocatorScope& operator=(const ArrayAllocatorScope&) = delete;

  private:
    ArrayAllocator previous_;
    void* previousContext_;
};

// Storage for an array of this dtype and shape, from the current allocator.
ArrayValue allocateArray(DType dtype, const std::vector<int64_t>& shape, ArrayFill fill = ArrayFill::Zeroed);
// Storage on the heap, whatever the current allocator (which may fall back to it).
ArrayValue allocateOnHeap(DType dtype, const std::vector<int64_t>& shape, ArrayFill fill = ArrayFill::Zeroed);

// The untyped part, so that lists of arrays of different element types can be packed together.
class SpArrayBase {
  public:
    explicit SpArrayBase(std::string name, DType dtype) : name_(std::move(name)) { value_.dtype = dtype; }
    virtual ~SpArrayBase() = default;

    const std::string& getName() const { return name_; }
    DType getDType() const { return value_.dtype; }
    const std::vector<int64_t>& getShape() const { return value_.shape; }
    int64_t getSize() const { return value_.data ? value_.elementCount() : 0; }
    SpArrayBase* getPtr() { return this; }
    // "(480, 640, 4)"; "None" before the array has data.
    std::string describeShape() const;
    // Throws InvalidArgument "<what> must have shape (*, 3), got (4, 2)" unless the shape matches; -1 in
    // `expected` matches any extent. `what` names the function and array ("APointFilter.Filter(): array
    // 'Points'").
    void checkShape(std::initializer_list<int64_t> expected, std::string_view what) const;

    const ArrayValue& value() const { return value_; }
    // Adopts `value` (sharing its storage). Throws InvalidArgument when the dtype differs.
    void assign(ArrayValue value, std::string_view context) {
        if (value.dtype != value_.dtype) {
            // A parameter's context already names the array; a packed array is named here.
            const std::string what =
                name_.empty() ? std::string(context) : detail::concat(context, ": array '", name_, "'");
            SP_THROW(InvalidArgument, what, " must have dtype ", dtypeName(value_.dtype), ", got ",
                     dtypeName(value.dtype));
        }
        value_ = std::move(value);
    }

  protected:
    std::string name_;
    ArrayValue value_;
};

template <typename T> class SpArray : public SpArrayBase {
  public:
    using ElementType = T;

    explicit SpArray(std::string name = "") : SpArrayBase(std::move(name), DTypeOf<T>::value) {}

    std::span<T> getView() const { return {static_cast<T*>(value_.data), size_t(getSize())}; }
    T* data() const { return static_cast<T*>(value_.data); }

    // Takes ownership of `data`. `shape` may contain one -1, which is inferred; the default is 1-D.
    void setDataSource(std::vector<T> data, std::vector<int64_t> shape = {-1}) {
        auto storage = std::make_shared<std::vector<T>>(std::move(data));
        value_.shape = resolveShape(std::move(shape), int64_t(storage->size()));
        // An empty vector may have no storage at all; a null pointer would read as "no array" (an unset
        // TypedDict field), so an empty array points at a byte that is never read instead.
        static char emptyStorage = 0;
        value_.data = storage->empty() ? static_cast<void*>(&emptyStorage) : storage->data();
        value_.owner = std::move(storage);
    }
    void setDataSource(std::initializer_list<T> data) { setDataSource(std::vector<T>(data)); }

    // Allocates zeroed storage of the given shape (from the current ArrayAllocator).
    void resize(const std::vector<int64_t>& shape) { value_ = allocateArray(DTypeOf<T>::value, shape); }
    // Allocates storage of the given shape that the caller overwrites whole before anyone reads the array
    // (its contents are undefined until then; an array not fully written must not be handed out).
    void resizeForOverwrite(const std::vector<int64_t>& shape) {
        value_ = allocateArray(DTypeOf<T>::value, shape, ArrayFill::Overwritten);
    }

  private:
    std::vector<int64_t> resolveShape(std::vector<int64_t> shape, int64_t count) const {
        int64_t known = 1;
        int wildcard = -1;
        for (size_t i = 0; i < shape.size(); ++i) {
            if (shape[i] == -1) {
                SP_CHECK(wildcard < 0, InvalidArgument, "SpArray::setDataSource(): array '", name_,
                         "' has more than one -1 in its shape");
                wildcard = int(i);
            } else {
                // Checked: a product that wraps around could equal `count` by accident.
                SP_CHECK(shape[i] >= 0 && !__builtin_mul_overflow(known, shape[i], &known), InvalidArgument,
                         "SpArray::setDataSource(): array '", name_, "' has an invalid extent ", shape[i],
                         " in its shape (negative, or too large for ", count, " elements)");
            }
        }
        if (wildcard >= 0) {
            SP_CHECK(known > 0 && count % known == 0, InvalidArgument, "SpArray::setDataSource(): array '",
                     name_, "' has ", count, " elements, which do not fit the shape");
            shape[size_t(wildcard)] = count / known;
            known = count;
        }
        SP_CHECK(known == count, InvalidArgument, "SpArray::setDataSource(): array '", name_, "' has ", count,
                 " elements but its shape holds ", known);
        return shape;
    }
};

} // namespace sp::reflect
