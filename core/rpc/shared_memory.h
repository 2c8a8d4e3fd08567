#pragma once
// POSIX shared-memory segments for arrays too large to copy through the socket. Names carry the
// creating process id and 64 random bits ("/spear-<pid>-<16 hex digits>"): the id so that segments left
// by a process that died can be found and removed (removeOrphanedSegments, at every server start and
// every client start), the random bits so that no other user can create a name before its owner does.
//
// A client can shrink a segment (ftruncate) that the server has mapped: its own reply buffers, the
// arguments it names, and the server's segments whose names it was sent. Touching a page past the new end
// is SIGBUS. Sizes are therefore checked against the file (fstat) on every use, never taken from the
// client; and since a client can still shrink a segment between that check and the access, the server
// also installs guardAgainstTruncation(), which turns such a fault into a lost segment instead of a crash.

#include <cstddef>
#include <cstdint>
#include <string>

namespace sp::rpc {

class SharedMemorySegment {
  public:
    // Creates a new segment of `size` bytes (readable and writable by the owner only).
    static SharedMemorySegment create(size_t size);
    // Maps `size` bytes of an existing segment created by the peer; throws InvalidArgument when the
    // segment (by fstat) holds fewer.
    static SharedMemorySegment open(const std::string& name, size_t size);

    SharedMemorySegment(SharedMemorySegment&& other) noexcept;
    SharedMemorySegment& operator=(SharedMemorySegment&& other) noexcept;
    SharedMemorySegment(const SharedMemorySegment&) = delete;
    SharedMemorySegment& operator=(const SharedMemorySegment&) = delete;
    ~SharedMemorySegment(); // unmaps; does not unlink

    const std::string& name() const { return name_; }
    void* data() const { return data_; }
    size_t size() const { return size_; } // the bytes mapped
    // Whether the first `bytes` of the mapping can be touched now: within the mapping, the segment still
    // holds them (fstat, for segments a client created: it may have shrunk them since), and no truncation
    // fault has replaced the mapping (guardAgainstTruncation).
    bool holds(size_t bytes) const;
    // A truncation fault replaced the mapping with zeroed private memory: it no longer shows the segment.
    bool revoked() const;
    // Removes the name; the mapping stays valid until unmapped. Idempotent.
    void unlink();
    bool unlinked() const { return unlinked_; }

  private:
    SharedMemorySegment() = default;
    void release(); // unmaps and closes
    std::string name_;
    void* data_ = nullptr;
    size_t size_ = 0;
    bool unlinked_ = false;
    int fd_ = -1;    // kept for segments the peer created, to fstat them on every use
    int guard_ = -1; // this mapping's slot in the truncation guard, or -1
};

// Installs a SIGBUS handler (once per process) that recovers from a fault in any mapped segment: the
// mapping is replaced by zeroed private memory, so the access completes, and the segment is revoked().
// Faults anywhere else go to the previous handler, or crash as before.
void guardAgainstTruncation();
// How many segments a truncation fault revoked so far in this process.
uint64_t truncationFaults();

// Unlinks /dev/shm/spear-<pid>-* segments whose creating process no longer exists. Returns how many.
int removeOrphanedSegments();

} // namespace sp::rpc
