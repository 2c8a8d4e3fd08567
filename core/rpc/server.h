#pragma once
// Server: serves one engine to any number of clients over a Unix socket (owner-only permissions) or
// TCP (loopback unless told otherwise; a token is required). Single-threaded: requests run on the
// thread that owns the engine, one at a time, in arrival order; a client that sends garbage,
// disappears mid-call or leaves its replies unread is dropped and the others are served on. The server
// never blocks on one client: sockets are non-blocking and unread replies wait in a bounded queue.

#include <chrono>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <poll.h>
#include <sys/uio.h>

#include "core/rpc/dispatcher.h"
#include "core/rpc/shared_memory.h"

namespace sp::rpc {

struct ServerOptions {
    std::string socketPath; // Unix socket; used when tcpPort < 0
    int tcpPort = -1;       // 0 picks a free port
    std::string bindAddress = "127.0.0.1";
    std::string token; // required for TCP
    // The plugins the server was started with (--plugin), which clients may load_plugin again; with
    // allowRemotePluginLoad, any library (Dispatcher::setPluginPolicy).
    std::vector<std::string> plugins;
    bool allowRemotePluginLoad = false;
    size_t maxMessageBytes = size_t(1) << 30;
    // Until a connection has said hello (proved its token over TCP), it is anyone's: its messages are
    // capped, few such connections are kept, and each has a while to say hello. Otherwise a handful of
    // unauthenticated clients announcing 1 GiB messages could make the server buffer gigabytes, and
    // connections that never say hello could take every slot.
    size_t maxMessageBytesBeforeHello = size_t(64) << 10;
    size_t maxConnectionsBeforeHello = 64;
    int helloTimeoutMs = 10000;
    // Past this many wrong tokens from a peer (TCP: its address), the refusal of each further wrong token is
    // held back for a while before it is sent, doubling with each (1 s, 2 s, ... 60 s), its connection still
    // counting against maxConnectionsBeforeHello: a guessing client gets a few tries a minute instead of
    // thousands a second. The right token is answered at once: on loopback every local user is the same peer,
    // and a guesser must not lock them out.
    int tokenFailuresBeforeLockout = 3;
    // A client's replies that it has not read yet are queued up to these limits; past either, the client
    // is dropped: one that sends requests and never reads must not stop the server for everyone. (A
    // single reply waits whatever its size: only replies queued behind another count against a client.)
    size_t maxQueuedReplyBytes = size_t(64) << 20;
    size_t maxQueuedReplies = 256;
    // How long the server polls its sockets without sleeping before it sleeps in poll() (spin_poll.h);
    // spear-server takes it from SPEAR_RPC_SPIN_US.
    std::chrono::microseconds spin{100};
    // The inspector (spear-server --inspect PORT, or a client's inspect request): a second TCP port, on
    // loopback unless bindAddress says otherwise, where a browser loads the page in inspectRoot over HTTP and
    // then speaks this protocol over a WebSocket (web.h). inspectToken guards both (the page's ?token=, its
    // hello), whatever the transport of the main port: a Unix socket's owner-only permissions mean nothing to
    // a browser's other tabs. Without one, the TCP token is used, else a random one is made.
    int inspectPort = -1; // 0 picks a free port; -1: none until a client asks (Dispatcher's inspect op)
    std::string inspectRoot;
    std::string inspectToken;
};

class Server {
  public:
    // With neither socketPath nor tcpPort, the server has no main port: it serves the inspector alone (an
    // in-process engine's, pumped by its owner between frames).
    Server(engine::Engine& engine, ServerOptions options, std::string apiHash);
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    // Where clients connect: "unix:/path" or "tcp:127.0.0.1:port".
    std::string address() const;
    // The inspector's page, "http://127.0.0.1:port/" (without the token), or "" without --inspect.
    std::string inspectAddress() const;
    // The page with its token ("http://127.0.0.1:port/?token=..."), or "" without an inspector.
    std::string inspectUrl() const;
    // Starts the inspector on `port` (0: a free one) unless it runs; returns inspectUrl(). Throws
    // InvalidState for another port than the one it runs on, NotFound without the page.
    std::string openInspector(int port);
    // Serves until a client asks for shutdown or stop() is called (also from a signal handler).
    void run();
    // Serves what is ready within timeoutMs (0: only what is ready now; -1: waits for something), once;
    // false once a client asked for shutdown. For an owner whose thread the engine is (an in-process engine).
    bool pump(int timeoutMs);
    // Whether something waits to be served (pump() would act), waiting up to timeoutMs; serves nothing, so an
    // owner may wait without holding what guards its engine (Python's GIL) and pump() with it.
    bool waitReady(int timeoutMs) const;
    static void stop();

