#pragma once
// Reading (and writing) files whose path a user, or a client over RPC, names. Such a path can name
// anything: a FIFO that no one writes blocks open() and read() forever, and /dev/zero never ends, so a
// single-threaded server would hang or run out of memory. Only regular files of bounded size are read:
// the file is opened without blocking (O_NONBLOCK, which only matters for FIFOs and devices), then
// checked by fstat on the descriptor that is read, so nothing can be swapped in between.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sp {

// Whose choice a path is. A user file is named by the engine's user (in-process) or by a client over RPC,
// and is confined to the file roots when a server has some (confineUserFiles); an engine file is named
// by the server's own configuration (its command line, its plugin path) and is not.
enum class FileScope { User, Engine };
// What a user file is opened for: a file that is read may lie under any root, one that is written only
// under a writable root and never under a read-only one (confineUserFiles).
enum class FileAccess { Read, Write };

// Confines user files to `roots` and `readOnlyRoots`: a path must then resolve, symbolic links and ".."
// followed, to a root or below one, and the resolved path is what is opened (a relative path is relative to
// the working directory, as everywhere). Files under `readOnlyRoots` (a server's built-in assets and asset
// folders) are read, never written, even where a writable root holds them. Empty lists (the default, and
// always in-process: the user owns the process) allow any path. Set once, before a server serves clients; a
// server's clients otherwise read and write whatever the server's user can (/proc/self/..., keys).
void confineUserFiles(std::vector<std::string> roots, std::vector<std::string> readOnlyRoots = {});

// The largest user-named file the engine reads: far above any scene, blueprint, mesh or texture.
inline constexpr size_t kMaxUserFileBytes = size_t(256) << 20;

// The whole contents of the regular file at `path`. `function` and `what` name the caller and the
// file in messages ("UWorld.load_scene(): scene file 'x.json' ..."). Throws sp::NotFound when the file
// does not exist (or is a directory), sp::InvalidArgument when it is not a regular file (a FIFO, a
// device, a socket), holds more than `maxBytes`, cannot be read, or is a user file outside the roots.
std::string readRegularFile(const std::string& path, std::string_view function, std::string_view what,
                            size_t maxBytes = kMaxUserFileBytes);

// The same checks without reading, for files a library opens by path itself (assimp, stb_image): throws
// as readRegularFile does, else returns the file's size.
size_t checkRegularFile(const std::string& path, std::string_view function, std::string_view what,
                        size_t maxBytes = kMaxUserFileBytes, FileScope scope = FileScope::User);

// The path to open for user file `path`: `path` itself when user files are not confined, else its
// resolved form. Throws sp::InvalidArgument naming the function, the file and the roots when it is
// outside them, or, to be written, outside the writable ones or under a read-only one (before anything
// about the file, even whether it exists, is told).
std::string resolveUserPath(const std::string& path, std::string_view function, std::string_view what,
                            FileAccess access = FileAccess::Read);

// Replaces the contents of the file at `path` (created owner-writable under the umask) with `contents`,
// whole: they are written to a new file beside it that is then renamed over it, so a reader, or a crash
// mid-write, never sees half a file. Only a regular file is replaced: a FIFO, a device or a socket at
// `path` is refused. Throws sp::NotFound when the directory does not exist, sp::InvalidArgument when the
// path is not a regular file, is outside the file roots, or the write fails.
void writeRegularFile(const std::string& path, std::string_view contents, std::string_view function,
                      std::string_view what);

} // namespace sp
