#include "core/base/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/base/error.h"

namespace sp {

namespace {
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

std::string readRegularFile(const std::string& path, std::string_view function, std::string_view what,
                            size_t maxBytes) {
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
                        size_t maxBytes) {
    FileDescriptor file;
    return openRegular(file, path, function, what, maxBytes);
}

void writeRegularFile(const std::string& path, std::string_view contents, std::string_view function,
                      std::string_view what) {
    FileDescriptor file;
    // No O_TRUNC: nothing is truncated before it is known to be a regular file. O_NONBLOCK: a FIFO with
    // no reader fails (ENXIO) instead of waiting for one.
    file.fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0666);
    if (file.fd < 0) {
        const int error = errno;
        SP_CHECK(error != ENOENT && error != ENOTDIR, NotFound, function, ": cannot write ", what, " '", path,
                 "': ", std::strerror(error));
        SP_CHECK(error != ENXIO, InvalidArgument, function, ": ", what, " '", path,
                 "' is not a regular file (a FIFO, device or socket)"); // a FIFO with no reader
        SP_THROW(InvalidArgument, function, ": cannot write ", what, " '", path, "': ", std::strerror(error));
    }
    struct stat info {};
    SP_CHECK(::fstat(file.fd, &info) == 0 && S_ISREG(info.st_mode), InvalidArgument, function, ": ", what,
             " '", path, "' is not a regular file (a FIFO, device or socket)");
    SP_CHECK(::ftruncate(file.fd, 0) == 0, InvalidArgument, function, ": cannot write ", what, " '", path,
             "': ", std::strerror(errno));
    size_t done = 0;
    while (done < contents.size()) {
        const ssize_t wrote = ::write(file.fd, contents.data() + done, contents.size() - done);
        if (wrote < 0 && errno == EINTR)
            continue;
        SP_CHECK(wrote > 0, InvalidArgument, function, ": writing ", what, " '", path,
                 "' failed: ", std::strerror(errno));
        done += size_t(wrote);
    }
}

} // namespace sp
