#include "core/rpc/server.h"

#include "core/rpc/reply_buffers.h"
#include "core/rpc/server_connection.h"

#include "core/reflect/sp_array.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/progress.h"
#include "core/plugin/plugin_loader.h"
#include "core/rpc/spin_poll.h"
#include "core/rpc/web.h"
#include "generated/rpc/cpp/protocol.gen.h"

namespace sp::rpc {

namespace {
std::atomic<int> gWakeFd{-1}; // write end of the self-pipe that stop() pokes

// Makes way for the socket at `path`: only a socket that no server listens on any more is removed. Any
// other file there (a typo'd --socket naming someone's data) is left alone, and so is a live server's.
void removeStaleSocket(const std::string& path, const sockaddr_un& address) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0)
        return; // nothing there
    SP_CHECK(S_ISSOCK(info.st_mode), InvalidArgument, "spear-server: --socket '", path,
             "' exists and is not a socket; refusing to replace it");
    const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const bool live =
        probe >= 0 && ::connect(probe, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
    if (probe >= 0)
        ::close(probe);
    SP_CHECK(!live, InvalidState, "spear-server: --socket '", path, "': another server is listening there");
    ::unlink(path.c_str());
}

} // namespace

namespace {
// The ArrayAllocator installed while a request runs: new arrays (a camera's readback) are placed in
// shared memory, which the reply then names instead of copying the bytes. Arrays the reply would carry
// inline (below kSharedMemoryThreshold: a path, a few points) stay on the heap: a segment costs a
// system call or two to make and map, more than copying them.
reflect::ArrayValue allocateInSegment(reflect::DType dtype, const std::vector<int64_t>& shape,
                                      reflect::ArrayFill fill, void* context) {
    auto& connection = *static_cast<Server::Connection*>(context);
    reflect::ArrayValue value;
    value.dtype = dtype;
    value.shape = shape;
    if (value.byteSize() < kSharedMemoryThreshold)
        return reflect::allocateOnHeap(dtype, shape, fill);
    auto [segment, clientBuffer] = connection.replySegment(value.byteSize());
    if (clientBuffer) {
        if (fill == reflect::ArrayFill::Zeroed) // a reused buffer holds an earlier reply
            std::memset(segment->data(), 0, value.byteSize());
        // If the engine keeps this array (a camera's frame until the next render), the reply says so.
        // Owners besides the engine: the connection's ReplyBuffers and requestSegments.
        if (OpenedSegments* opened = OpenedSegmentsScope::current())
            opened->push_back({segment->name(), segment, 2});
    }
    value.data = segment->data();
    value.owner = segment;
    connection.requestSegments.emplace_back(std::move(segment), clientBuffer);
    return value;
}
} // namespace

