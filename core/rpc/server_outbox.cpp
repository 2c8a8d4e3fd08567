#include "core/rpc/server.h"

#include "core/rpc/server_connection.h"

#include <sys/socket.h>
#include <sys/uio.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/log.h"
#include "core/rpc/value_msgpack.h"

// The server's sending side: replies go to the socket as far as it takes them now, never waiting for a
// client; the rest waits in the connection's outbox, bounded (Server::withinOutboxLimits).

namespace sp::rpc {

namespace {
// A frame whose memory is kept for the connection's next large one: one of at least this size (a camera's
// image, inline), and not past this (a connection that once got a huge reply does not hold it for good).
constexpr size_t kSpareFrameMin = size_t(1) << 20;
constexpr size_t kSpareFrameMax = size_t(64) << 20;

// Keeps a sent frame's memory for the connection's next large frame, when it is such a frame.
void keepAsSpare(std::string& spare, std::string&& sent) {
    if (sent.size() >= kSpareFrameMin && sent.size() <= kSpareFrameMax)
        spare = std::move(sent);
}

// Zero bytes for the padding before a tail's array (less than kTailAlignment of it).
constexpr char kZeros[kTailAlignment] = {};

// Sends `pieces` from byte `sent` of them on, what the socket takes now without waiting; advances `sent`;
// false when the connection is broken.
bool sendSomeGathered(int fd, std::span<const iovec> pieces, size_t& sent) {
    while (true) {
        std::array<iovec, 64> batch{};
        size_t count = 0;
        size_t skip = sent;
        for (const iovec& piece : pieces) {
            if (skip >= piece.iov_len) {
                skip -= piece.iov_len;
                continue;
            }
            if (count == batch.size())
                break;
            batch[count++] = {static_cast<char*>(piece.iov_base) + skip, piece.iov_len - skip};
            skip = 0;
        }
        if (count == 0)
            return true; // all of it
        msghdr message{};
        message.msg_iov = batch.data();
        message.msg_iovlen = count;
        const ssize_t n = ::sendmsg(fd, &message, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return true; // the client has not read enough yet
        if (n <= 0)
            return false;
        sent += size_t(n);
    }
}

// Sends what the socket takes now of `size` bytes at `data` without waiting, advancing both; false when the
// connection is broken.
bool sendSome(int fd, const char*& data, size_t& size) {
    const iovec piece{const_cast<char*>(data), size};
    size_t sent = 0;
    if (!sendSomeGathered(fd, {&piece, 1}, sent))
        return false;
    data += sent;
    size -= sent;
    return true;
}

// Copies `pieces` from byte `from` of them on into `out`.
void gather(std::span<const iovec> pieces, size_t from, char* out) {
    for (const iovec& piece : pieces) {
        if (from >= piece.iov_len) {
            from -= piece.iov_len;
            continue;
        }
        std::memcpy(out, static_cast<const char*>(piece.iov_base) + from, piece.iov_len - from);
        out += piece.iov_len - from;
        from = 0;
    }
}

} // namespace

bool Server::queueReply(Connection& connection, const char* data, size_t size) {
    if (connection.transport != Connection::Transport::WebSocket)
        return queueBytes(connection, data, size);
    // One binary message per reply; the copy costs little next to a browser's own work on it.
    std::string framed = web::frameHeader(web::kBinary, size);
    framed.append(data, size);
    return queueBytes(connection, framed.data(), framed.size());
}

bool Server::queueFrame(Connection& connection, std::string&& frame) {
    if (connection.transport == Connection::Transport::WebSocket)
        return queueReply(connection, frame.data(), frame.size());
    // As queueBytes, but what the socket does not take now waits in the outbox as it is, not as a copy.
    const char* data = frame.data();
    size_t size = frame.size();
    if (connection.outbox.empty() && !connection.held() && !sendSome(connection.fd, data, size))
        return false;
    if (size == 0) {
        keepAsSpare(connection.spareFrame, std::move(frame));
        return true;
    }
    if (connection.outbox.empty())
        connection.outboxOffset = frame.size() - size;
    connection.outboxBytes += frame.size();
    connection.outbox.push_back(std::move(frame));
    return withinOutboxLimits(connection);
}

bool Server::queueWithTail(Connection& connection, std::string_view message,
                           std::span<const std::pair<size_t, reflect::ArrayValue>> tail, size_t tailSize) {
    // [length | kTailFlag][message length][message][padding][tail], the tail aligned from the byte after the
    // length word (where the client's buffer starts).
    const auto messageLength = uint32_t(message.size());
    const size_t tailStart = 4 + (4 + messageLength + kTailAlignment - 1) / kTailAlignment * kTailAlignment;
    if (tailStart + tailSize - 4 >= kTailFlag) {
        SP_LOG("spear-server: dropping a client whose reply of ", tailStart + tailSize,
               " bytes is past the 2 GiB a frame can carry");
        return false;
    }
    // The header, the message and its padding are written here; the arrays go from their own memory (sendmsg
    // gathers them), copied only where the socket does not take them whole now.
    std::string head(tailStart, '\0');
    const uint32_t length = uint32_t(tailStart + tailSize - 4) | kTailFlag;
    std::memcpy(head.data(), &length, 4);
    std::memcpy(head.data() + 4, &messageLength, 4);
    std::memcpy(head.data() + 8, message.data(), messageLength);
    std::vector<iovec> pieces{{head.data(), head.size()}};
    size_t written = 0; // of the tail
    for (const auto& [offset, array] : tail) {
        if (offset > written)
            pieces.push_back({const_cast<char*>(kZeros), offset - written});
        pieces.push_back({array.data, array.byteSize()});
        written = offset + array.byteSize();
    }
    return queueGathered(connection, pieces);
}

bool Server::queueGathered(Connection& connection, std::span<const iovec> pieces) {
    size_t total = 0;
    for (const iovec& piece : pieces)
        total += piece.iov_len;
    size_t sent = 0;
    if (connection.transport == Connection::Transport::Socket && connection.outbox.empty() &&
        !connection.held() && !sendSomeGathered(connection.fd, pieces, sent))
        return false;
    if (sent == total)
        return true;
    // The rest is copied to wait in the outbox: an array may be the engine's own, which a later request
    // (this client's or another's) could change before the socket takes it. Into the memory of the last
    // such frame: a client reading a camera every frame gets no fresh pages.
    std::string rest = std::move(connection.spareFrame);
    rest.resize(total - sent);
    gather(pieces, sent, rest.data());
    return queueFrame(connection, std::move(rest));
}

bool Server::queueBytes(Connection& connection, const char* data, size_t size) {
    // Straight to the socket when nothing waits before it (the usual case: a client reads each reply
    // before it sends its next request); the rest is queued, in order.
    if (connection.outbox.empty() && !connection.held() && !sendSome(connection.fd, data, size))
        return false;
    if (size == 0)
        return true;
    connection.outbox.emplace_back(data, size);
    connection.outboxBytes += size;
    return withinOutboxLimits(connection);
}

bool Server::withinOutboxLimits(Connection& connection) {
    // One reply may wait whatever its size: a client reading a large reply is not misbehaving. It is the
    // replies behind it, those of requests sent without reading, that are bounded.
    if (connection.outbox.size() > 1 && (connection.outboxBytes > options_.maxQueuedReplyBytes ||
                                         connection.outbox.size() > options_.maxQueuedReplies)) {
        // A client that sends requests but does not read the replies: waiting for it would stop every
        // other client, so it is dropped (its frame aborted, its shared memory released).
        SP_LOG("spear-server: dropping a client that left ", connection.outbox.size(), " replies (",
               connection.outboxBytes, " bytes) unread");
        return false;
    }
    return true;
}

bool Server::flush(Connection& connection) {
    while (!connection.outbox.empty()) {
        const std::string& front = connection.outbox.front();
        const char* data = front.data() + connection.outboxOffset;
        size_t size = front.size() - connection.outboxOffset;
        if (!sendSome(connection.fd, data, size))
            return false;
        connection.outboxOffset = front.size() - size;
        if (size > 0)
            return true; // the socket is full again
        connection.outboxBytes -= front.size();
        keepAsSpare(connection.spareFrame, std::move(connection.outbox.front()));
        connection.outbox.pop_front();
        connection.outboxOffset = 0;
    }
    return true;
}

void Server::flushBeforeExit() {
    // The replies already made (a shutdown request's, above all) still reach clients that read them; one
    // that does not read gets a second at most, not the power to keep the server from exiting.
    for (int waited = 0; waited < 1000; waited += 10) {
        std::vector<pollfd> fds;
        for (const auto& connection : connections_)
            if (connection->fd >= 0 && !connection->outbox.empty())
                fds.push_back({connection->fd, POLLOUT, 0});
        if (fds.empty() || ::poll(fds.data(), fds.size(), 10) < 0)
            return;
        for (auto& connection : connections_)
            if (connection->fd >= 0 && !connection->outbox.empty() && !flush(*connection))
                drop(*connection);
    }
}

} // namespace sp::rpc
