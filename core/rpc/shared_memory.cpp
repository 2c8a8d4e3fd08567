#include "core/rpc/shared_memory.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <utility>

#include "core/base/error.h"
#include "core/base/log.h"

namespace sp::rpc {

namespace {

// The truncation guard: the address ranges of every mapped segment, in a fixed table that the SIGBUS
// handler can read without locks or allocation. Slots are claimed and released under a mutex, on the
// threads that map and unmap; the handler only loads.
struct GuardSlot {
    std::atomic<uintptr_t> begin{0}; // 0: free
    std::atomic<uintptr_t> end{0};
    std::atomic<bool> revoked{false};
};
constexpr size_t kGuardSlots = 4096; // far more segments than a server maps at a time
std::array<GuardSlot, kGuardSlots> gGuard;
std::mutex gGuardMutex;
std::atomic<uint64_t> gTruncationFaults{0};
struct sigaction gPreviousSigbus {};

int guardMapping(void* data, size_t length) {
    std::lock_guard lock(gGuardMutex);
    for (size_t i = 0; i < kGuardSlots; ++i) {
        if (gGuard[i].begin.load(std::memory_order_relaxed) != 0)
            continue;
        gGuard[i].revoked.store(false, std::memory_order_relaxed);
        gGuard[i].end.store(reinterpret_cast<uintptr_t>(data) + length, std::memory_order_relaxed);
        gGuard[i].begin.store(reinterpret_cast<uintptr_t>(data), std::memory_order_release);
        return int(i);
    }
    static std::once_flag warned;
    std::call_once(warned, [] { SP_LOG("spear-server: truncation guard full; new segments are unguarded"); });
    return -1;
}

void unguardMapping(int slot) {
    if (slot < 0)
        return;
    std::lock_guard lock(gGuardMutex);
    gGuard[size_t(slot)].begin.store(0, std::memory_order_release);
}

void onSigbus(int signal, siginfo_t* info, void* context) {
    const auto address = reinterpret_cast<uintptr_t>(info->si_addr);
    for (GuardSlot& slot : gGuard) {
        const uintptr_t begin = slot.begin.load(std::memory_order_acquire);
        const uintptr_t end = slot.end.load(std::memory_order_relaxed);
        if (begin == 0 || address < begin || address >= end)
            continue;
        // A peer shrank this segment under us. Zeroed private pages take the mapping's place (mmap is a
        // plain system call, safe here in practice), the faulting access is retried on return and
        // succeeds, and the request that used the segment is answered with an error
        // (truncationFaults()).
        if (::mmap(reinterpret_cast<void*>(begin), end - begin, PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) == MAP_FAILED)
            break;
        slot.revoked.store(true, std::memory_order_relaxed);
        gTruncationFaults.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    // Not a segment's fault: the previous disposition handles it when the access faults again.
    if ((gPreviousSigbus.sa_flags & SA_SIGINFO) && gPreviousSigbus.sa_sigaction) {
        gPreviousSigbus.sa_sigaction(signal, info, context);
        return;
    }
    ::sigaction(SIGBUS, &gPreviousSigbus, nullptr);
}
// 64 random bits in hex: a name no other user can guess and create first (shm_open with O_EXCL would
// then fail, or a peer would be handed a segment of theirs).
std::string randomSuffix() {
    uint64_t bits = 0;
    for (size_t got = 0; got < sizeof(bits);) {
        const ssize_t n = ::getrandom(reinterpret_cast<char*>(&bits) + got, sizeof(bits) - got, 0);
        SP_CHECK(n > 0 || errno == EINTR, Error,
                 "SharedMemorySegment::create(): getrandom failed: ", std::strerror(errno));
        got += n > 0 ? size_t(n) : 0;
    }
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(bits));
    return text;
}
} // namespace

void guardAgainstTruncation() {
    static std::once_flag installed;
    std::call_once(installed, [] {
        struct sigaction action {};
        action.sa_sigaction = &onSigbus;
        action.sa_flags = SA_SIGINFO;
        sigemptyset(&action.sa_mask);
        ::sigaction(SIGBUS, &action, &gPreviousSigbus);
    });
}

uint64_t truncationFaults() {
    return gTruncationFaults.load(std::memory_order_relaxed);
}

bool SharedMemorySegment::holds(size_t bytes) const {
    if (!data_ || bytes > size_ || revoked())
        return false;
    if (fd_ < 0)
        return true;
    struct stat info {};
    return ::fstat(fd_, &info) == 0 && size_t(info.st_size) >= bytes;
}

bool SharedMemorySegment::revoked() const {
    return guard_ >= 0 && gGuard[size_t(guard_)].revoked.load(std::memory_order_relaxed);
}

SharedMemorySegment SharedMemorySegment::create(size_t size) {
    SharedMemorySegment segment;
    segment.name_ = "/spear-" + std::to_string(::getpid()) + "-" + randomSuffix();
    segment.size_ = size;
    int fd = ::shm_open(segment.name_.c_str(), O_CREAT | O_EXCL | O_RDWR, 0600);
    SP_CHECK(fd >= 0, Error, "SharedMemorySegment::create(): shm_open('", segment.name_,
             "') failed: ", std::strerror(errno));
    if (::ftruncate(fd, off_t(size == 0 ? 1 : size)) != 0) {
        const std::string error = std::strerror(errno);
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
        SP_THROW(Error, "SharedMemorySegment::create(): mmap of ", size,
                 " bytes failed: ", std::strerror(errno));
    }
    segment.guard_ = guardMapping(segment.data_, size == 0 ? 1 : size);
    return segment;
}

SharedMemorySegment SharedMemorySegment::open(const std::string& name, size_t size) {
    SP_CHECK(name.starts_with("/spear-") && name.find('/', 1) == std::string::npos, InvalidArgument,
             "SharedMemorySegment::open(): '", name, "' is not a spear segment name");
    SharedMemorySegment segment;
    segment.name_ = name;
    segment.size_ = size;
    segment.unlinked_ = true; // the creator owns the name
    segment.fd_ = ::shm_open(name.c_str(), O_RDWR | O_CLOEXEC, 0);
    SP_CHECK(segment.fd_ >= 0, InvalidArgument, "SharedMemorySegment::open(): cannot open '", name,
             "': ", std::strerror(errno));
    struct stat info {};
    SP_CHECK(::fstat(segment.fd_, &info) == 0 && size_t(info.st_size) >= size, InvalidArgument,
             "SharedMemorySegment::open(): segment '", name, "' holds ", info.st_size, " bytes, fewer than ",
             size);
    segment.data_ = ::mmap(nullptr, size == 0 ? 1 : size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_POPULATE,
                           segment.fd_, 0);
    if (segment.data_ == MAP_FAILED) {
        segment.data_ = nullptr;
        SP_THROW(InvalidArgument, "SharedMemorySegment::open(): mmap of '", name,
                 "' failed: ", std::strerror(errno));
    }
    segment.guard_ = guardMapping(segment.data_, size == 0 ? 1 : size);
    return segment;
}

SharedMemorySegment::SharedMemorySegment(SharedMemorySegment&& other) noexcept {
    *this = std::move(other);
}

SharedMemorySegment& SharedMemorySegment::operator=(SharedMemorySegment&& other) noexcept {
    if (this != &other) {
        release();
        name_ = std::move(other.name_);
        data_ = std::exchange(other.data_, nullptr);
        size_ = other.size_;
        unlinked_ = other.unlinked_;
        fd_ = std::exchange(other.fd_, -1);
        guard_ = std::exchange(other.guard_, -1);
    }
    return *this;
}

SharedMemorySegment::~SharedMemorySegment() {
    release();
}

void SharedMemorySegment::release() {
    unguardMapping(std::exchange(guard_, -1)); // before munmap: the range may be mapped again by anyone
    if (data_)
        ::munmap(data_, size_ == 0 ? 1 : size_);
    data_ = nullptr;
    if (fd_ >= 0)
        ::close(fd_);
    fd_ = -1;
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
