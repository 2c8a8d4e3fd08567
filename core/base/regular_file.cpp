#include "core/base/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>

#include "core/base/error.h"

namespace sp {

namespace {
std::vector<std::string>& roots() {
    static std::vector<std::string> value;
    return value;
}
std::vector<std::string>& readOnlyRoots() {
    static std::vector<std::string> value;
    return value;
}

std::string quotedList(const std::vector<std::string>& folders) {
    std::string list;
    for (const std::string& folder : folders)
        list += (list.empty() ? "'" : ", '") + folder + "'";
    return list;
}

// True when `path` (absolute, resolved) is `root` or below it.
bool within(const std::string& path, const std::string& root) {
    if (root == "/")
        return true;
    return path.compare(0, root.size(), root) == 0 &&
           (path.size() == root.size() || path[root.size()] == '/');
}

// An open descriptor, closed on every path out.
struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0)
            ::close(fd);
    }
};

// Opens `path` for reading and checks it is a regular file of at most `maxBytes`; returns its size.
size_t openRegular(FileDescriptor& file, const std::string& path, std::string_view function,
                   std::string_view what, size_t maxBytes) {
    // O_NONBLOCK: opening a FIFO for reading otherwise waits for a writer. O_NOCTTY: a terminal named
    // here never becomes the process's controlling terminal.
    file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (file.fd < 0) {
        const int error = errno;
        SP_CHECK(error != ENOENT && error != ENOTDIR, NotFound, function, ": ", what, " '", path,
                 "' not found");
        SP_THROW(InvalidArgument, function, ": ", what, " '", path,
                 "' cannot be opened: ", std::strerror(error));
    }
    struct stat info {};
    SP_CHECK(::fstat(file.fd, &info) == 0, InvalidArgument, function, ": ", what, " '", path,
             "' cannot be read: ", std::strerror(errno));
    SP_CHECK(!S_ISDIR(info.st_mode), NotFound, function, ": ", what, " '", path, "' not found (a directory)");
    SP_CHECK(S_ISREG(info.st_mode), InvalidArgument, function, ": ", what, " '", path,
             "' is not a regular file (a FIFO, device or socket)");
    SP_CHECK(info.st_size >= 0 && size_t(info.st_size) <= maxBytes, InvalidArgument, function, ": ", what,
             " '", path, "' holds ", info.st_size, " bytes, more than the ", maxBytes, " allowed");
    return size_t(info.st_size);
}
} // namespace

void confineUserFiles(std::vector<std::string> newRoots, std::vector<std::string> newReadOnlyRoots) {
    for (std::vector<std::string>* list : {&newRoots, &newReadOnlyRoots})
        for (std::string& root : *list) {
            std::error_code error;
            const std::filesystem::path resolved = std::filesystem::canonical(root, error);
            SP_CHECK(!error && std::filesystem::is_directory(resolved), NotFound,
                     "confineUserFiles(): file root '", root, "' is not a directory");
            root = resolved.string();
        }
    roots() = std::move(newRoots);
    readOnlyRoots() = std::move(newReadOnlyRoots);
}

std::string resolveUserPath(const std::string& path, std::string_view function, std::string_view what,
                            FileAccess access) {
    if (roots().empty() && readOnlyRoots().empty())
        return path;
    SP_CHECK(!path.empty(), InvalidArgument, function, ": ", what, " path is empty");
    // weakly_canonical: symbolic links and ".." of the part that exists are followed, the rest (a file to
    // be created) is normalised; the resolved path is what gets opened.
    std::error_code error;
    const std::string resolved =
        std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error).string();
    const auto under = [&](const std::vector<std::string>& folders) {
        return std::any_of(folders.begin(), folders.end(),
                           [&](const std::string& root) { return within(resolved, root); });
    };
    const bool readOnly = !error && under(readOnlyRoots());
    if (access == FileAccess::Write && readOnly)
        SP_THROW(InvalidArgument, function, ": ", what, " '", path,
                 "' is under a read-only asset folder of the server (", quotedList(readOnlyRoots()),
                 "): clients read the assets, never write them; write under a --file-root folder ", "(",
                 quotedList(roots()), ")");
    if (error || !(under(roots()) || readOnly)) {
        std::vector<std::string> all = roots();
        all.insert(all.end(), readOnlyRoots().begin(), readOnlyRoots().end());
        SP_THROW(InvalidArgument, function, ": ", what, " '", path, "' is outside the server's file roots (",
                 quotedList(access == FileAccess::Write ? roots() : all),
                 "); start spear-server with --file-root DIR to allow another folder");
    }
    return resolved;
}