Server::Server(engine::Engine& engine, ServerOptions options, std::string apiHash)
    : options_(std::move(options)), dispatcher_(engine, std::move(apiHash), options_.token) {
    SP_CHECK(::pipe2(wakeFds_, O_CLOEXEC | O_NONBLOCK) == 0, Error,
             "spear-server: pipe failed: ", std::strerror(errno));
    dispatcher_.setInspectHook([this](int port) { return openInspector(port); });
    const bool inspectorOnly = options_.tcpPort < 0 && options_.socketPath.empty();
    if (!inspectorOnly) {
        // (Shared memory is for the main port's clients; a browser never maps any.)
        removeOrphanedSegments();
        guardAgainstTruncation(); // a client shrinking a segment the server maps must not crash it
    }
    if (options_.tcpPort >= 0) {
        SP_CHECK(!options_.token.empty(), InvalidArgument,
                 "spear-server: TCP needs a token (--token or SPEAR_TOKEN)");
        listenFd_ = detail::listenTcp(options_.bindAddress, options_.tcpPort, boundPort_);
    } else if (!inspectorOnly) {
        SP_CHECK(options_.socketPath.size() < sizeof(sockaddr_un::sun_path), InvalidArgument,
                 "spear-server: bad socket path '", options_.socketPath, "'");
        listenFd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un address{};
        address.sun_family = AF_UNIX;
        std::strncpy(address.sun_path, options_.socketPath.c_str(), sizeof(address.sun_path) - 1);
        removeStaleSocket(options_.socketPath, address);
        // Owner-only from the moment it exists: no window in which another user could connect.
        const mode_t previous = ::umask(0077);
        const int bound = ::bind(listenFd_, reinterpret_cast<sockaddr*>(&address), sizeof(address));
        ::umask(previous);
        SP_CHECK(bound == 0, Error, "spear-server: cannot bind '", options_.socketPath,
                 "': ", std::strerror(errno));
    }
    if (listenFd_ >= 0)
        SP_CHECK(::listen(listenFd_, 16) == 0, Error, "spear-server: listen failed: ", std::strerror(errno));
    if (options_.inspectPort >= 0)
        openInspector(options_.inspectPort);
    std::vector<std::string> allowed;
    for (const std::string& plugin : options_.plugins) {
        std::error_code error;
        const auto canonical = std::filesystem::weakly_canonical(plugin::resolve(plugin), error);
        if (!error)
            allowed.push_back(canonical.string());
    }
    dispatcher_.setPluginPolicy(options_.allowRemotePluginLoad, std::move(allowed));
}

Server::~Server() {
    for (auto& connection : connections_)
        if (connection->fd >= 0)
            drop(*connection);
    if (listenFd_ >= 0)
        ::close(listenFd_);
    if (inspectFd_ >= 0)
        ::close(inspectFd_);
    if (listenFd_ >= 0 && options_.tcpPort < 0 && !options_.socketPath.empty())
        ::unlink(options_.socketPath.c_str());
    ::close(wakeFds_[0]);
    ::close(wakeFds_[1]);
    if (logListener_)
        base::removeLogListener(logListener_);
    if (progressListener_)
        base::removeProgressListener(progressListener_);
}

std::string Server::address() const {
    if (options_.tcpPort >= 0)
        return "tcp:" + options_.bindAddress + ":" + std::to_string(boundPort_);
    return "unix:" + options_.socketPath;
}

void Server::stop() {
    base::requestStop(); // long work in progress (a path-traced frame) ends within a second
    const int fd = gWakeFd.load();
    if (fd >= 0) {
        const char byte = 1;
        [[maybe_unused]] ssize_t ignored = ::write(fd, &byte, 1); // async-signal-safe
    }
}

void Server::accept(int listenFd, bool inspector) {
    sockaddr_in peerAddress{};
    socklen_t addressLength = sizeof(peerAddress);
    const int fd = ::accept4(listenFd, reinterpret_cast<sockaddr*>(&peerAddress), &addressLength,
                             SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0)
        return;
    ucred peer{};
    socklen_t peerLength = sizeof(peer);
    const bool tcp = inspector || options_.tcpPort >= 0;
    const bool knownPeer = !tcp && ::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &peer, &peerLength) == 0;
    std::string peerName = "unix";
    if (tcp) {
        char text[INET_ADDRSTRLEN] = "";
        ::inet_ntop(AF_INET, &peerAddress.sin_addr, text, sizeof(text));
        peerName = text;
    } else if (knownPeer)
        peerName = "uid " + std::to_string(peer.uid);
    const auto now = std::chrono::steady_clock::now();
    const size_t waiting = size_t(std::count_if(connections_.begin(), connections_.end(), [](const auto& c) {
        return c->fd >= 0 && !c->session.greeted;
    }));
    if (waiting >= options_.maxConnectionsBeforeHello) {
        if (!refusingBeforeHello_) // once, until a connection is accepted again
            SP_LOG("spear-server: refusing connections: ", waiting, " are already waiting for their hello");
        refusingBeforeHello_ = true;
        ::close(fd);
        return;
    }
    refusingBeforeHello_ = false;
    if (tcp) {
        int one = 1;
        ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
    }
    auto connection = std::make_unique<Connection>();
    connection->fd = fd;
    connection->peer = peerName;
    connection->helloDeadline = now + std::chrono::milliseconds(options_.helloTimeoutMs);
    if (inspector) {
        connection->transport = Connection::Transport::Http;
        connection->session.requiredToken = options_.inspectToken;
        connection->session.browser = true;
    }
    // Reply buffers only on a Unix socket, where the kernel says which process the client is: the server then
    // accepts only that process's buffers (never another client's segments); over TCP, replies use the
    // server's own segments.
    if (knownPeer && peer.pid > 0) {
        connection->session.peerPid = peer.pid;
        ReplyBuffers* buffers = connection->replyBuffers.get();
        buffers->setOwner(peer.pid);
        connection->session.offerReplyBuffer = [buffers](const std::string& name, size_t size) {
            buffers->offer(name, size);
        };
        connection->session.dropReplyBuffer = [buffers](const std::string& name) { buffers->forget(name); };
    }
    connections_.push_back(std::move(connection));
}

