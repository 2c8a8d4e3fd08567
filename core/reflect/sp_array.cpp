#include "core/reflect/sp_array.h"

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

ArrayValue allocateArray(DType dtype, const std::vector<int64_t>& shape) {
    for (int64_t extent : shape)
        SP_CHECK(extent >= 0, InvalidArgument, "allocateArray(): negative extent ", extent);
    if (gAllocator)
        return gAllocator(dtype, shape, gAllocatorContext);
    ArrayValue value;
    value.dtype = dtype;
    value.shape = shape;
    const size_t bytes = value.byteSize();
    auto storage = std::shared_ptr<char[]>(new char[bytes == 0 ? 1 : bytes]());
    value.data = storage.get();
    value.owner = std::move(storage);
    return value;
}

} // namespace sp::reflect