std::string readRegularFile(const std::string& userPath, std::string_view function, std::string_view what,
                            size_t maxBytes) {
    const std::string path = resolveUserPath(userPath, function, what);
    FileDescriptor file;
    const size_t size = openRegular(file, path, function, what, maxBytes);
    std::string contents(size, '\0');
    size_t done = 0;
    // Up to the size fstat gave: a file that grows meanwhile is read as it was, never without bound.
    while (done < size) {
        const ssize_t got = ::read(file.fd, contents.data() + done, size - done);
        if (got < 0 && errno == EINTR)
            continue;
        SP_CHECK(got >= 0, InvalidArgument, function, ": ", what, " '", path,
                 "' cannot be read: ", std::strerror(errno));
        if (got == 0)
            break; // it shrank meanwhile
        done += size_t(got);
    }
    contents.resize(done);
    return contents;
}

size_t checkRegularFile(const std::string& path, std::string_view function, std::string_view what,
                        size_t maxBytes, FileScope scope) {
    FileDescriptor file;
    return openRegular(file, scope == FileScope::User ? resolveUserPath(path, function, what) : path,
                       function, what, maxBytes);
}

void writeRegularFile(const std::string& userPath, std::string_view contents, std::string_view function,
                      std::string_view what) {
    const std::string path = resolveUserPath(userPath, function, what, FileAccess::Write);
    // Only a regular file (or nothing) may be replaced: never a FIFO, a device or a socket. lstat: a
    // symbolic link is replaced itself, as rename() does, not the file it points to.
    struct stat existing {};
    if (::lstat(path.c_str(), &existing) == 0)
        SP_CHECK(S_ISREG(existing.st_mode) || S_ISLNK(existing.st_mode), InvalidArgument, function, ": ",
                 what, " '", userPath, "' is not a regular file (a FIFO, device or socket)");
    const std::filesystem::path target(path);
    const std::filesystem::path directory = target.has_parent_path() ? target.parent_path() : ".";
    SP_CHECK(std::filesystem::is_directory(directory), NotFound, function, ": cannot write ", what, " '",
             userPath, "': no such directory");
    // The new contents go to a file of an unpredictable name beside the target (O_EXCL: never one that
    // exists), then replace it in one rename().
    std::random_device random;
    FileDescriptor file;
    std::string temporary;
    for (int attempt = 0; attempt < 16 && file.fd < 0; ++attempt) {
        temporary =
            (directory / ("." + target.filename().string() + ".tmp" + std::to_string(random()))).string();
        file.fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        SP_CHECK(file.fd >= 0 || errno == EEXIST, InvalidArgument, function, ": cannot write ", what, " '",
                 userPath, "': ", std::strerror(errno));
    }
    SP_CHECK(file.fd >= 0, InvalidArgument, function, ": cannot write ", what, " '", userPath,
             "': no free temporary name");
    try {
        size_t done = 0;
        while (done < contents.size()) {
            const ssize_t wrote = ::write(file.fd, contents.data() + done, contents.size() - done);
            if (wrote < 0 && errno == EINTR)
                continue;
            SP_CHECK(wrote > 0, InvalidArgument, function, ": writing ", what, " '", userPath,
                     "' failed: ", std::strerror(errno));
            done += size_t(wrote);
        }
        SP_CHECK(::fsync(file.fd) == 0, InvalidArgument, function, ": writing ", what, " '", userPath,
                 "' failed: ", std::strerror(errno));
        SP_CHECK(::rename(temporary.c_str(), path.c_str()) == 0, InvalidArgument, function, ": cannot write ",
                 what, " '", userPath, "': ", std::strerror(errno));
    } catch (...) {
        ::unlink(temporary.c_str()); // nothing is left behind by a failed write
        throw;
    }
}

} // namespace sp
