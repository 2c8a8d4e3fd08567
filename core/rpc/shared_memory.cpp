#include "core/rpc/shared_memory.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

#include "core/base/error.h"

namespace sp::rpc {

namespace {
std::string systemError() {
    return std::strerror(errno);
}
} // namespace

SharedMemorySegment SharedMemorySegment::create(size_t size) {
    static std::atomic<uint64_t> counter{0};
    SharedMemorySegment segment;
    segment.name_ = "/spear-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    segment.size_ = size;
    int fd = ::shm_open(segment.name_.c_str(), O_CREAT | O_EXCL | O_RDWR, 0600);
    SP_CHECK(fd >= 0, Error, "SharedMemorySegment::create(): shm_open('", segment.name_,
             "') failed: ", systemError());
    if (::ftruncate(fd, off_t(size == 0 ? 1 : size)) != 0) {
        const std::string error = systemError();
        ::close(fd);
        ::shm_unlink(segment.name_.c_str());
        SP_THROW(Error, "SharedMemorySegment::create(): cannot size '", segment.name_, "' to ", size,
                 " bytes: ", error);
    }
    segment.data_ =
        ::mmap(nullptr, size == 0 ? 1 : size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_POPULATE, fd, 0);
    ::close(fd);
    if (segment.data_ == MAP_FAILED) {
        segment.data_ = nullptr;
        ::shm_unlink(segment.name_.c_str());
        SP_THROW(Error, "SharedMemorySegment::create(): mmap of ", size, " bytes failed: ", systemError());
    }
    return segment;
}

SharedMemorySegment SharedMemorySegment::open(const std::string& name, size_t size) {
    SP_CHECK(name.starts_with("/spear-") && name.find('/', 1) == std::string::npos, InvalidArgument,
             "SharedMemorySegment::open(): '", name, "' is not a spear segment name");
    SharedMemorySegment segment;
    segment.name_ = name;
    segment.size_ = size;
    int fd = ::shm_open(name.c_str(), O_RDWR, 0);
    SP_CHECK(fd >= 0, InvalidArgument, "SharedMemorySegment::open(): cannot open '", name,
             "': ", systemError());
    struct stat info {};
    if (::fstat(fd, &info) != 0 || size_t(info.st_size) < size) {
        ::close(fd);
        SP_THROW(InvalidArgument, "SharedMemorySegment::open(): '", name, "' holds fewer than ", size,
                 " bytes");
    }
    segment.data_ =
        ::mmap(nullptr, size == 0 ? 1 : size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_POPULATE, fd, 0);
    ::close(fd);
    SP_CHECK(segment.data_ != MAP_FAILED, InvalidArgument, "SharedMemorySegment::open(): mmap of '", name,
             "' failed: ", systemError());
    segment.unlinked_ = true; // the creator owns the name
    return segment;
}

SharedMemorySegment::SharedMemorySegment(SharedMemorySegment&& other) noexcept {
    *this = std::move(other);
}

SharedMemorySegment& SharedMemorySegment::operator=(SharedMemorySegment&& other) noexcept {
    if (this != &other) {
        if (data_)
            ::munmap(data_, size_ == 0 ? 1 : size_);
        name_ = std::move(other.name_);
        data_ = std::exchange(other.data_, nullptr);
        size_ = other.size_;
        unlinked_ = other.unlinked_;
    }
    return *this;
}

SharedMemorySegment::~SharedMemorySegment() {
    if (data_)
        ::munmap(data_, size_ == 0 ? 1 : size_);
}

void SharedMemorySegment::unlink() {
    if (!unlinked_ && !name_.empty())
        ::shm_unlink(name_.c_str()); // ENOENT is fine: the peer may have removed it already
    unlinked_ = true;
}

int removeOrphanedSegments() {
    int removed = 0;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator("/dev/shm", error)) {
        const std::string name = entry.path().filename().string();
        if (!name.starts_with("spear-"))
            continue;
        const size_t dash = name.find('-', 6);
        const pid_t pid = pid_t(std::atoi(name.substr(6, dash - 6).c_str()));
        if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) {
            ::shm_unlink(("/" + name).c_str());
            ++removed;
        }
    }
    return removed;
}

} // namespace sp::rpc
