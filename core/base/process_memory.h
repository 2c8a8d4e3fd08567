#pragma once
// How the process's allocator treats the memory a frame frees: kept for the next frame, not handed back.
//
// Why: a software rasteriser (Mesa's llvmpipe) allocates its per-frame triangle bins and frees them when the
// frame is drawn, and glibc hands what lies free at the top of the heap back to the system each time, so
// every frame faults those pages in again and the kernel zeroes them. Measured on 2 cores (BENCHMARKS.md):
// a still scene of 4000 instances at 64 x 64 over RPC 37-47 -> 23-29 ms a frame; Table 3 in-process at
// 1080p, N = 64 21 -> 18-19 ms and N = 256 35-38 -> 31 ms.

namespace sp {

// Sets glibc's mmap threshold to 32 MiB and its trim threshold to 128 MiB, once per process, unless the
// environment names either (MALLOC_MMAP_THRESHOLD_ / MALLOC_TRIM_THRESHOLD_: the user's choice wins). Both
// are set because setting one makes glibc stop adapting the other. glibc's own adaptation, once a 32 MiB
// block is freed, ends at blocks of up to 32 MiB from the heap and trimming past 64 MiB free; this reaches
// that at once and keeps up to 128 MiB, a frame's worth of a large scene's bins and readback arrays.
// Returns whether this call or an earlier one set them.
bool keepFreedMemory();

} // namespace sp
