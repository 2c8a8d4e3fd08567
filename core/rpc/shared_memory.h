#pragma once
// POSIX shared-memory segments for arrays too large to copy through the socket. Names carry the
// creating process id ("/spear-<pid>-<n>"), so that segments left by a process that died can be found
// and removed (removeOrphanedSegments), and nothing stays under /dev/shm after either side exits.

#include <cstddef>
#include <string>

namespace sp::rpc {

class SharedMemorySegment {
  public:
    // Creates a new segment of `size` bytes (readable and writable by the owner only).
    static SharedMemorySegment create(size_t size);
    // Maps an existing segment created by the peer.
    static SharedMemorySegment open(const std::string& name, size_t size);

    SharedMemorySegment(SharedMemorySegment&& other) noexcept;
    SharedMemorySegment& operator=(SharedMemorySegment&& other) noexcept;
    SharedMemorySegment(const SharedMemorySegment&) = delete;
    SharedMemorySegment& operator=(const SharedMemorySegment&) = delete;
    ~SharedMemorySegment(); // unmaps; does not unlink

    const std::string& name() const { return name_; }
    void* data() const { return data_; }
    size_t size() const { return size_; }
    // Removes the name; the mapping stays valid until unmapped. Idempotent.
    void unlink();
    bool unlinked() const { return unlinked_; }

  private:
    SharedMemorySegment() = default;
    std::string name_;
    void* data_ = nullptr;
    size_t size_ = 0;
    bool unlinked_ = false;
};

// Unlinks /dev/shm/spear-<pid>-* segments whose creating process no longer exists. Returns how many.
int removeOrphanedSegments();

} // namespace sp::rpc
