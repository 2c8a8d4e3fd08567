#pragma once
// Recycled blocks: large, uninitialised memory blocks that go back to a small process-wide pool when their
// last owner lets go, and are handed to the next request of the same size.
//
// Why: a camera allocates the arrays it reads a frame into every frame. Blocks past glibc's mapping threshold
// (32 MiB at most) come fresh from the kernel each time and go back when freed, and the kernel zeroes and
// faults in every 4 KiB page of them: for the 14 modalities of a 1080p frame, about 20,000 page faults a
// frame. The pool keeps at most kMaxRecycledBytes, giving up the oldest blocks first.

#include <cstddef>
#include <memory>

namespace sp {

// Requests smaller than this are plain heap allocations: glibc reuses those itself.
inline constexpr std::size_t kMinRecycledBlockBytes = std::size_t(1) << 20;
inline constexpr std::size_t kMaxRecycledBytes = std::size_t(256) << 20;

// A block of `bytes` uninitialised bytes (a kept block of exactly that size when there is one); it returns to
// the pool when the last copy of the pointer goes. Safe from any thread.
std::shared_ptr<char[]> takeRecycledBlock(std::size_t bytes);

// The bytes the pool keeps now, waiting to be taken again.
std::size_t recycledBytesKept();

} // namespace sp
