// The inspector's side of the server: its listening port, the page over HTTP, WebSocket framing around the
// socket transport's bytes, and the log lines and progress sent to the browsers watching (web.h, server.h).

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/progress.h"
#include "core/rpc/server_connection.h"
#include "core/rpc/web.h"
#include "generated/rpc/cpp/protocol.gen.h"

namespace sp::rpc {

namespace detail {
// A TCP socket bound to address:port (0: a free one, written to boundPort).
int listenTcp(const std::string& bindAddress, int port, int& boundPort) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    SP_CHECK(fd >= 0, Error, "spear-server: socket failed: ", std::strerror(errno));
    int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(uint16_t(port));
    if (::inet_pton(AF_INET, bindAddress.c_str(), &address.sin_addr) != 1) {
        ::close(fd);
        SP_THROW(InvalidArgument, "spear-server: bad bind address '", bindAddress, "'");
    }
    if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
        const int error = errno;
        ::close(fd);
        SP_THROW(Error, "spear-server: cannot bind ", bindAddress, ":", port, ": ", std::strerror(error));
    }
    socklen_t length = sizeof(address);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
    boundPort = ntohs(address.sin_port);
    return fd;
}
} // namespace detail

std::string Server::openInspector(int port) {
    if (inspectFd_ >= 0) {
        SP_CHECK(port == 0 || port == inspectBoundPort_, InvalidState,
                 "inspect(): the inspector already listens on ", inspectAddress(), "; it serves one port");
        return inspectUrl();
    }
    SP_CHECK(port >= 0 && port <= 65535, InvalidArgument, "inspect(): port must be in [0, 65535], got ",
             port);
    SP_CHECK(std::filesystem::is_regular_file(std::filesystem::path(options_.inspectRoot) / "index.html"),
             NotFound, "inspect(): no inspector page at '", options_.inspectRoot,
             "/index.html'; it is built with the engine when npm is present (bash run.sh installs it)");
    if (options_.inspectToken.empty())
        options_.inspectToken = options_.token.empty() ? randomSecret() : options_.token;
    inspectFd_ = detail::listenTcp(options_.bindAddress, port, inspectBoundPort_);
    broadcast_ = std::make_shared<Broadcast>();
    logListener_ = base::addLogListener(
        [broadcast = broadcast_](std::string_view file, int line, std::string_view message) {
            broadcast->log(file, line, message);
        });
    progressListener_ = base::addProgressListener(
        [broadcast = broadcast_](std::string_view task, double done, double total, bool finished) {
            broadcast->report(task, done, total, finished);
        });
    if (::listen(inspectFd_, 16) != 0) {
        const int error = errno;
        ::close(inspectFd_);
        inspectFd_ = -1;
        SP_THROW(Error, "inspect(): listen failed: ", std::strerror(error));
    }
    options_.inspectPort = inspectBoundPort_;
    return inspectUrl();
}

std::string Server::inspectUrl() const {
    return inspectFd_ < 0 ? std::string() : inspectAddress() + "?token=" + options_.inspectToken;
}

std::string Server::inspectAddress() const {
    if (inspectFd_ < 0)
        return {};
    return "http://" + options_.bindAddress + ":" + std::to_string(inspectBoundPort_) + "/";
}

bool Server::receiveWeb(Connection& connection, std::string_view bytes) {
    connection.webInput.append(bytes);
    if (connection.transport == Connection::Transport::Http)
        return serveHttp(connection);
    const size_t limit =
        connection.session.greeted ? options_.maxMessageBytes : options_.maxMessageBytesBeforeHello;
    size_t at = 0;
    try {
        web::Frame frame;
        while (!connection.closing) {
            const size_t taken =
                web::decodeFrame(std::string_view(connection.webInput).substr(at), limit + 4, frame);
            if (taken == 0)
                break;
            at += taken;
            if (frame.opcode == web::kBinary || frame.opcode == web::kContinuation) {
                // A message holds the socket transport's bytes, so frames are just the stream in pieces.
                connection.inbox += frame.payload;
            } else if (frame.opcode == web::kPing) {
                const std::string pong = web::frameHeader(web::kPong, frame.payload.size()) + frame.payload;
                if (!queueBytes(connection, pong.data(), pong.size()))
                    return false;
            } else if (frame.opcode == web::kClose) {
                const std::string close = web::frameHeader(web::kClose, 0);
                connection.closing = true; // dropped once the answer is out
                return queueBytes(connection, close.data(), close.size());
            } else if (frame.opcode == web::kText) {
                SP_LOG("spear-server: inspector: dropping a client that sent a text message (the protocol is "
                       "binary msgpack)");
                return false;
            } // pongs are ignored
        }
    } catch (const std::exception& error) {
        SP_LOG("spear-server: dropping an inspector client from ", connection.peer, ": ", error.what());
        return false;
    }
    connection.webInput.erase(0, at);
    return true;
}

