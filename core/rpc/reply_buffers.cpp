#include "core/rpc/reply_buffers.h"

#include <sys/mman.h>

#include "core/base/error.h"

namespace sp::rpc {

ReplyBuffers::~ReplyBuffers() {
    for (const auto& [name, buffer] : buffers_)
        ::shm_unlink(name.c_str()); // ENOENT when the client removed it first
}

void ReplyBuffers::offer(const std::string& name, size_t size) {
    if (!name.starts_with(prefix_) || name.size() == prefix_.size() ||
        name.find_first_not_of("0123456789abcdef", prefix_.size()) != std::string::npos)
        return;
    auto it = buffers_.find(name);
    if (it == buffers_.end()) {
        if (buffers_.size() >= kMaxBuffers)
            return;
        try {
            it = buffers_
                     .emplace(name, Buffer{std::make_shared<SharedMemorySegment>(
                                               SharedMemorySegment::open(name, size)),
                                           false})
                     .first;
        } catch (const Error&) {
            return; // not a segment this client can offer: its reply uses the server's own
        }
    }
    // The segment's size now, by fstat: the client may have shrunk it since it was first offered, and
    // writing past its end would be SIGBUS.
    if (it->second.segment->holds(size))
        it->second.offered = true;
}

std::shared_ptr<SharedMemorySegment> ReplyBuffers::take(size_t bytes) {
    Buffer* best = nullptr;
    for (auto& [name, buffer] : buffers_) {
        const size_t capacity = buffer.segment->size();
        // use_count() == 1: no array the engine kept from an earlier request lives in it.
        if (buffer.offered && buffer.segment.use_count() == 1 && capacity >= bytes &&
            capacity <= 2 * std::max<size_t>(bytes, 1) && (!best || capacity < best->segment->size()))
            best = &buffer;
    }
    // Checked again just before the server writes into it (fstat, see offer()).
    if (best && !best->segment->holds(bytes)) {
        best->offered = false;
        return take(bytes);
    }
    if (!best)
        return nullptr;
    best->offered = false;
    return best->segment;
}

void ReplyBuffers::forget(const std::string& name) {
    buffers_.erase(name); // an array the engine kept in it keeps the mapping alive
}

void ReplyBuffers::endRequest() {
    for (auto& [name, buffer] : buffers_)
        buffer.offered = false;
}

} // namespace sp::rpc
