#pragma once
// Dispatcher: turns one request into one reply, through the registry's invokers. It knows nothing of
// sockets, so the protocol can be tested without a connection.
//
// Requests are msgpack maps {"id": n, "op": name, ...}; replies are {"id": n, "ok": value} or
// {"id": n, "error": [type, message]}, where type names a class of spear.errors. Ops:
//   hello {api_hash, token}       must come first; mismatched API hash or token closes the connection. Its
//                                 reply names "shm_probe", a shared-memory segment holding a nonce
//   shm_proof {nonce}             the nonce the client read from the probe ("" if it could not map it):
//                                 when it matches, large reply arrays travel through shared memory on this
//                                 connection (Session::sharedMemoryReplies); until then they come inline
//   world {kind}                  "game" (an editor world only exists in editor mode)
//   worlds {action, name, object} create (name) | destroy (object) | list: worlds beside the game world
//   frame {action}                begin | execute | begin_end | end | abort
//   call {object, function, args} invoke a reflected function
//   call {class, function, args}  invoke a static function of a class (no object)
//   get {object, property}, set {object, property, value}
//   is_valid {object}, describe {object}
//   batch {calls: [request...], critical: [i...], between_frames}
//                                 many calls in one message; one reply per call, in order; when a call
//                                 at a critical position fails, the later ones are not run (their replies
//                                 say so): a client sends a frame's begin with its block's calls. With
//                                 between_frames true, the calls may use objects outside a frame without
//                                 ticking the world (the inspector's view of a paused simulation)
//   echo {value}                  returns value (diagnostics; measures the transport alone)
//   inspect {port}                starts the browser inspector on a TCP port of loopback (0: a free one) if
//   it
//                                 does not run; returns its address with the token ("http://...?token=...")
//   shutdown                      stop the server after replying
// Any request may also carry "reply_buffers" and "dropped_buffers" (see Session).

#include <msgpack.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/engine/engine.h"
#include "core/rpc/request.h"
#include "core/rpc/shared_memory.h"
#include "core/rpc/value_msgpack.h"

namespace sp::rpc {

struct Session {
    bool greeted = false;
    bool closeAfterReply = false;
    bool shutdownRequested = false;
    // A hello gave a wrong token (the server counts these per peer, to slow down guessing).
    bool tokenRefused = false;
    // A request's "reply_buffers" ([[name, size], ...]) and "dropped_buffers" ([name, ...]): the client's
    // shared-memory buffers for large reply arrays (core/rpc/reply_buffers.h).
    std::function<void(const std::string& name, size_t size)> offerReplyBuffer;
    std::function<void(const std::string& name)> dropReplyBuffer;
    // The client's pid when the kernel says it (Unix socket), else -1: only its segments are argument arrays.
    long peerPid = -1;
    // Whether large reply arrays may travel through the server's shared memory: only once the client showed
    // that it can map the server's segments (shm_proof), so that a client on another host, or with a /dev/shm
    // of its own, gets them inline in the reply instead of a segment name it cannot open.
    bool sharedMemoryReplies = false;
    // The inspector's connections (a browser, over WebSocket): hello must give requiredToken whatever the
    // server's own token (a Unix socket server has none), and no shared-memory probe is offered.
    bool browser = false;
    std::string requiredToken;
    // The segment hello named and the nonce it holds, until the proof (or the end of the session) removes it.
    std::shared_ptr<SharedMemorySegment> probe;
    std::string probeNonce;
};

// 128 random bits from the system's source, in hex: a shared-memory probe's nonce, the inspector's token
// where the server has none.
std::string randomSecret();

// Whether `given` is `secret` (never when `secret` is empty), compared in time that depends on the lengths
// only, not on how many leading characters of a guess are right.
bool sameSecret(const std::string& given, const std::string& secret);

// An error reply {"id": id (nil without one), "error": [type, message]}, `type` a spear.errors class name.
void packError(msgpack::packer<msgpack::sbuffer>& out, const msgpack::object* id, const char* type,
               const std::string& message);

class Dispatcher {
  public:
    Dispatcher(engine::Engine& engine, std::string apiHash, std::string token)
        : engine_(engine), apiHash_(std::move(apiHash)), token_(std::move(token)) {}

