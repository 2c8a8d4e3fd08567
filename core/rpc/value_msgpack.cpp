#include "core/rpc/value_msgpack.h"

#include <cstdint>
#include <cstring>
#include <memory>

#include "core/base/error.h"
#include "core/reflect/object_base.h"
#include "core/reflect/registry.h"
#include "core/reflect/type_info.h"
#include "core/rpc/shared_memory.h"

namespace sp::rpc {

using reflect::Value;

namespace {
thread_local OpenedSegments* gOpened = nullptr;
thread_local long gSegmentOwner = -1;
thread_local const std::string_view* gRequestTail = nullptr;
} // namespace

RequestTailScope::RequestTailScope(std::string_view tail) : tail_(tail), previous_(gRequestTail) {
    gRequestTail = &tail_;
}

RequestTailScope::~RequestTailScope() {
    gRequestTail = previous_;
}

const std::string_view* RequestTailScope::current() {
    return gRequestTail;
}

bool splitFrame(std::string_view body, bool tailed, std::string_view& message, std::string_view& tail) {
    if (!tailed) {
        message = body;
        tail = {};
        return true;
    }
    uint32_t length = 0;
    if (body.size() < 4)
        return false;
    std::memcpy(&length, body.data(), 4);
    if (size_t(length) > body.size() - 4)
        return false;
    const size_t tailStart = (4 + size_t(length) + kTailAlignment - 1) / kTailAlignment * kTailAlignment;
    if (tailStart > body.size())
        return false;
    message = body.substr(4, length);
    tail = body.substr(tailStart);
    return true;
}

SegmentOwnerScope::SegmentOwnerScope(long pid) : previous_(gSegmentOwner) {
    gSegmentOwner = pid;
}

SegmentOwnerScope::~SegmentOwnerScope() {
    gSegmentOwner = previous_;
}

long SegmentOwnerScope::current() {
    return gSegmentOwner;
}

OpenedSegmentsScope::OpenedSegmentsScope(OpenedSegments& list) : previous_(gOpened) {
    gOpened = &list;
}

OpenedSegmentsScope::~OpenedSegmentsScope() {
    gOpened = previous_;
}

OpenedSegments* OpenedSegmentsScope::current() {
    return gOpened;
}

namespace {
// Always a msgpack float 64. msgpack-c's pack_double() writes a whole-number double as an integer, so a
// coordinate of 1.0 would reach Python as the int 1 (and -0.0 as 0): the bytes are written here instead.
void packFloat64(msgpack::packer<msgpack::sbuffer>& out, double value) {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    char bytes[9] = {char(0xcb)};
    for (int i = 0; i < 8; ++i)
        bytes[1 + i] = char(bits >> (56 - 8 * i)); // big-endian, as msgpack stores numbers
    out.pack_bin_body(bytes, sizeof bytes);        // appends the bytes as they are (no bin header)
}

void packExt(msgpack::packer<msgpack::sbuffer>& out, ExtType type, const std::string& body) {
    out.pack_ext(body.size(), type);
    out.pack_ext_body(body.data(), body.size());
}

void packArray(msgpack::packer<msgpack::sbuffer>& out, const reflect::ArrayValue& array,
               const ArrayToSharedMemory& toShm) {
    msgpack::sbuffer body;
    msgpack::packer<msgpack::sbuffer> inner(&body);
    inner.pack_array(3);
    inner.pack(std::string(reflect::dtypeName(array.dtype)));
    inner.pack(array.shape);
    const size_t bytes = array.data ? array.byteSize() : 0;
    if (bytes >= kSharedMemoryThreshold && toShm) {
        const SharedArray shared = toShm(array);
        inner.pack_map(2);
        if (shared.tail) {
            inner.pack(std::string("tail"));
            inner.pack(*shared.tail);
        } else {
            inner.pack(std::string(shared.clientBuffer ? "buffer" : "shm"));
            inner.pack(shared.name);
        }
        inner.pack(std::string("size"));
        inner.pack(uint64_t(bytes));
    } else {
        inner.pack_bin(uint32_t(bytes));
        inner.pack_bin_body(static_cast<const char*>(array.data), uint32_t(bytes));
    }
    packExt(out, kExtArray, std::string(body.data(), body.size()));
}

reflect::ArrayValue unpackArray(const msgpack::object& body, std::string_view context) {
    msgpack::object_handle handle = unpackBounded(body.via.ext.data(), body.via.ext.size);
    const msgpack::object& parts = handle.get();
    SP_CHECK(parts.type == msgpack::type::ARRAY && parts.via.array.size == 3, InvalidArgument, context,
             ": malformed array value");
    reflect::ArrayValue array;
    array.dtype = reflect::dtypeFromName(parts.via.array.ptr[0].as<std::string>());
    array.shape = parts.via.array.ptr[1].as<std::vector<int64_t>>();
    const size_t expected = reflect::checkedByteSize(array.dtype, array.shape, context);
    const msgpack::object& payload = parts.via.array.ptr[2];
    if (payload.type == msgpack::type::BIN) {
        SP_CHECK(payload.via.bin.size == expected, InvalidArgument, context, ": array holds ",
                 payload.via.bin.size, " bytes, its shape needs ", expected);
        auto storage = std::shared_ptr<char[]>(new char[expected == 0 ? 1 : expected]);
        std::memcpy(storage.get(), payload.via.bin.ptr, expected);
        array.data = storage.get();
        array.owner = storage;
        return array;
    }
    SP_CHECK(payload.type == msgpack::type::MAP, InvalidArgument, context, ": malformed array payload");
    std::string name;
    uint64_t size = 0;
    std::optional<uint64_t> tailOffset;
    for (uint32_t i = 0; i < payload.via.map.size; ++i) {
        const auto key = payload.via.map.ptr[i].key.as<std::string>();
        if (key == "shm")
            name = payload.via.map.ptr[i].val.as<std::string>();
        else if (key == "size")
            size = payload.via.map.ptr[i].val.as<uint64_t>();
        else if (key == "tail")
            tailOffset = payload.via.map.ptr[i].val.as<uint64_t>();
    }
    if (tailOffset) {
        // Bytes after the message (kTailFlag), copied out: the message's buffer is gone once it is handled.
        const std::string_view* tail = RequestTailScope::current();
        SP_CHECK(tail, InvalidArgument, context,
                 ": an array in the message's tail, but the message has none");
        SP_CHECK(size == expected, InvalidArgument, context, ": array holds ", size,
                 " bytes, its shape needs ", expected);
        SP_CHECK(*tailOffset <= tail->size() && size <= tail->size() - *tailOffset, InvalidArgument, context,
                 ": an array of ", size, " bytes at ", *tailOffset, " runs past the message's ", tail->size(),
                 "-byte tail");
        auto storage = std::shared_ptr<char[]>(new char[expected == 0 ? 1 : expected]);
        std::memcpy(storage.get(), tail->data() + *tailOffset, expected);
        array.data = storage.get();
        array.owner = storage;
        return array;
    }
    SP_CHECK(size == expected, InvalidArgument, context, ": shared-memory array holds ", size,
             " bytes, its shape needs ", expected);
    const long owner = SegmentOwnerScope::current();
    SP_CHECK(owner > 0, InvalidArgument, context,
             ": shared-memory arrays are taken only over a Unix socket, from the client's own segments; send "
             "the array in the message");
    const std::string prefix = "/spear-" + std::to_string(owner) + "-";
    SP_CHECK(name.starts_with(prefix), InvalidArgument, context, ": shared-memory array '", name,
             "' is not a segment of the connected client (pid ", owner, ")");
    // open() compares `size` with the segment's real size (fstat): the client's word is not enough, since
    // touching a page past the end of a shrunk segment is a SIGBUS.
    std::shared_ptr<SharedMemorySegment> segment;
    try {
        segment = std::make_shared<SharedMemorySegment>(SharedMemorySegment::open(name, size));
    } catch (const InvalidArgument& e) {
        SP_THROW(InvalidArgument, context, ": shared-memory array: ", e.what());
    }
    if (OpenedSegments* opened = OpenedSegmentsScope::current())
        opened->push_back({name, segment, 0});
    array.data = segment->data();
    array.owner = segment;
    return array;
}
} // namespace

void pack(msgpack::packer<msgpack::sbuffer>& out, const Value& value, const ArrayToSharedMemory& toShm) {
    std::visit(
        [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>) {
                out.pack_nil();
            } else if constexpr (std::is_same_v<T, double>) {
                packFloat64(out, v);
            } else if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, int64_t> ||
                                 std::is_same_v<T, std::string>) {
                out.pack(v);
            } else if constexpr (std::is_same_v<T, reflect::ObjectHandle>) {
                std::string body(8, '\0');
                std::memcpy(body.data(), &v.index, 4);
                std::memcpy(body.data() + 4, &v.generation, 4);
                if (const reflect::ObjectBase* object = reflect::ObjectTable::find(v))
                    body += object->GetClass().name;
                packExt(out, kExtObject, body);
            } else if constexpr (std::is_same_v<T, reflect::ClassName>) {
                // A blueprint's class travels with its native class ("BP_Axes\0AActor"), which the client
                // needs to give it a Python class.
                const reflect::TypeInfo* type = reflect::Registry::get().findType(v.name);
                packExt(out, kExtClass,
                        type && type->isDataDefined() ? v.name + '\0' + type->nativeClass().name : v.name);
            } else if constexpr (std::is_same_v<T, reflect::EnumValue>) {
                out.pack(v.value);
            } else if constexpr (std::is_same_v<T, Value::List>) {
                out.pack_array(uint32_t(v.size()));
                for (const auto& item : v)
                    pack(out, item, toShm);
            } else if constexpr (std::is_same_v<T, Value::Dict>) {
                out.pack_map(uint32_t(v.size()));
                for (const auto& [key, item] : v) {
                    out.pack(key);
                    pack(out, item, toShm);
                }
            } else if constexpr (std::is_same_v<T, reflect::ArrayValue>) {
                packArray(out, v, toShm);
            }
        },
        value.storage());
}

