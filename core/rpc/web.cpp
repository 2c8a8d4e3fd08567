#include "core/rpc/web.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/base/error.h"

namespace sp::rpc::web {

namespace {
uint32_t rotl(uint32_t value, int bits) {
    return (value << bits) | (value >> (32 - bits));
}

int hexDigit(char c) {
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

std::string percentDecode(std::string_view text, bool plusIsSpace) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size() && hexDigit(text[i + 1]) >= 0 &&
            hexDigit(text[i + 2]) >= 0) {
            out += char(hexDigit(text[i + 1]) * 16 + hexDigit(text[i + 2]));
            i += 2;
        } else if (plusIsSpace && text[i] == '+')
            out += ' ';
        else
            out += text[i];
    }
    return out;
}

std::string_view trim(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t'))
        text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t'))
        text.remove_suffix(1);
    return text;
}

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

// Whether the comma-separated header value `list` holds `token`, case-insensitively ("keep-alive, Upgrade").
bool listHas(std::string_view list, std::string_view token) {
    const std::string wanted = lower(token);
    while (!list.empty()) {
        const size_t comma = list.find(',');
        if (lower(trim(list.substr(0, comma))) == wanted)
            return true;
        if (comma == std::string_view::npos)
            break;
        list.remove_prefix(comma + 1);
    }
    return false;
}
} // namespace

std::array<uint8_t, 20> sha1(std::string_view data) {
    uint32_t h[5] = {0x67452301u, 0xEFCDAB89u, 0x98BADCFEu, 0x10325476u, 0xC3D2E1F0u};
    // The message, a 1 bit, zeros up to 56 mod 64 bytes, then its length in bits (big endian).
    std::string message(data);
    message += char(0x80);
    while (message.size() % 64 != 56)
        message += char(0);
    const uint64_t bits = uint64_t(data.size()) * 8;
    for (int i = 7; i >= 0; --i)
        message += char((bits >> (8 * i)) & 0xff);
    for (size_t block = 0; block < message.size(); block += 64) {
        uint32_t w[80];
        for (int t = 0; t < 16; ++t) {
            const auto* p = reinterpret_cast<const unsigned char*>(message.data() + block + 4 * t);
            w[t] = uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
        }
        for (int t = 16; t < 80; ++t)
            w[t] = rotl(w[t - 3] ^ w[t - 8] ^ w[t - 14] ^ w[t - 16], 1);
        uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4];
        for (int t = 0; t < 80; ++t) {
            uint32_t f, k;
            if (t < 20) {
                f = (b & c) | (~b & d);
                k = 0x5A827999u;
            } else if (t < 40) {
                f = b ^ c ^ d;
                k = 0x6ED9EBA1u;
            } else if (t < 60) {
                f = (b & c) | (b & d) | (c & d);
                k = 0x8F1BBCDCu;
            } else {
                f = b ^ c ^ d;
                k = 0xCA62C1D6u;
            }
            const uint32_t next = rotl(a, 5) + f + e + k + w[t];
            e = d;
            d = c;
            c = rotl(b, 30);
            b = a;
            a = next;
        }
        h[0] += a;
        h[1] += b;
        h[2] += c;
        h[3] += d;
        h[4] += e;
    }
    std::array<uint8_t, 20> digest{};
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 4; ++j)
            digest[size_t(4 * i + j)] = uint8_t(h[i] >> (24 - 8 * j));
    return digest;
}

std::string base64(std::string_view data) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((data.size() + 2) / 3 * 4);
    for (size_t i = 0; i < data.size(); i += 3) {
        const size_t n = std::min<size_t>(3, data.size() - i);
        uint32_t group = 0;
        for (size_t j = 0; j < 3; ++j)
            group = group << 8 | (j < n ? uint8_t(data[i + j]) : 0u);
        for (size_t j = 0; j < 4; ++j)
            out += j <= n ? kAlphabet[(group >> (18 - 6 * j)) & 63] : '=';
    }
    return out;
}

std::string acceptKey(std::string_view clientKey) {
    // RFC 6455 section 4.2.2: the key with this GUID appended, hashed, in base64.
    const auto digest = sha1(std::string(clientKey) + "258EAFA5-E914-47DA-95CA-C5AB0DC85B11");
    return base64(std::string_view(reinterpret_cast<const char*>(digest.data()), digest.size()));
}

std::string HttpRequest::header(const std::string& name) const {
    const auto found = headers.find(name);
    return found == headers.end() ? std::string() : found->second;
}

