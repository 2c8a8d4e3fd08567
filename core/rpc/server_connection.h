#pragma once
// What server.cpp (the event loop, the socket transport) and server_web.cpp (the inspector's HTTP and
// WebSocket serving, the broadcast of log lines) share: one client's state, and the listening TCP socket.
// Private to core/rpc.

#include <atomic>
#include <chrono>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/rpc/dispatcher.h"
#include "core/rpc/reply_buffers.h"
#include "core/rpc/server.h"
#include "core/rpc/shared_memory.h"
#include "generated/rpc/cpp/protocol.gen.h"

namespace sp::rpc {

namespace detail {
// A TCP socket bound to address:port (0: a free one, written to boundPort); throws naming the address.
int listenTcp(const std::string& bindAddress, int port, int& boundPort);
} // namespace detail

struct Server::Connection {
    int fd = -1;
    // The inspector's connections start as HTTP and either switch to WebSocket or close after one response.
    enum class Transport { Socket, Http, WebSocket } transport = Transport::Socket;
    std::string webInput; // bytes read but not yet decoded: an HTTP head, or WebSocket frames
    std::string peer;     // TCP: the client's address; Unix socket: its user id (for token failures)
    std::chrono::steady_clock::time_point helloDeadline; // dropped if still not greeted then
    std::string inbox;
    // Replies the socket did not take yet, oldest first; the first is sent from outboxOffset on. The
    // server never waits for a client to read (it serves everyone on one thread): a client whose unread
    // replies pass the limits in server.h is dropped instead (Server::queueReply).
    std::deque<std::string> outbox;
    size_t outboxOffset = 0;
    size_t outboxBytes = 0;
    // The memory of the last large frame queued (what the socket did not take at once of a reply carrying
    // arrays inline), reused for the next one so that a slow client reading a camera every frame over TCP
    // does not cost fresh pages each time.
    std::string spareFrame;
    // The last reply ends the connection (a refused hello, a malformed first message): nothing more is
    // read, and the connection is dropped once the outbox is empty.
    bool closing = false;
    // A refused hello's reply is not sent before then (Server::countTokenFailure).
    std::chrono::steady_clock::time_point heldUntil{};
    bool held() const { return std::chrono::steady_clock::now() < heldUntil; }
    Session session;
    // The client's buffers for large reply arrays (core/rpc/reply_buffers.h).
    std::unique_ptr<ReplyBuffers> replyBuffers = std::make_unique<ReplyBuffers>();
    // Segments of the server's own holding the arrays of the last reply: the client maps them before it
    // sends anything else, so they are unlinked when its next request arrives (or when it goes away).
    std::vector<std::shared_ptr<SharedMemorySegment>> replySegments;
    // Segments that arrays were allocated in while the current request ran (see allocateInSegment), and
    // whether each is a reply buffer of the client's.
    std::vector<std::pair<std::shared_ptr<SharedMemorySegment>, bool>> requestSegments;

    // A segment for `bytes` of reply: one of the client's buffers if it offered one that fits, else a
    // new one of the server's.
    std::pair<std::shared_ptr<SharedMemorySegment>, bool> replySegment(size_t bytes) {
        if (auto buffer = replyBuffers->take(bytes))
            return {std::move(buffer), true};
        return {std::make_shared<SharedMemorySegment>(SharedMemorySegment::create(bytes)), false};
    }
};

// Log lines and progress reports, queued from whichever thread makes them while browsers are connected, and
// sent to every greeted browser after each round of requests (a log line reaches a watching page within its
// next poll, a quarter of a second). Bounded: a flood between two rounds keeps its first lines and says how
// many more there were.
struct Server::Broadcast {
    static constexpr size_t kMaxLines = 200;
    std::mutex mutex;
    std::vector<std::string> messages; // framed: [length][msgpack]
    size_t dropped = 0;
    std::map<std::string, std::string> progress; // the latest report of each task, framed
    std::atomic<int> browsers{0};

    // A framed message the server sends browsers unasked: {key: [fields...]} (protocol.json's "push").
    template <typename... Fields> static std::string push(std::string_view key, const Fields&... fields) {
        msgpack::sbuffer body;
        msgpack::packer<msgpack::sbuffer> out(&body);
        out.pack_map(1);
        out.pack(key);
        out.pack_array(sizeof...(fields));
        (out.pack(fields), ...);
        std::string framed(4, '\0');
        const uint32_t length = uint32_t(body.size());
        std::memcpy(framed.data(), &length, 4);
        framed.append(body.data(), body.size());
        return framed;
    }
    void log(std::string_view file, int line, std::string_view message) {
        if (browsers.load() == 0)
            return;
        std::string framed = push(protocol::reply::kLog, file, line, message);
        std::lock_guard lock(mutex);
        if (messages.size() < kMaxLines)
            messages.push_back(std::move(framed));
        else
            ++dropped;
    }
    void report(std::string_view task, double done, double total, bool finished) {
        if (browsers.load() == 0)
            return;
        std::string framed = push(protocol::reply::kProgress, task, done, total, finished);
        std::lock_guard lock(mutex);
        progress[std::string(task)] = std::move(framed);
    }
};

} // namespace sp::rpc