void Server::drop(Connection& connection) {
    if (connection.transport == Connection::Transport::WebSocket && connection.fd >= 0)
        --broadcast_->browsers;
    dispatcher_.endSession(connection.session);
    for (auto& segment : connection.replySegments)
        segment->unlink();
    connection.replySegments.clear();
    connection.session.offerReplyBuffer = nullptr;
    connection.session.dropReplyBuffer = nullptr;
    connection.replyBuffers.reset(); // removes the names of the buffers the client offered
    if (connection.fd >= 0)
        ::close(connection.fd);
    connection.fd = -1;
}

bool Server::receive(Connection& connection) {
    char buffer[65536];
    const ssize_t received = ::recv(connection.fd, buffer, sizeof(buffer), 0);
    if (received < 0 && (errno == EINTR || errno == EAGAIN))
        return true;
    if (received <= 0)
        return false; // closed, or killed mid-call
    if (connection.transport == Connection::Transport::Socket) {
        connection.inbox.append(buffer, size_t(received));
        return true;
    }
    return receiveWeb(connection, std::string_view(buffer, size_t(received)));
}

bool Server::serve(Connection& connection) {
    if (!receive(connection))
        return false;
    while (connection.inbox.size() >= 4) {
        uint32_t word = 0;
        std::memcpy(&word, connection.inbox.data(), 4);
        // A frame with kTailFlag carries its large arguments raw after the message (a client without shared
        // memory); the limits hold for the whole frame.
        const bool tailed = (word & kTailFlag) != 0;
        const uint32_t length = word & ~kTailFlag;
        const bool greeted = connection.session.greeted;
        if (length > (greeted ? options_.maxMessageBytes : options_.maxMessageBytesBeforeHello)) {
            SP_LOG("spear-server: dropping a client that announced a ", length, "-byte message",
                   greeted ? "" : " before its hello");
            return false;
        }
        if (connection.inbox.size() < 4 + size_t(length))
            return true; // the rest is still on its way
        std::string_view message;
        std::string_view requestTail;
        if (!splitFrame(std::string_view(connection.inbox).substr(4, length), tailed, message, requestTail)) {
            SP_LOG("spear-server: dropping a client whose ", length, "-byte frame's message runs past it");
            return false;
        }
        for (auto& segment : connection.replySegments)
            segment->unlink();
        connection.replySegments.clear();
        msgpack::sbuffer reply;
        reply.write("\0\0\0\0", 4);
        auto send = [&](const std::shared_ptr<SharedMemorySegment>& segment, bool clientBuffer) {
            if (!clientBuffer)
                connection.replySegments.push_back(segment);
            return SharedArray{segment->name(), clientBuffer, std::nullopt};
        };
        auto toShm = [&](const reflect::ArrayValue& array) {
            for (const auto& [segment, clientBuffer] : connection.requestSegments) // already there: no copy
                if (segment->data() == array.data && (clientBuffer || !segment->unlinked()))
                    return send(segment, clientBuffer);
            auto [segment, clientBuffer] = connection.replySegment(array.byteSize());
            std::memcpy(segment->data(), array.data, array.byteSize());
            return send(segment, clientBuffer);
        };
        // A client that cannot map the server's memory gets large arrays in the reply's tail (kTailFlag):
        // placed now (kept alive by their owners), copied once, straight into the frame that is sent.
        std::vector<std::pair<size_t, reflect::ArrayValue>> tail;
        size_t tailSize = 0;
        auto toTail = [&](const reflect::ArrayValue& array) {
            tailSize = (tailSize + kTailAlignment - 1) / kTailAlignment * kTailAlignment;
            SharedArray placed;
            placed.tail = tailSize;
            tail.emplace_back(tailSize, array);
            tailSize += array.byteSize();
            return placed;
        };
        {
            // Until the client has shown it maps the server's segments (Session::sharedMemoryReplies), arrays
            // stay on the heap and the reply carries them inline.
            const bool shared = connection.session.sharedMemoryReplies;
            std::optional<reflect::ArrayAllocatorScope> allocator;
            if (shared)
                allocator.emplace(&allocateInSegment, &connection);
            // A request that keeps the engine busy for long (a path-traced frame at thousands of samples per
            // pixel) does not leave the other clients unanswered meanwhile.
            struct Busy {
                Server* server;
                const Connection* running;
            } busy{this, &connection};
            base::setBusyHook(
                [](void* context, std::string_view task, double seconds) {
                    auto* b = static_cast<Busy*>(context);
                    b->server->answerBusy(*b->running, task, seconds);
                },
                &busy);
            dispatcher_.handle(message.data(), message.size(), connection.session, reply,
                               shared ? ArrayToSharedMemory(toShm) : ArrayToSharedMemory(toTail),
                               tailed ? &requestTail : nullptr);
            base::setBusyHook(nullptr, nullptr);
        }
        if (connection.session.tokenRefused) {
            connection.session.tokenRefused = false;
            connection.heldUntil = std::chrono::steady_clock::now() + countTokenFailure(connection.peer);
        }
        // Arrays allocated in segments of the server's but not sent (kept by the engine for later) lose
        // their names now; their mappings live on with their owners.
        for (auto& [segment, clientBuffer] : connection.requestSegments)
            if (!clientBuffer && std::find(connection.replySegments.begin(), connection.replySegments.end(),
                                           segment) == connection.replySegments.end())
                segment->unlink();
        connection.requestSegments.clear();
        connection.replyBuffers->endRequest();
        connection.inbox.erase(0, 4 + size_t(length));
        uint32_t replyLength = uint32_t(reply.size() - 4);
        if (!tail.empty()) {
            const bool queued =
                queueWithTail(connection, std::string_view(reply.data() + 4, replyLength), tail, tailSize);
            tail.clear();
            if (!queued)
                return false;
        } else {
            std::memcpy(reply.data(), &replyLength, 4);
            if (!queueReply(connection, reply.data(), reply.size()))
                return false;
        }
        shutdown_ = shutdown_ || connection.session.shutdownRequested;
        if (connection.session.closeAfterReply) {
            connection.closing = true; // dropped once its last reply is out (run())
            break;
        }
    }
    return true;
}

