#pragma once
// The inspector's transport: just enough HTTP/1.1 and WebSocket (RFC 6455) for a browser on loopback to load
// the inspector page and then speak spear's own RPC protocol. A WebSocket message carries the same bytes as
// the socket transport (a length word, then msgpack; see value_msgpack.h), so the server, the dispatcher and
// the generated TypeScript client share one protocol, and a browser is one more client of the server.
//
// Pure functions over byte buffers (no sockets): the server (server.cpp) feeds them what it read, and the
// tests drive them with hand-made frames.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace sp::rpc::web {

// SHA-1 (FIPS 180-4) and base64, for the handshake's Sec-WebSocket-Accept only (not for secrets).
std::array<uint8_t, 20> sha1(std::string_view data);
std::string base64(std::string_view data);
// The Sec-WebSocket-Accept value for a client's Sec-WebSocket-Key.
std::string acceptKey(std::string_view clientKey);

struct HttpRequest {
    std::string method;
    std::string path;                           // percent-decoded, without the query
    std::string query;                          // as sent, without the '?'
    std::map<std::string, std::string> headers; // names lower-cased, values trimmed
    std::string header(const std::string& name) const;
};

// Request heads larger than this are refused: a browser's are a few hundred bytes.
inline constexpr size_t kMaxRequestHead = 16 * 1024;

// Parses the request head at the start of `buffer` (through its blank line), setting `consumed` to its
// length; nullopt while the head is incomplete. Throws InvalidArgument for a malformed or oversized head.
std::optional<HttpRequest> parseRequest(std::string_view buffer, size_t& consumed);

// The value of `name` in a query string ("a=1&token=x"), percent-decoded; "" when absent.
std::string queryParameter(std::string_view query, std::string_view name);

// A complete response; `extraHeaders` is a list of "Name: value\r\n" lines.
std::string response(int status, std::string_view reason, std::string_view contentType, std::string_view body,
                     std::string_view extraHeaders = {});
// The 101 response that switches a connection to WebSocket, for the client's Sec-WebSocket-Key.
std::string upgradeResponse(std::string_view clientKey);
// Whether `request` asks for a WebSocket upgrade (GET with Upgrade: websocket and a key).
bool isUpgrade(const HttpRequest& request);

enum Opcode : uint8_t { kContinuation = 0, kText = 1, kBinary = 2, kClose = 8, kPing = 9, kPong = 10 };

struct Frame {
    bool fin = false;
    uint8_t opcode = 0;
    std::string payload; // unmasked
};

// Decodes one client frame from the start of `buffer` into `frame`; returns the bytes it took, or 0 while the
// frame is incomplete. Throws InvalidArgument for what RFC 6455 says must fail the connection: an unmasked
// client frame, reserved bits, an unknown opcode, a fragmented or oversized control frame, or a payload past
// `maxPayload`.
size_t decodeFrame(std::string_view buffer, size_t maxPayload, Frame& frame);
// The header of an unmasked server frame (final, no extensions) carrying `size` bytes of payload.
std::string frameHeader(Opcode opcode, uint64_t size);

} // namespace sp::rpc::web
