#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/base/error.h"
#include "core/reflect/sp_array.h"

using namespace sp::reflect;

namespace {
std::string thrown(const auto& call) {
    try {
        call();
    } catch (const sp::InvalidArgument& e) {
        return e.what();
    }
    return "(nothing thrown)";
}
} // namespace

TEST(ArraySize, CountsAndBytes) {
    EXPECT_EQ(checkedElementCount({2, 3}, "f()"), 6);
    EXPECT_EQ(checkedElementCount({}, "f()"), 1);
    EXPECT_EQ(checkedByteSize(DType::Float64, {2, 3}, "f()"), 48u);
    // Empty whatever the other extents, as in numpy: no product is formed.
    EXPECT_EQ(checkedByteSize(DType::Float64, {INT64_MAX, INT64_MAX, 0}, "f()"), 0u);
}

TEST(ArraySize, ProductsThatWouldWrapAroundAreRefused) {
    // 1537228672809129302 * 3 * 4 bytes is 2^64 + 8: unchecked, this shape "needs" 8 bytes.
    EXPECT_EQ(thrown([] {
                  checkedByteSize(DType::Float32, {1537228672809129302, 3}, "echo()");
              }),
              "echo(): array shape (1537228672809129302, 3) of float32 holds more bytes than fit in 64 bits");
    EXPECT_EQ(thrown([] {
                  checkedElementCount({INT64_MAX, 2}, "f()");
              }),
              "f(): array shape (9223372036854775807, 2) has more elements than fit in 64 bits");
    const ArrayValue value{DType::Float32, {1537228672809129302, 3}, nullptr, nullptr};
    EXPECT_THROW(value.byteSize(), sp::InvalidArgument);
    EXPECT_THROW(allocateArray(DType::Float32, {1537228672809129302, 3}), sp::InvalidArgument);
}

TEST(ArraySize, NegativeExtentsAreRefused) {
    EXPECT_EQ(thrown([] {
                  checkedElementCount({2, -1}, "f()");
              }),
              "f(): array shape (2, -1) has a negative extent -1");
    // Negative extents pair up to a positive product: each is checked, not only the product.
    EXPECT_THROW(checkedElementCount({-2, -3}, "f()"), sp::InvalidArgument);
}

TEST(ArraySize, SetDataSourceChecksItsShape) {
    SpArray<float> array("points");
    // 3 * 6148914691236517206 wraps around to exactly 2, the number of elements given.
    EXPECT_EQ(
        thrown([&] {
            array.setDataSource({1.0f, 2.0f}, {3, 6148914691236517206});
        }),
        "SpArray::setDataSource(): array 'points' has an invalid extent 6148914691236517206 in its shape "
        "(negative, or too large for 2 elements)");
    EXPECT_THROW(array.setDataSource({1.0f, 2.0f}, {-2, -1}), sp::InvalidArgument);
    array.setDataSource({1.0f, 2.0f}, {2, 1});
    EXPECT_EQ(array.getSize(), 2);
}

TEST(ArraySize, AllocatorsAreToldWhetherTheStorageMustBeZeroed) {
    // A camera's readback overwrites its arrays whole: the RPC server's allocator then skips zeroing a
    // reused shared-memory buffer. Plain arrays still come zeroed.
    static std::vector<ArrayFill> asked;
    ArrayAllocator recording = [](DType dtype, const std::vector<int64_t>& shape, ArrayFill fill, void*) {
        asked.push_back(fill);
        return allocateOnHeap(dtype, shape, fill);
    };
    ArrayAllocatorScope scope(recording, nullptr);
    SpArray<float> zeroed, overwritten;
    zeroed.resize({4, 4});
    overwritten.resizeForOverwrite({4, 4});
    ASSERT_EQ(asked.size(), 2u);
    EXPECT_EQ(asked[0], ArrayFill::Zeroed);
    EXPECT_EQ(asked[1], ArrayFill::Overwritten);
    for (float v : zeroed.getView())
        EXPECT_EQ(v, 0.0f);
    EXPECT_EQ(overwritten.getView().size(), 16u);
}