void Server::answerBusy(const Connection& running, std::string_view task, double seconds) {
    if (broadcast_)
        sendBroadcast(); // the long work's own progress, live
    for (auto& connection : connections_) {
        if (connection.get() == &running || connection->fd < 0 || connection->closing)
            continue;
        if (!connection->outbox.empty() && !flush(*connection)) {
            drop(*connection);
            continue;
        }
        char buffer[65536];
        ssize_t received = 0;
        bool broken = false;
        while (!broken && (received = ::recv(connection->fd, buffer, sizeof(buffer), 0)) > 0) {
            if (connection->transport == Connection::Transport::Socket)
                connection->inbox.append(buffer, size_t(received));
            else
                broken = !receiveWeb(*connection, std::string_view(buffer, size_t(received)));
        }
        if (broken) {
            drop(*connection);
            continue;
        }
        // (Closed, or a message past the limits: the event loop finds out after the busy request.)
        while (connection->inbox.size() >= 4) {
            uint32_t word = 0;
            std::memcpy(&word, connection->inbox.data(), 4);
            const uint32_t length = word & ~kTailFlag;
            const bool greeted = connection->session.greeted;
            if (length > (greeted ? options_.maxMessageBytes : options_.maxMessageBytesBeforeHello) ||
                connection->inbox.size() < 4 + size_t(length))
                break;
            msgpack::object_handle request;
            const msgpack::object* id = nullptr;
            std::string_view message;
            std::string_view tail;
            try {
                if (splitFrame(std::string_view(connection->inbox).substr(4, length), (word & kTailFlag) != 0,
                               message, tail)) {
                    request = unpackBounded(message.data(), message.size());
                    id = mapField(request.get(), protocol::field::kId);
                }
            } catch (const std::exception&) {
            }
            msgpack::sbuffer reply;
            reply.write("\0\0\0\0", 4);
            msgpack::packer<msgpack::sbuffer> out(&reply);
            if (id && (id->type == msgpack::type::ARRAY || id->type == msgpack::type::MAP))
                id = nullptr; // echoed only as a scalar, as the dispatcher does
            char elapsed[32];
            std::snprintf(elapsed, sizeof(elapsed), "%.1f", seconds);
            packError(out, id, "InvalidStateError",
                      "spear-server: busy: another client's request has kept the engine for " +
                          std::string(elapsed) + " s (" + std::string(task) +
                          "); this request was not run: send it again when that is done");
            const uint32_t replyLength = uint32_t(reply.size() - 4);
            std::memcpy(reply.data(), &replyLength, 4);
            connection->inbox.erase(0, 4 + size_t(length));
            if (!queueReply(*connection, reply.data(), reply.size())) {
                drop(*connection);
                break;
            }
            if (!greeted) { // its hello was not run: it connects again later
                connection->closing = true;
                break;
            }
        }
    }
}

