#pragma once
// Reading (and writing) files whose path a user, or a client over RPC, names. Such a path can name
// anything: a FIFO that no one writes blocks open() and read() forever, and /dev/zero never ends, so a
// single-threaded server would hang or run out of memory. Only regular files of bounded size are read:
// the file is opened without blocking (O_NONBLOCK, which only matters for FIFOs and devices), then
// checked by fstat on the descriptor that is read, so nothing can be swapped in between.

#include <cstddef>
#include <string>
#include <string_view>

namespace sp {

// The largest user-named file the engine reads: far above any scene, blueprint, mesh or texture.
inline constexpr size_t kMaxUserFileBytes = size_t(256) << 20;

// The whole contents of the regular file at `path`. `function` and `what` name the caller and the
// file in messages ("UWorld.load_scene(): scene file 'x.json' ..."). Throws sp::NotFound when the file
// does not exist (or is a directory), sp::InvalidArgument when it is not a regular file (a FIFO, a
// device, a socket), holds more than `maxBytes`, or cannot be read.
std::string readRegularFile(const std::string& path, std::string_view function, std::string_view what,
                            size_t maxBytes = kMaxUserFileBytes);

// The same checks without reading, for files a library opens by path itself (assimp, stb_image): throws
// as readRegularFile does, else returns the file's size.
size_t checkRegularFile(const std::string& path, std::string_view function, std::string_view what,
                        size_t maxBytes = kMaxUserFileBytes);

// Replaces the contents of the file at `path` (created owner-writable under the umask) with `contents`.
// Only a regular file is written: a FIFO without a reader would otherwise block the open, and a device
// would take the bytes. Throws sp::NotFound when the directory does not exist, sp::InvalidArgument when
// the path is not a regular file or the write fails.
void writeRegularFile(const std::string& path, std::string_view contents, std::string_view function,
                      std::string_view what);

} // namespace sp
