#include "core/reflect/sp_array.h"

#include "core/base/recycled_blocks.h"

namespace sp::reflect {

namespace {
thread_local ArrayAllocator gAllocator = nullptr;
thread_local void* gAllocatorContext = nullptr;
} // namespace

ArrayAllocatorScope::ArrayAllocatorScope(ArrayAllocator allocator, void* context)
    : previous_(gAllocator), previousContext_(gAllocatorContext) {
    gAllocator = allocator;
    gAllocatorContext = context;
}

ArrayAllocatorScope::~ArrayAllocatorScope() {
    gAllocator = previous_;
    gAllocatorContext = previousContext_;
}

std::string SpArrayBase::describeShape() const {
    return value_.data ? shapeText(value_.shape) : std::string("None");
}

void SpArrayBase::checkShape(std::initializer_list<int64_t> expected, std::string_view what) const {
    bool ok = value_.data && value_.shape.size() == expected.size();
    for (size_t i = 0; ok && i < expected.size(); ++i)
        ok = expected.begin()[i] < 0 || expected.begin()[i] == value_.shape[i];
    SP_CHECK(ok, InvalidArgument, what, " must have shape ", shapeText(std::vector<int64_t>(expected), true),
             ", got ", describeShape());
}

ArrayValue allocateArray(DType dtype, const std::vector<int64_t>& shape, ArrayFill fill) {
    checkedByteSize(dtype, shape, "allocateArray()"); // before any allocator sizes storage from the shape
    if (gAllocator)
        return gAllocator(dtype, shape, fill, gAllocatorContext);
    return allocateOnHeap(dtype, shape, fill);
}

ArrayValue allocateOnHeap(DType dtype, const std::vector<int64_t>& shape, ArrayFill fill) {
    ArrayValue value;
    value.dtype = dtype;
    value.shape = shape;
    const size_t bytes = value.byteSize() == 0 ? 1 : value.byteSize();
    // Storage written whole before it is read (a camera's frame) is recycled when large: see
    // recycled_blocks.h.
    auto storage =
        fill == ArrayFill::Overwritten && bytes >= kMinRecycledBlockBytes
            ? takeRecycledBlock(bytes)
            : std::shared_ptr<char[]>(fill == ArrayFill::Zeroed ? new char[bytes]() : new char[bytes]);
    value.data = storage.get();
    value.owner = std::move(storage);
    return value;
}

} // namespace sp::reflect