    struct Connection; // one client: its socket, session and shared memory (server.cpp)
    struct Broadcast;  // log lines and progress for the inspector's browsers (server.cpp)

  private:
    std::vector<pollfd> pollSet() const;
    void accept(int listenFd, bool inspector);
    // Reads what the socket has into the connection's inbox (through HTTP and WebSocket framing on the
    // inspector's port); false: drop the connection.
    bool receive(Connection& connection);
    bool receiveWeb(Connection& connection, std::string_view bytes);
    bool serveHttp(Connection& connection); // the page and its files, or the switch to WebSocket
    bool serve(Connection& connection);     // false: drop the connection
    // Sends a reply now as far as the socket takes it, queueing the rest; false: drop the connection
    // (broken, or too many replies left unread).
    bool queueReply(Connection& connection, const char* data, size_t size);
    // A reply built whole (with its arrays inline): what the socket does not take waits as it is, not copied.
    bool queueFrame(Connection& connection, std::string&& frame);
    // A reply whose large arrays travel raw after its message (a client without shared memory): `tail`
    // holds each array at its offset there (kTailAlignment), `tailSize` bytes in all.
    bool queueWithTail(Connection& connection, std::string_view message,
                       std::span<const std::pair<size_t, reflect::ArrayValue>> tail, size_t tailSize);
    // The pieces of a reply to send in order (its head, then each array from its own memory): sent as far as
    // the socket takes it, the rest copied into the outbox.
    bool queueGathered(Connection& connection, std::span<const iovec> pieces);
    // False (the client is to be dropped) when its unread replies are past the limits.
    bool withinOutboxLimits(Connection& connection);
    // queueReply's bytes as they are, without the WebSocket framing of a reply (HTTP, control frames).
    bool queueBytes(Connection& connection, const char* data, size_t size);
    bool flush(Connection& connection); // sends queued replies; false: drop the connection
    void flushBeforeExit();
    void drop(Connection& connection);
    // Counts a wrong token from `peer`; returns how long its refusal is held back.
    std::chrono::milliseconds countTokenFailure(const std::string& peer);
    void dropSilentBeforeHello(); // connections past their hello deadline
    // While `running`'s request keeps the engine's thread past a second (base::setBusyHook): the other
    // clients' waiting replies are sent, and each request they send is answered "busy" without being run.
    void answerBusy(const Connection& running, std::string_view task, double seconds);
    // For poll(): until the next hello deadline or held refusal, -1 while there is none.
    int msUntilHelloDeadline() const;

    ServerOptions options_;
    Dispatcher dispatcher_;
    int listenFd_ = -1;
    int boundPort_ = -1;
    int inspectFd_ = -1;
    int inspectBoundPort_ = -1;
    int wakeFds_[2] = {-1, -1}; // the self-pipe stop() pokes (run() makes it the signal handler's)
    // What the engine logs and reports while browsers watch, sent to them after each round of requests.
    std::shared_ptr<Broadcast> broadcast_;
    int logListener_ = 0;
    int progressListener_ = 0;
    void sendBroadcast();
    std::vector<std::unique_ptr<Connection>> connections_;
    bool shutdown_ = false;
    struct TokenFailures {
        int count = 0;
        std::chrono::steady_clock::time_point lockedUntil;
    };
    std::map<std::string, TokenFailures> tokenFailures_; // by peer
    bool refusingBeforeHello_ = false; // the limit of connections waiting for hello is reached
};

} // namespace sp::rpc
