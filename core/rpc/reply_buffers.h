#pragma once
// Reply buffers: shared-memory segments a client owns and offers, request by request, for the large
// arrays of the replies (a request's "reply_buffers": [[name, size], ...]).
//
// A fresh segment costs the kernel a page fault and a zeroed page per 4 KiB on first touch; for a 1080p
// RGBA image that is several times the cost of copying it. A buffer the client keeps has its pages
// already, and the client reads the reply through the mapping it already has. The client offers only
// buffers no array of its own still views, and the server takes one only if no array the engine kept
// (a camera's readback held for a later frame) lives in it, so nothing either side holds changes under
// it. The client owns the names; the server removes those it was offered when the connection ends, so a
// client that dies leaves nothing under /dev/shm.

#include <cstddef>
#include <map>
#include <memory>
#include <string>

#include "core/rpc/shared_memory.h"

namespace sp::rpc {

class ReplyBuffers {
  public:
    ReplyBuffers() = default;
    ReplyBuffers(const ReplyBuffers&) = delete;
    ReplyBuffers& operator=(const ReplyBuffers&) = delete;
    ~ReplyBuffers(); // removes the names of every buffer offered on the connection

    // The client process; only buffers it named ("/spear-<pid>-r<hex digits>") are accepted.
    void setOwner(long pid) { prefix_ = "/spear-" + std::to_string(pid) + "-r"; }
    // The client offers `name` for the current request's reply. Maps it the first time; a name that is
    // not one of the client's buffers, or too small for `size`, is ignored (the reply then uses a segment
    // of the server's own). At most kMaxBuffers are mapped at a time.
    void offer(const std::string& name, size_t size);
    static constexpr size_t kMaxBuffers = 32;
    // An offered buffer of at least `bytes` (at most twice, so a small array does not use a large one),
    // taken for this reply; nullptr when there is none.
    std::shared_ptr<SharedMemorySegment> take(size_t bytes);
    // After a reply: nothing stays offered until the client offers it again.
    void endRequest();
    // The client removed the buffer (a request's "dropped_buffers"): its mapping goes once nothing uses it.
    void forget(const std::string& name);

  private:
    struct Buffer {
        std::shared_ptr<SharedMemorySegment> segment;
        bool offered = false;
    };
    std::map<std::string, Buffer> buffers_;
    std::string prefix_ = "/spear-?"; // no name matches until setOwner()
};

} // namespace sp::rpc
