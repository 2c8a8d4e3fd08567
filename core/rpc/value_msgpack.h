#pragma once
// Values on the wire, as msgpack. Plain values map to msgpack's own types; three extension types carry
// what msgpack lacks:
//   1 object: u32 index, u32 generation (little endian), then the class name (UTF-8)
//   2 class:  the class name (UTF-8)
//   3 array:  a msgpack array [dtype, shape, payload], payload either the bytes (bin) or, for large
//             arrays, a map {"shm": segment name, "size": bytes} naming a shared-memory segment (in
//             replies also {"buffer": name, "size": bytes}, one of the client's reply buffers, or
//             {"tail": offset, "size": bytes}, bytes after the message: see kTailFlag; requests from a
//             client without shared memory carry their large arrays the same way).
//   4 enum:   i64 value (little endian), then the enum's name (UTF-8); sent by clients, so that an enum
//             argument is told apart from an int. Replies carry enums as plain ints: the client knows each
//             result's type from the generated API.

#include <msgpack.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/reflect/value.h"

namespace sp::rpc {

enum ExtType : int8_t { kExtObject = 1, kExtClass = 2, kExtArray = 3, kExtEnum = 4 };

// Arrays of at least this many bytes travel through shared memory.
inline constexpr size_t kSharedMemoryThreshold = 64 * 1024;

// Where a large array of a reply is: a segment the server made ("shm": the client maps it and removes its
// name), one of the client's reply buffers ("buffer": core/rpc/reply_buffers.h), or, for a client that cannot
// map the server's memory, the reply's tail ("tail": its offset there; see kTailFlag).
struct SharedArray {
    std::string name;
    bool clientBuffer = false;
    std::optional<uint64_t> tail;
};

// A frame whose length word has this bit set carries raw array bytes after its msgpack message: the
// next 4 bytes are the message's length m, the message follows, and the tail starts at 4 + m rounded up to
// kTailAlignment (counted from the byte after the length word), each array at its "tail" offset from there. A
// large array then travels once, as it is, instead of being copied through msgpack on both sides. (Messages
// are at most 1 GiB: the bit is free.) Replies to a client that cannot map the server's memory use it, and so
// do requests from such a client (over TCP, where the server opens no segment of the client's).
inline constexpr uint32_t kTailFlag = 0x80000000u;
inline constexpr size_t kTailAlignment = 64;
// Called for a large array: places its bytes in shared memory (unless they are there already).
using ArrayToSharedMemory = std::function<SharedArray(const reflect::ArrayValue&)>;

void pack(msgpack::packer<msgpack::sbuffer>& out, const reflect::Value& value,
          const ArrayToSharedMemory& toShm);
// Throws InvalidArgument (with `context`) for anything that is not a valid encoded value, including lists
// and dicts nested deeper than reflect::kMaxValueDepth.
reflect::Value unpack(const msgpack::object& in, std::string_view context);

// msgpack::unpack with every count bounded by the bytes at hand: each element of an array or map takes at
// least one byte, so a 5-byte array32 header that announces 2^32 elements is refused instead of making
// msgpack-c allocate 64 GiB of objects for them. (Its parser is iterative, so depth alone cannot overflow
// the stack; the recursive conversions after it bound depth themselves.)
msgpack::object_handle unpackBounded(const char* data, size_t size);

// The tail of the request being decoded (kTailFlag), while a scope is alive on this thread: unpack() copies
// an array named {"tail": offset, "size": bytes} from it, after checking that it lies inside. Outside a
// scope, such an array is refused.
class RequestTailScope {
  public:
    explicit RequestTailScope(std::string_view tail);
    ~RequestTailScope();
    RequestTailScope(const RequestTailScope&) = delete;
    RequestTailScope& operator=(const RequestTailScope&) = delete;
    // The innermost scope's tail, or nullptr outside any.
    static const std::string_view* current();

  private:
    std::string_view tail_;
    const std::string_view* previous_;
};

// A frame's parts: the msgpack message and, for a frame whose length word has kTailFlag, its tail. `body` is
// what follows the length word. False when a tailed frame's own lengths do not fit inside it.
bool splitFrame(std::string_view body, bool tailed, std::string_view& message, std::string_view& tail);

class SharedMemorySegment;
// The client-owned segments a request used, recorded while a scope is alive on this thread: those unpack()
// mapped for its arguments, and the client's reply buffers the server wrote arrays into. One that is still
// referenced by more than `othersHolding` owners once the request's values are gone is used by the engine
// (it kept the array): the reply names it "kept", so that the client never writes into it again.
struct OpenedSegment {
    std::string name;
    std::weak_ptr<SharedMemorySegment> segment;
    long othersHolding = 0; // owners that are not the engine (the server's own bookkeeping)
};
using OpenedSegments = std::vector<OpenedSegment>;
class OpenedSegmentsScope {
  public:
    explicit OpenedSegmentsScope(OpenedSegments& list);
    ~OpenedSegmentsScope();
    OpenedSegmentsScope(const OpenedSegmentsScope&) = delete;
    OpenedSegmentsScope& operator=(const OpenedSegmentsScope&) = delete;
    // The list of the innermost scope on this thread, or nullptr.
    static OpenedSegments* current();

  private:
    OpenedSegments* previous_;
};

// The process whose shared-memory segments a request may name as argument arrays ("/spear-<pid>-..."):
// the connecting client, as the kernel reports it on a Unix socket. Outside a scope, or with no known peer
// (TCP), no segment is opened, so no client can make the server read another process's memory.
class SegmentOwnerScope {
  public:
    explicit SegmentOwnerScope(long pid);
    ~SegmentOwnerScope();
    SegmentOwnerScope(const SegmentOwnerScope&) = delete;
    SegmentOwnerScope& operator=(const SegmentOwnerScope&) = delete;
    // The pid of the innermost scope on this thread, or -1.
    static long current();

  private:
    long previous_;
};

} // namespace sp::rpc
