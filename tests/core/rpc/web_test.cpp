#include "core/rpc/web.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/base/error.h"

namespace sp::rpc::web {
namespace {

std::string hex(const std::array<uint8_t, 20>& digest) {
    std::string out;
    char byte[3];
    for (uint8_t value : digest) {
        std::snprintf(byte, sizeof(byte), "%02x", value);
        out += byte;
    }
    return out;
}

// A client frame as a browser sends it: masked with `mask`.
std::string clientFrame(uint8_t firstByte, const std::string& payload,
                        const char mask[4] = "\x12\x34\x56\x78") {
    std::string frame(1, char(firstByte));
    if (payload.size() < 126)
        frame += char(0x80 | payload.size());
    else if (payload.size() <= 0xffff) {
        frame += char(0x80 | 126);
        frame += char(payload.size() >> 8);
        frame += char(payload.size() & 0xff);
    } else {
        frame += char(0x80 | 127);
        for (int i = 7; i >= 0; --i)
            frame += char((uint64_t(payload.size()) >> (8 * i)) & 0xff);
    }
    frame.append(mask, 4);
    for (size_t i = 0; i < payload.size(); ++i)
        frame += char(payload[i] ^ mask[i % 4]);
    return frame;
}

TEST(Web, Sha1MatchesTheStandardsVectors) {
    EXPECT_EQ(hex(sha1("abc")), "a9993e364706816aba3e25717850c26c9cd0d89d");
    EXPECT_EQ(hex(sha1("")), "da39a3ee5e6b4b0d3255bfef95601890afd80709");
    // Two blocks: the padding spills into a second one.
    EXPECT_EQ(hex(sha1("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
              "84983e441c3bd26ebaae4aa1f95129e5e54670f1");
}

TEST(Web, Base64PadsAsTheRfcSays) {
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

TEST(Web, AcceptKeyIsRfc6455sExample) {
    EXPECT_EQ(acceptKey("dGhlIHNhbXBsZSBub25jZQ=="), "s3pPLMBiTxaQ9kYGzzhZRbK+xOo=");
}

TEST(Web, ParsesARequestHeadOnceItIsComplete) {
    const std::string head = "GET /index.html?token=a%2Bb&x=1 HTTP/1.1\r\nHost: 127.0.0.1:8080\r\n"
                             "Upgrade:  websocket \r\nConnection: keep-alive, Upgrade\r\n"
                             "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\nrest";
    size_t consumed = 0;
    EXPECT_FALSE(parseRequest(head.substr(0, 40), consumed).has_value());
    const auto request = parseRequest(head, consumed);
    ASSERT_TRUE(request.has_value());
    EXPECT_EQ(consumed, head.size() - 4);
    EXPECT_EQ(request->method, "GET");
    EXPECT_EQ(request->path, "/index.html");
    EXPECT_EQ(request->header("host"), "127.0.0.1:8080");
    EXPECT_EQ(request->header("upgrade"), "websocket");
    EXPECT_TRUE(isUpgrade(*request));
    EXPECT_EQ(queryParameter(request->query, "token"), "a+b");
    EXPECT_EQ(queryParameter(request->query, "x"), "1");
    EXPECT_EQ(queryParameter(request->query, "missing"), "");
}

TEST(Web, RefusesMalformedAndOversizedHeads) {
    size_t consumed = 0;
    EXPECT_THROW(parseRequest("NONSENSE\r\n\r\n", consumed), InvalidArgument);
    EXPECT_THROW(parseRequest("GET http://elsewhere/ HTTP/1.1\r\n\r\n", consumed), InvalidArgument);
    EXPECT_THROW(parseRequest("GET / HTTP/1.1\r\nno colon here\r\n\r\n", consumed), InvalidArgument);
    EXPECT_THROW(parseRequest(std::string(kMaxRequestHead + 1, 'a'), consumed), InvalidArgument);
    try {
        parseRequest("GET / SMTP\r\n\r\n", consumed);
        FAIL();
    } catch (const InvalidArgument& error) {
        EXPECT_STREQ(error.what(), "inspector: malformed request line 'GET / SMTP'");
    }
}

TEST(Web, ResponsesCarryTheirLengthAndNeverCache) {
    const std::string text = response(403, "Forbidden", "text/plain", "no");
    EXPECT_TRUE(text.starts_with("HTTP/1.1 403 Forbidden\r\n"));
    EXPECT_NE(text.find("Content-Length: 2\r\n"), std::string::npos);
    EXPECT_NE(text.find("Cache-Control: no-store\r\n"), std::string::npos);
    EXPECT_TRUE(text.ends_with("\r\n\r\nno"));
    EXPECT_NE(upgradeResponse("dGhlIHNhbXBsZSBub25jZQ==")
                  .find("Sec-WebSocket-Accept: s3pPLMBiTxaQ9kYGzzhZRbK+xOo="),
              std::string::npos);
}

TEST(Web, DecodesMaskedFramesOfEverySize) {
    for (const size_t size : {size_t(0), size_t(5), size_t(125), size_t(126), size_t(65535), size_t(70000)}) {
        std::string payload(size, '\0');
        for (size_t i = 0; i < size; ++i)
            payload[i] = char(i * 7);
        const std::string bytes = clientFrame(0x82, payload) + "next";
        Frame frame;
        // Incomplete until the last payload byte is there.
        EXPECT_EQ(decodeFrame(std::string_view(bytes).substr(0, bytes.size() - 5), 1 << 20, frame), 0u)
            << size;
        EXPECT_EQ(decodeFrame(bytes, 1 << 20, frame), bytes.size() - 4) << size;
        EXPECT_TRUE(frame.fin);
        EXPECT_EQ(frame.opcode, kBinary);
        EXPECT_EQ(frame.payload, payload) << size;
    }
    Frame frame;
    EXPECT_EQ(decodeFrame(clientFrame(0x02, "ab"), 100, frame), 8u);
    EXPECT_FALSE(frame.fin); // the first of a fragmented message
}

TEST(Web, RefusesWhatMustFailTheConnection) {
    Frame frame;
    std::string unmasked = clientFrame(0x82, "abc");
    unmasked[1] = char(unmasked[1] & 0x7f);
    EXPECT_THROW(decodeFrame(unmasked, 100, frame), InvalidArgument);
    EXPECT_THROW(decodeFrame(clientFrame(0xc2, "abc"), 100, frame), InvalidArgument); // reserved bit
    EXPECT_THROW(decodeFrame(clientFrame(0x83, "abc"), 100, frame), InvalidArgument); // opcode 3
    EXPECT_THROW(decodeFrame(clientFrame(0x09, "abc"), 100, frame), InvalidArgument); // fragmented ping
    EXPECT_THROW(decodeFrame(clientFrame(0x89, std::string(126, 'a')), 1000, frame),
                 InvalidArgument); // big ping
    try {
        decodeFrame(clientFrame(0x82, std::string(200, 'a')), 100, frame);
        FAIL();
    } catch (const InvalidArgument& error) {
        EXPECT_STREQ(error.what(), "inspector: a WebSocket frame of 200 bytes (at most 100)");
    }
}

TEST(Web, ServerFrameHeadersUseTheShortestLength) {
    EXPECT_EQ(frameHeader(kBinary, 5), std::string("\x82\x05", 2));
    EXPECT_EQ(frameHeader(kBinary, 300), std::string("\x82\x7e\x01\x2c", 4));
    EXPECT_EQ(frameHeader(kClose, 0), std::string("\x88\x00", 2));
    const std::string large = frameHeader(kBinary, 70000);
    ASSERT_EQ(large.size(), 10u);
    EXPECT_EQ(uint8_t(large[1]), 127);
    EXPECT_EQ(uint8_t(large[7]), 0x01);
    EXPECT_EQ(uint8_t(large[8]), 0x11);
    EXPECT_EQ(uint8_t(large[9]), 0x70);
}

TEST(Web, ArbitraryBytesAreRefusedOrParsedNeverMisread) {
    // What a hostile peer sends before any token is checked: random heads and frames, and mutations of valid
    // ones.
    std::mt19937 random(7);
    const std::string head =
        "GET /?token=x HTTP/1.1\r\nHost: a\r\nUpgrade: websocket\r\nSec-WebSocket-Key: k\r\n\r\n";
    const std::string valid = clientFrame(0x82, std::string(300, 'p'));
    for (int round = 0; round < 20000; ++round) {
        std::string bytes = round % 2 ? head : valid;
        for (int flips = int(random() % 4); flips >= 0; --flips)
            bytes[random() % bytes.size()] = char(random());
        if (round % 7 == 0)
            bytes.resize(random() % (bytes.size() + 1));
        size_t consumed = 0;
        try {
            if (auto request = parseRequest(bytes, consumed)) {
                EXPECT_LE(consumed, bytes.size());
            }
        } catch (const InvalidArgument&) {
        }
        Frame frame;
        try {
            const size_t taken = decodeFrame(bytes, 1 << 16, frame);
            EXPECT_LE(taken, bytes.size());
            if (taken > 0) {
                EXPECT_LE(frame.payload.size(), taken);
            }
        } catch (const InvalidArgument&) {
        }
    }
}

} // namespace
} // namespace sp::rpc::web