msgpack::object_handle unpackBounded(const char* data, size_t size) {
    const msgpack::unpack_limit limit(size, size / 2, size, size, size);
    return msgpack::unpack(data, size, nullptr, nullptr, limit);
}

namespace {
Value unpackAt(const msgpack::object& in, std::string_view context, int depth);

// Lists and dicts recurse: each level costs a C++ stack frame, so the depth is bounded.
void checkDepth(int depth, std::string_view context) {
    SP_CHECK(depth < reflect::kMaxValueDepth, InvalidArgument, context,
             ": a value has lists or dicts nested deeper than ", reflect::kMaxValueDepth, " levels");
}
} // namespace

Value unpack(const msgpack::object& in, std::string_view context) {
    return unpackAt(in, context, 0);
}

namespace {
Value unpackAt(const msgpack::object& in, std::string_view context, int depth) {
    switch (in.type) {
    case msgpack::type::NIL:
        return Value();
    case msgpack::type::BOOLEAN:
        return Value(in.via.boolean);
    case msgpack::type::POSITIVE_INTEGER:
        SP_CHECK(in.via.u64 <= uint64_t(INT64_MAX), InvalidArgument, context, ": integer ", in.via.u64,
                 " is too large");
        return Value(int64_t(in.via.u64));
    case msgpack::type::NEGATIVE_INTEGER:
        return Value(int64_t(in.via.i64));
    case msgpack::type::FLOAT32:
    case msgpack::type::FLOAT64:
        return Value(in.via.f64);
    case msgpack::type::STR:
        return Value(std::string(in.via.str.ptr, in.via.str.size));
    case msgpack::type::ARRAY: {
        checkDepth(depth, context);
        Value::List items;
        items.reserve(in.via.array.size);
        for (uint32_t i = 0; i < in.via.array.size; ++i)
            items.push_back(unpackAt(in.via.array.ptr[i], context, depth + 1));
        return Value(std::move(items));
    }
    case msgpack::type::MAP: {
        checkDepth(depth, context);
        Value::Dict items;
        for (uint32_t i = 0; i < in.via.map.size; ++i) {
            const auto& kv = in.via.map.ptr[i];
            SP_CHECK(kv.key.type == msgpack::type::STR, InvalidArgument, context,
                     ": map keys must be strings");
            items.emplace(std::string(kv.key.via.str.ptr, kv.key.via.str.size),
                          unpackAt(kv.val, context, depth + 1));
        }
        return Value(std::move(items));
    }
    case msgpack::type::EXT: {
        const auto type = in.via.ext.type();
        const char* data = in.via.ext.data();
        const uint32_t size = in.via.ext.size;
        if (type == kExtObject) {
            SP_CHECK(size >= 8, InvalidArgument, context, ": malformed object reference");
            reflect::ObjectHandle handle;
            std::memcpy(&handle.index, data, 4);
            std::memcpy(&handle.generation, data + 4, 4);
            return Value(handle);
        }
        if (type == kExtClass) { // "name", "name\0native" (server to client) or "name\0\0asset" (a blueprint)
            const std::string body(data, size);
            const size_t first = body.find('\0');
            const size_t second = first == std::string::npos ? first : body.find('\0', first + 1);
            return Value(reflect::ClassName{body.substr(0, first), second == std::string::npos
                                                                       ? std::string()
                                                                       : body.substr(second + 1)});
        }
        if (type == kExtArray)
            return Value(unpackArray(in, context));
        if (type == kExtEnum) {
            SP_CHECK(size > 8, InvalidArgument, context, ": malformed enum value");
            reflect::EnumValue entry{std::string(data + 8, size - 8)};
            std::memcpy(&entry.value, data, 8);
            return Value(std::move(entry));
        }
        SP_THROW(InvalidArgument, context, ": unknown extension type ", int(type));
    }
    default:
        SP_THROW(InvalidArgument, context, ": unsupported msgpack value");
    }
}
} // namespace

} // namespace sp::rpc