std::chrono::milliseconds Server::countTokenFailure(const std::string& peer) {
    const auto now = std::chrono::steady_clock::now();
    if (tokenFailures_.size() >= 4096) // bounded: forget the peers whose last hold is over
        std::erase_if(tokenFailures_, [&](const auto& entry) { return entry.second.lockedUntil <= now; });
    TokenFailures& failures = tokenFailures_[peer];
    ++failures.count;
    if (failures.count <= options_.tokenFailuresBeforeLockout)
        return std::chrono::milliseconds(0);
    // Not reset by the right token: on loopback a guesser and the users it is guessing for are one peer.
    const int doublings = std::min(failures.count - options_.tokenFailuresBeforeLockout - 1, 6);
    const auto hold = std::min(std::chrono::seconds(1 << doublings), std::chrono::seconds(60));
    failures.lockedUntil = now + hold;
    // Once per doubling, so that a guesser cannot fill the log.
    if (doublings < 6 || failures.count % 64 == 0)
        SP_LOG("spear-server: ", failures.count, " wrong tokens from ", peer, "; each refusal is held for ",
               hold.count(), " s (the right token is answered at once)");
    return hold;
}

int Server::msUntilHelloDeadline() const {
    const auto now = std::chrono::steady_clock::now();
    int64_t soonest = -1;
    for (const auto& connection : connections_)
        if (connection->fd >= 0 && ((!connection->session.greeted && !connection->closing) ||
                                    (connection->closing && connection->held()))) {
            const auto deadline = connection->closing ? connection->heldUntil : connection->helloDeadline;
            const int64_t left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count() + 1;
            soonest =
                soonest < 0 ? std::max<int64_t>(left, 0) : std::min(soonest, std::max<int64_t>(left, 0));
        }
    return int(soonest);
}