std::optional<HttpRequest> parseRequest(std::string_view buffer, size_t& consumed) {
    const size_t end = buffer.find("\r\n\r\n");
    if (end == std::string_view::npos) {
        SP_CHECK(buffer.size() <= kMaxRequestHead, InvalidArgument, "inspector: a request head past ",
                 kMaxRequestHead, " bytes");
        return std::nullopt;
    }
    SP_CHECK(end + 4 <= kMaxRequestHead, InvalidArgument, "inspector: a request head of ", end + 4,
             " bytes (at most ", kMaxRequestHead, ")");
    consumed = end + 4;
    std::string_view head = buffer.substr(0, end);
    const size_t lineEnd = head.find("\r\n");
    const std::string_view line = head.substr(0, lineEnd);
    const size_t firstSpace = line.find(' ');
    const size_t secondSpace =
        firstSpace == std::string_view::npos ? firstSpace : line.find(' ', firstSpace + 1);
    SP_CHECK(secondSpace != std::string_view::npos && line.substr(secondSpace + 1).starts_with("HTTP/1."),
             InvalidArgument, "inspector: malformed request line '", line.substr(0, 200), "'");
    HttpRequest request;
    request.method = std::string(line.substr(0, firstSpace));
    const std::string_view target = line.substr(firstSpace + 1, secondSpace - firstSpace - 1);
    SP_CHECK(target.starts_with('/'), InvalidArgument, "inspector: request target '", target.substr(0, 200),
             "' is not a path");
    const size_t question = target.find('?');
    request.path = percentDecode(target.substr(0, question), false);
    if (question != std::string_view::npos)
        request.query = std::string(target.substr(question + 1));
    head = lineEnd == std::string_view::npos ? std::string_view() : head.substr(lineEnd + 2);
    while (!head.empty()) {
        const size_t next = head.find("\r\n");
        const std::string_view field = head.substr(0, next);
        const size_t colon = field.find(':');
        SP_CHECK(colon != std::string_view::npos && colon > 0, InvalidArgument,
                 "inspector: malformed header '", field.substr(0, 200), "'");
        request.headers[lower(trim(field.substr(0, colon)))] = std::string(trim(field.substr(colon + 1)));
        head = next == std::string_view::npos ? std::string_view() : head.substr(next + 2);
    }
    return request;
}

std::string queryParameter(std::string_view query, std::string_view name) {
    while (!query.empty()) {
        const size_t amp = query.find('&');
        const std::string_view pair = query.substr(0, amp);
        const size_t equals = pair.find('=');
        if (percentDecode(pair.substr(0, equals), true) == name)
            return equals == std::string_view::npos ? std::string()
                                                    : percentDecode(pair.substr(equals + 1), true);
        if (amp == std::string_view::npos)
            break;
        query.remove_prefix(amp + 1);
    }
    return {};
}

std::string response(int status, std::string_view reason, std::string_view contentType, std::string_view body,
                     std::string_view extraHeaders) {
    std::string out = "HTTP/1.1 " + std::to_string(status) + " " + std::string(reason) + "\r\n";
    out += "Content-Type: " + std::string(contentType) + "\r\n";
    out += "Content-Length: " + std::to_string(body.size()) + "\r\n";
    // The page is the engine's, live: never from a cache; and never framed by another site's page.
    out += "Cache-Control: no-store\r\nX-Frame-Options: DENY\r\nX-Content-Type-Options: nosniff\r\n";
    out += "Connection: close\r\n";
    out += extraHeaders;
    out += "\r\n";
    out += body;
    return out;
}

bool isUpgrade(const HttpRequest& request) {
    return request.method == "GET" && listHas(request.header("upgrade"), "websocket") &&
           !request.header("sec-websocket-key").empty();
}

std::string upgradeResponse(std::string_view clientKey) {
    return "HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
           "Sec-WebSocket-Accept: " +
           acceptKey(clientKey) + "\r\n\r\n";
}

size_t decodeFrame(std::string_view buffer, size_t maxPayload, Frame& frame) {
    if (buffer.size() < 2)
        return 0;
    const auto byte = [&](size_t i) { return uint8_t(buffer[i]); };
    const bool fin = byte(0) & 0x80;
    const uint8_t opcode = byte(0) & 0x0f;
    SP_CHECK((byte(0) & 0x70) == 0, InvalidArgument, "inspector: a WebSocket frame with reserved bits set");
    SP_CHECK(opcode <= kBinary || (opcode >= kClose && opcode <= kPong), InvalidArgument,
             "inspector: a WebSocket frame with unknown opcode ", int(opcode));
    SP_CHECK(byte(1) & 0x80, InvalidArgument, "inspector: an unmasked WebSocket frame from a client");
    uint64_t size = byte(1) & 0x7f;
    size_t at = 2;
    if (size == 126) {
        if (buffer.size() < 4)
            return 0;
        size = uint64_t(byte(2)) << 8 | byte(3);
        at = 4;
    } else if (size == 127) {
        if (buffer.size() < 10)
            return 0;
        size = 0;
        for (size_t i = 2; i < 10; ++i)
            size = size << 8 | byte(i);
        at = 10;
    }
    if (opcode >= kClose)
        SP_CHECK(fin && size <= 125, InvalidArgument,
                 "inspector: a fragmented or oversized WebSocket control frame");
    SP_CHECK(size <= maxPayload, InvalidArgument, "inspector: a WebSocket frame of ", size,
             " bytes (at most ", maxPayload, ")");
    if (buffer.size() < at + 4 + size)
        return 0;
    const char* mask = buffer.data() + at;
    at += 4;
    frame.fin = fin;
    frame.opcode = opcode;
    frame.payload.assign(buffer.data() + at, size_t(size));
    for (size_t i = 0; i < frame.payload.size(); ++i)
        frame.payload[i] = char(frame.payload[i] ^ mask[i % 4]);
    return at + size_t(size);
}

std::string frameHeader(Opcode opcode, uint64_t size) {
    std::string header(1, char(0x80 | opcode));
    if (size < 126)
        header += char(size);
    else if (size <= 0xffff) {
        header += char(126);
        header += char(size >> 8);
        header += char(size & 0xff);
    } else {
        header += char(127);
        for (int i = 7; i >= 0; --i)
            header += char((size >> (8 * i)) & 0xff);
    }
    return header;
}

} // namespace sp::rpc::web