bool Server::serveHttp(Connection& connection) {
    std::optional<web::HttpRequest> request;
    size_t consumed = 0;
    auto respond = [&](int status, std::string_view reason, std::string_view body) {
        const std::string bytes = web::response(status, reason, "text/plain; charset=utf-8", body);
        connection.closing = true;
        return queueBytes(connection, bytes.data(), bytes.size());
    };
    try {
        request = web::parseRequest(connection.webInput, consumed);
    } catch (const std::exception& error) {
        return respond(400, "Bad Request", error.what());
    }
    if (!request)
        return true; // the rest of the head is on its way
    connection.webInput.erase(0, consumed);
    if (request->method != "GET")
        return respond(405, "Method Not Allowed", "spear-server: inspector: only GET");
    if (web::isUpgrade(*request)) {
        // A page of another site may open a WebSocket to loopback too: only the inspector's own page may (a
        // browser always sends Origin; a client outside a browser sends none and must know the token anyway).
        const std::string origin = request->header("origin");
        if (!origin.empty() && origin != "http://" + request->header("host"))
            return respond(403, "Forbidden",
                           "spear-server: inspector: WebSocket from another origin ('" + origin + "')");
        const std::string bytes = web::upgradeResponse(request->header("sec-websocket-key"));
        connection.transport = Connection::Transport::WebSocket;
        ++broadcast_->browsers;
        if (!queueBytes(connection, bytes.data(), bytes.size()))
            return false;
        if (connection.webInput.empty())
            return true;
        std::string rest;
        rest.swap(connection.webInput); // frames sent right behind the handshake
        return receiveWeb(connection, rest);
    }
    std::string path = request->path == "/" ? "/index.html" : request->path;
    if (path == "/index.html") {
        // The page itself needs the token (?token=): it is what a user opens; the scripts it loads are the
        // same for everyone, and its WebSocket proves the token again in its hello.
        if (!sameSecret(web::queryParameter(request->query, "token"), options_.inspectToken)) {
            connection.heldUntil = std::chrono::steady_clock::now() + countTokenFailure(connection.peer);
            return respond(403, "Forbidden",
                           "spear-server: inspector: wrong or missing token; open the address spear-server "
                           "printed (http://.../?token=...)");
        }
    }
    // Only files under the inspector's folder, by a path without '..' or hidden names.
    const bool plain = path.find("/.") == std::string::npos && path.find('\\') == std::string::npos &&
                       path.find('\0') == std::string::npos;
    const std::filesystem::path file = std::filesystem::path(options_.inspectRoot) / path.substr(1);
    std::error_code error;
    if (!plain || !std::filesystem::is_regular_file(file, error) ||
        std::filesystem::file_size(file, error) > (size_t(16) << 20))
        return respond(404, "Not Found", "spear-server: inspector: no file '" + path.substr(0, 200) + "'");
    std::string body;
    {
        std::FILE* in = std::fopen(file.c_str(), "rb");
        if (!in)
            return respond(404, "Not Found",
                           "spear-server: inspector: cannot read '" + path.substr(0, 200) + "'");
        char chunk[65536];
        size_t n = 0;
        while ((n = std::fread(chunk, 1, sizeof(chunk), in)) > 0)
            body.append(chunk, n);
        std::fclose(in);
    }
    static const std::map<std::string, std::string> kTypes = {{".html", "text/html; charset=utf-8"},
                                                              {".js", "text/javascript; charset=utf-8"},
                                                              {".css", "text/css; charset=utf-8"},
                                                              {".map", "application/json"},
                                                              {".json", "application/json"},
                                                              {".png", "image/png"},
                                                              {".svg", "image/svg+xml"}};
    const auto type = kTypes.find(file.extension().string());
    const std::string bytes =
        web::response(200, "OK", type == kTypes.end() ? "application/octet-stream" : type->second, body);
    connection.closing = true;
    return queueBytes(connection, bytes.data(), bytes.size());
}

void Server::sendBroadcast() {
    std::vector<std::string> messages;
    {
        std::lock_guard lock(broadcast_->mutex);
        if (broadcast_->messages.empty() && broadcast_->progress.empty())
            return;
        messages.swap(broadcast_->messages);
        for (auto& [task, message] : broadcast_->progress)
            messages.push_back(std::move(message));
        broadcast_->progress.clear();
        if (broadcast_->dropped > 0) {
            messages.push_back(Broadcast::push(
                protocol::reply::kLog, std::string_view("server.cpp"), __LINE__,
                std::to_string(broadcast_->dropped) + " more log lines were not sent to the inspector"));
            broadcast_->dropped = 0;
        }
    }
    for (auto& connection : connections_)
        if (connection->fd >= 0 && connection->transport == Connection::Transport::WebSocket &&
            connection->session.greeted && !connection->closing)
            for (const std::string& message : messages)
                if (!queueReply(*connection, message.data(), message.size())) {
                    drop(*connection);
                    break;
                }
}

} // namespace sp::rpc