void Server::dropSilentBeforeHello() {
    const auto now = std::chrono::steady_clock::now();
    for (auto& connection : connections_)
        if (connection->fd >= 0 && !connection->session.greeted && !connection->closing &&
            now >= connection->helloDeadline) {
            if (connection->transport != Connection::Transport::Http) // a browser's idle spare connection
                SP_LOG("spear-server: dropping a client from ", connection->peer,
                       " that did not say hello within ", options_.helloTimeoutMs, " ms");
            drop(*connection);
        }
}

void Server::run() {
    gWakeFd = wakeFds_[1];
    while (!shutdown_ && pump(-1)) {
    }
    flushBeforeExit();
    gWakeFd = -1;
}

std::vector<pollfd> Server::pollSet() const {
    // The wake pipe, the listening sockets, then one entry per connection (the order pump() relies on).
    std::vector<pollfd> fds{{wakeFds_[0], POLLIN, 0}, {listenFd_, POLLIN, 0}, {inspectFd_, POLLIN, 0}};
    for (const auto& connection : connections_) {
        // Reading while replies wait is what lets a client that never reads be found out (queueReply).
        short events = connection->closing ? 0 : POLLIN;
        if (!connection->outbox.empty() && !connection->held())
            events |= POLLOUT;
        fds.push_back({connection->fd, events, 0});
    }
    return fds;
}

bool Server::waitReady(int timeoutMs) const {
    std::vector<pollfd> fds = pollSet();
    const int deadline = msUntilHelloDeadline();
    const int timeout = deadline < 0 ? timeoutMs : std::min(deadline, timeoutMs);
    return ::poll(fds.data(), fds.size(), timeout) > 0 || deadline == 0;
}

bool Server::pump(int timeoutMs) {
    if (shutdown_)
        return false;
    if (broadcast_)
        sendBroadcast(); // what was logged since the last round (in-process: by the frames between two pumps)
    std::vector<pollfd> fds = pollSet(); // (poll() ignores the entries of sockets that are not open: fd -1)
    const size_t first = 3;              // the first connection's
    int timeout = msUntilHelloDeadline();
    if (timeoutMs >= 0)
        timeout = timeout < 0 ? timeoutMs : std::min(timeout, timeoutMs);
    if (pollSpinning(fds.data(), fds.size(), timeout,
                     timeoutMs == 0 ? std::chrono::microseconds(0) : options_.spin) < 0)
        return errno == EINTR;
    if (fds[0].revents)
        return false;
    // The client whose frame is open is served first. A client does not wait for the reply to a frame's
    // end (it reads it before its next request), so another client may already have sent its next
    // frame's begin, causally after that end, when both are read in one round: in connection order, the
    // begin could run first and be refused because the frame is still open.
    std::vector<size_t> order; // positions in fds
    for (size_t i = first; i < fds.size(); ++i)
        order.insert(
            &connections_[i - first]->session == dispatcher_.frameOwner() ? order.begin() : order.end(), i);
    for (const size_t i : order) {
        const short revents = fds[i].revents;
        if (!revents)
            continue;
        Connection& connection = *connections_[i - first];
        bool keep = true;
        if (revents & POLLOUT)
            keep = flush(connection);
        if (keep && (revents & (POLLIN | POLLHUP | POLLERR)))
            keep = connection.closing ? false : serve(connection);
        if (keep && connection.closing && connection.outbox.empty())
            keep = false; // its last reply is out
        if (!keep)
            drop(connection);
    }
    dropSilentBeforeHello();
    // After the others: connections that went away in the meantime no longer count against the limit of
    // connections waiting for their hello.
    if (fds[1].revents & POLLIN)
        accept(listenFd_, false);
    if (fds[2].revents & POLLIN)
        accept(inspectFd_, true);
    std::erase_if(connections_, [](const auto& connection) { return connection->fd < 0; });
    if (broadcast_)
        sendBroadcast();
    return !shutdown_;
}

} // namespace sp::rpc
