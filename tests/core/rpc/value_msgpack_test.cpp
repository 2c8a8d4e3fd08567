#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/error.h"
#include "core/rpc/value_msgpack.h"

using sp::reflect::Value;

namespace {
// `depth` msgpack fixarrays of one element, each holding the next, around a nil.
std::string nestedArrays(int depth) {
    return std::string(size_t(depth), '\x91') + '\xc0';
}

std::string unpackError(const std::string& bytes, std::string_view context) {
    msgpack::object_handle handle = sp::rpc::unpackBounded(bytes.data(), bytes.size());
    try {
        sp::rpc::unpack(handle.get(), context);
    } catch (const sp::InvalidArgument& e) {
        return e.what();
    }
    return "(nothing thrown)";
}

// An array value (extension 3) around its encoded [dtype, shape, payload].
std::string arrayExtension(const msgpack::sbuffer& body) {
    msgpack::sbuffer out;
    msgpack::packer<msgpack::sbuffer> packer(&out);
    packer.pack_ext(body.size(), sp::rpc::kExtArray);
    packer.pack_ext_body(body.data(), body.size());
    return std::string(out.data(), out.size());
}

// An array value (extension 3) of this dtype and shape whose payload holds `bytes` bytes.
std::string arrayValue(const std::string& dtype, const std::vector<int64_t>& shape, size_t bytes) {
    msgpack::sbuffer body;
    msgpack::packer<msgpack::sbuffer> inner(&body);
    inner.pack_array(3);
    inner.pack(dtype);
    inner.pack(shape);
    inner.pack_bin(uint32_t(bytes));
    inner.pack_bin_body(std::string(bytes, '\0').data(), uint32_t(bytes));
    return arrayExtension(body);
}
} // namespace

TEST(ValueMsgpack, NestingIsBoundedInsteadOfOverflowingTheStack) {
    // 20 KB that used to recurse 20,000 frames deep and crash the server.
    EXPECT_EQ(unpackError(nestedArrays(20000), "echo()"),
              "echo(): a value has lists or dicts nested deeper than 64 levels");
    EXPECT_EQ(unpackError(nestedArrays(sp::reflect::kMaxValueDepth + 1), "f()"),
              "f(): a value has lists or dicts nested deeper than 64 levels");
    const std::string deepest = nestedArrays(sp::reflect::kMaxValueDepth);
    msgpack::object_handle handle = sp::rpc::unpackBounded(deepest.data(), deepest.size());
    EXPECT_TRUE(sp::rpc::unpack(handle.get(), "f()").is<Value::List>());
}

TEST(ValueMsgpack, CountsAreBoundedByTheBytesPresent) {
    // An array32 header announcing 2^32 - 1 elements in a 5-byte message: refused before msgpack-c
    // allocates an object for each.
    EXPECT_THROW(sp::rpc::unpackBounded("\xdd\xff\xff\xff\xff", 5), msgpack::size_overflow);
    EXPECT_THROW(sp::rpc::unpackBounded("\xdf\xff\xff\xff\xff", 5), msgpack::size_overflow);
    // Within the bound, a short message is only truncated.
    EXPECT_THROW(sp::rpc::unpackBounded("\x93\x01\x02", 3), msgpack::insufficient_bytes);
    // The same holds inside an array value's own encoding.
    const std::string body = "\xdd\xff\xff\xff\xff";
    std::string ext = std::string("\xc7\x05\x03") + body;
    msgpack::object_handle handle = sp::rpc::unpackBounded(ext.data(), ext.size());
    EXPECT_THROW(sp::rpc::unpack(handle.get(), "echo()"), msgpack::size_overflow);
}

TEST(ValueMsgpack, ArrayShapesAreCheckedWithoutWrappingAround) {
    // 1537228672809129302 * 3 float32s "need" 8 bytes when the product wraps around.
    EXPECT_EQ(unpackError(arrayValue("float32", {1537228672809129302, 3}, 8), "echo()"),
              "echo(): array shape (1537228672809129302, 3) of float32 holds more bytes than fit in 64 bits");
    EXPECT_EQ(unpackError(arrayValue("float32", {-2, -1}, 8), "echo()"),
              "echo(): array shape (-2, -1) has a negative extent -2");
    const std::string good = arrayValue("float32", {2, 1}, 8);
    msgpack::object_handle handle = sp::rpc::unpackBounded(good.data(), good.size());
    EXPECT_EQ(sp::rpc::unpack(handle.get(), "f()").as<sp::reflect::ArrayValue>().elementCount(), 2);
}