    // Handles one encoded request and appends the encoded reply to `reply`. Never throws: malformed
    // input becomes an error reply (and, before a successful hello, closes the session).
    // `tail`: the raw bytes after the message in a frame that has them (kTailFlag), where its large
    // arguments are; nullptr for a frame without.
    void handle(const char* data, size_t size, Session& session, msgpack::sbuffer& reply,
                const ArrayToSharedMemory& toShm, const std::string_view* tail = nullptr);
    // The client of `session` is gone: a frame it left open is aborted, so that other clients can go on.
    void endSession(Session& session);
    // The session whose frame is open (it began it and has not ended it), or nullptr.
    const Session* frameOwner() const { return frameOwner_; }

    // Which libraries load_plugin may open. Loading runs the library's code (its static constructors run
    // inside dlopen(), before any check that it is a plugin), so a client that could name any file could run
    // any code as the server's user. Unless `allowAny`, only the libraries at `allowed` (canonical paths: the
    // plugins the server was started with) and those found by name in the server's own SPEAR_PLUGIN_PATH are
    // loaded. Nothing is allowed until this is called.
    void setPluginPolicy(bool allowAny, std::vector<std::string> allowed) {
        allowAnyPlugin_ = allowAny;
        allowedPlugins_ = std::move(allowed);
    }
    // What the inspect op runs: starts the inspector on a port and returns its address with the token (the
    // server's Server::openInspector). Without one, inspect is refused.
    void setInspectHook(std::function<std::string(int port)> hook) { inspectHook_ = std::move(hook); }

    // Every op the dispatcher answers (its routes, hello and batch); a test holds it to protocol.json's.
    static std::vector<std::string_view> handledOps();

  private:
    // Runs a parsed request (not a batch): hello, or, once greeted, the op's handler from routes().
    reflect::Value execute(const Request& request, Session& session);
    using Handler = reflect::Value (Dispatcher::*)(const Request&, Session&);
    struct Route {
        std::string_view op;
        Handler handler;
    };
    static const std::vector<Route>& routes(); // every op but hello and batch
    reflect::Value hello(const Request& request, Session& session);
    reflect::Value world(const Request& request, Session& session);
    reflect::Value worlds(const Request& request, Session& session);
    reflect::Value frame(const Request& request, Session& session);
    reflect::Value call(const Request& request, Session& session);
    reflect::Value property(const Request& request, Session& session);
    reflect::Value loadPlugin(const Request& request, Session& session);
    reflect::Value unloadPlugin(const Request& request, Session& session);
    reflect::Value spFunc(const Request& request, Session& session);
    reflect::Value spFuncNames(const Request& request, Session& session);
    reflect::Value objectQuery(const Request& request, Session& session);
    reflect::Value echo(const Request& request, Session& session);
    reflect::Value shmProof(const Request& request, Session& session);
    reflect::Value shutdown(const Request& request, Session& session);
    reflect::Value inspect(const Request& request, Session& session);

    static void readReplyBuffers(const msgpack::object& request, Session& session);
    // Handles one request (or batch), appending its reply; false when the reply is an error.
    bool handleOne(const msgpack::object& message, Session& session, msgpack::sbuffer& reply,
                   const ArrayToSharedMemory& toShm, bool inBatch = false);

    engine::Engine& engine_;
    std::string apiHash_;
    std::string token_;
    bool allowAnyPlugin_ = false;
    std::vector<std::string> allowedPlugins_;
    // The file load_plugin may open for `pathOrName` (see setPluginPolicy); throws InvalidState otherwise.
    std::string allowedPlugin(const std::string& pathOrName) const;
    const Session* frameOwner_ = nullptr; // the session that last moved the open frame
    std::function<std::string(int)> inspectHook_;
};

} // namespace sp::rpc