TEST(ValueMsgpack, EnumValuesKeepTheirEnumsName) {
    // Extension 4: the value (i64, little endian), then the enum's name. Clients send enum arguments this
    // way so that the server can tell EComponentMobility.Movable from the int 2.
    std::string body(8, '\0');
    body[0] = 2;
    body += "EComponentMobility";
    msgpack::sbuffer out;
    msgpack::packer<msgpack::sbuffer> packer(&out);
    packer.pack_ext(body.size(), sp::rpc::kExtEnum);
    packer.pack_ext_body(body.data(), body.size());
    msgpack::object_handle handle = sp::rpc::unpackBounded(out.data(), out.size());
    EXPECT_EQ(sp::rpc::unpack(handle.get(), "f()"), Value(sp::reflect::EnumValue{"EComponentMobility", 2}));
    // Without a name (or shorter than the value) it is malformed.
    EXPECT_EQ(unpackError(std::string("\xd7\x04") + std::string(8, '\0'), "f()"),
              "f(): malformed enum value");
    EXPECT_EQ(unpackError(std::string("\xd4\x04\x01"), "f()"), "f(): malformed enum value");
    // Replies carry an enum as its int: the client reads the type from the generated API.
    msgpack::sbuffer reply;
    msgpack::packer<msgpack::sbuffer> replyPacker(&reply);
    sp::rpc::pack(replyPacker, Value(sp::reflect::EnumValue{"EComponentMobility", 2}), nullptr);
    EXPECT_EQ(std::string(reply.data(), reply.size()), std::string("\x02"));
}

namespace {
// An array value (extension 3) whose payload is {"tail": offset, "size": bytes}: its bytes in the frame's
// tail.
std::string tailArrayValue(const std::string& dtype, const std::vector<int64_t>& shape, uint64_t offset,
                           uint64_t bytes) {
    msgpack::sbuffer body;
    msgpack::packer<msgpack::sbuffer> inner(&body);
    inner.pack_array(3);
    inner.pack(dtype);
    inner.pack(shape);
    inner.pack_map(2);
    inner.pack(std::string("tail"));
    inner.pack(offset);
    inner.pack(std::string("size"));
    inner.pack(bytes);
    return arrayExtension(body);
}
} // namespace

TEST(ValueMsgpack, ArraysInARequestsTailAreCopiedFromInsideIt) {
    std::string tail(256, '\0');
    for (size_t i = 0; i < tail.size(); ++i)
        tail[i] = char(i);
    const std::string value = tailArrayValue("uint8", {2, 4}, 64, 8);
    msgpack::object_handle handle = sp::rpc::unpackBounded(value.data(), value.size());
    sp::reflect::ArrayValue array;
    {
        sp::rpc::RequestTailScope scope(tail);
        array = sp::rpc::unpack(handle.get(), "f()").as<sp::reflect::ArrayValue>();
    }
    tail.assign(tail.size(), 'x'); // the message's buffer is reused: the array kept its own copy
    ASSERT_EQ(array.byteSize(), 8u);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(static_cast<const unsigned char*>(array.data)[i], 64 + i);
}

TEST(ValueMsgpack, ATailArrayOutsideItsTailOrWithoutOneIsRefused) {
    const std::string tail(128, '\0');
    const auto refused = [&](const std::string& value, bool withTail) {
        std::optional<sp::rpc::RequestTailScope> scope;
        if (withTail)
            scope.emplace(tail);
        return unpackError(value, "f()");
    };
    EXPECT_EQ(refused(tailArrayValue("uint8", {8}, 0, 8), false),
              "f(): an array in the message's tail, but the message has none");
    EXPECT_EQ(refused(tailArrayValue("uint8", {8}, 124, 8), true),
              "f(): an array of 8 bytes at 124 runs past the message's 128-byte tail");
    EXPECT_EQ(refused(tailArrayValue("uint8", {8}, ~uint64_t(0) - 2, 8), true),
              "f(): an array of 8 bytes at 18446744073709551613 runs past the message's 128-byte tail");
    EXPECT_EQ(refused(tailArrayValue("uint8", {8}, 0, 9), true),
              "f(): array holds 9 bytes, its shape needs 8");
}

TEST(ValueMsgpack, AFramesOwnLengthsMustFitInsideIt) {
    std::string_view message, tail;
    // [message length 3][message "abc"][padding to 64][tail "TAIL"]
    std::string body(4, '\0');
    body[0] = 3;
    body += "abc";
    body.resize(sp::rpc::kTailAlignment, '\0');
    body += "TAIL";
    ASSERT_TRUE(sp::rpc::splitFrame(body, true, message, tail));
    EXPECT_EQ(message, "abc");
    EXPECT_EQ(tail, "TAIL");
    ASSERT_TRUE(sp::rpc::splitFrame("plain", false, message, tail));
    EXPECT_EQ(message, "plain");
    EXPECT_TRUE(tail.empty());
    EXPECT_FALSE(
        sp::rpc::splitFrame(std::string_view("\x03\0", 2), true, message, tail)); // no room for a length
    std::string past = body.substr(0, 8);
    past[0] = 100; // a message longer than the frame
    EXPECT_FALSE(sp::rpc::splitFrame(past, true, message, tail));
    EXPECT_FALSE(sp::rpc::splitFrame(body.substr(0, 10), true, message, tail)); // its padding cut short
}
