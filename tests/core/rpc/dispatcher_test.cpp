#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/rpc/dispatcher.h"
#include "generated/rpc/cpp/protocol.gen.h"

using sp::engine::Engine;
using sp::rpc::Dispatcher;
using sp::rpc::Session;
namespace protocol = sp::rpc::protocol;

namespace {
// {"op": op, key: value, ...} with string values.
std::string request(const std::string& op, const std::map<std::string, std::string>& fields = {}) {
    msgpack::sbuffer out;
    msgpack::packer<msgpack::sbuffer> packer(&out);
    packer.pack_map(uint32_t(fields.size() + 1));
    packer.pack(std::string("op"));
    packer.pack(op);
    for (const auto& [key, value] : fields) {
        packer.pack(key);
        packer.pack(value);
    }
    return std::string(out.data(), out.size());
}

// The reply's error message, or "" for a success.
std::string send(Dispatcher& dispatcher, Session& session, const std::string& message) {
    msgpack::sbuffer reply;
    dispatcher.handle(message.data(), message.size(), session, reply, nullptr);
    msgpack::object_handle handle = msgpack::unpack(reply.data(), reply.size());
    const msgpack::object& map = handle.get();
    for (uint32_t i = 0; i < map.via.map.size; ++i)
        if (map.via.map.ptr[i].key.as<std::string>() == "error")
            return map.via.map.ptr[i].val.via.array.ptr[1].as<std::string>();
    return "";
}

struct Fixture : testing::Test {
    Engine engine;
    Dispatcher dispatcher{engine, "hash", ""};
    Session greeted() {
        Session session;
        EXPECT_EQ(send(dispatcher, session, request("hello", {{"api_hash", "hash"}})), "");
        return session;
    }
};
using DispatcherTest = Fixture;
} // namespace

TEST_F(DispatcherTest, AFrameLeftOpenByAClientThatWentAwayIsAborted) {
    Session a = greeted();
    Session b = greeted();
    ASSERT_EQ(send(dispatcher, a, request("frame", {{"action", "begin"}})), "");
    EXPECT_NE(send(dispatcher, b, request("frame", {{"action", "begin"}})).find("expected idle"),
              std::string::npos);
    dispatcher.endSession(a); // a was killed mid-frame
    EXPECT_EQ(engine.GetFrameState(), Engine::FrameState::Idle);
    for (const char* action : {"begin", "execute", "begin_end", "end"})
        EXPECT_EQ(send(dispatcher, b, request("frame", {{"action", action}})), "") << action;
    EXPECT_EQ(engine.GetFrameCount(), 2); // a's frame ended with its tick, then b's
}

TEST_F(DispatcherTest, OnlyTheFramesOwnerAbortsIt) {
    Session a = greeted();
    Session b = greeted();
    ASSERT_EQ(send(dispatcher, b, request("frame", {{"action", "begin"}})), "");
    dispatcher.endSession(a); // a never touched the frame
    EXPECT_EQ(engine.GetFrameState(), Engine::FrameState::BeginFrame);
}

TEST_F(DispatcherTest, BatchesDoNotNest) {
    Session a = greeted();
    // 20,000 nested batches in 340 KB: each was a C++ stack frame before batches were kept flat.
    std::string message;
    for (int i = 0; i < 20000; ++i)
        message += "\x82\xa2op\xa5"
                   "batch\xa5"
                   "calls\x91";
    message += request("echo");
    msgpack::sbuffer reply;
    dispatcher.handle(message.data(), message.size(), a, reply, nullptr);
    // The outer batch answers; the batch inside it is refused.
    EXPECT_NE(std::string(reply.data(), reply.size()).find("batch(): a batch may not contain a batch"),
              std::string::npos);
    EXPECT_EQ(send(dispatcher, a, request("echo")), "");
}

TEST_F(DispatcherTest, OnlyScalarIdsAreEchoed) {
    Session a = greeted();
    // {"id": [[[...]]] 20,000 deep, "op": "echo"}: packing the id back recursed once per level.
    const std::string message =
        "\x82\xa2id" + std::string(20000, '\x91') + "\xc0" + request("echo").substr(1);
    EXPECT_EQ(send(dispatcher, a, message), "");
}

TEST_F(DispatcherTest, ABatchRunsNothingAfterAFailedCriticalCall) {
    // {"op": "batch", "critical": critical, "calls": [{"op": "frame", "action": a}, ...]}
    auto frameBatch = [](const std::vector<int>& critical, const std::vector<std::string>& actions) {
        msgpack::sbuffer out;
        msgpack::packer<msgpack::sbuffer> packer(&out);
        packer.pack_map(3);
        packer.pack(std::string("op"));
        packer.pack(std::string("batch"));
        packer.pack(std::string("critical"));
        packer.pack(critical);
        packer.pack(std::string("calls"));
        packer.pack_array(uint32_t(actions.size()));
        for (const std::string& action : actions)
            packer.pack(std::map<std::string, std::string>{{"op", "frame"}, {"action", action}});
        return std::string(out.data(), out.size());
    };
    // A client sends a frame's begin with the calls of its block and the frame's execution: when the begin
    // fails (here: a frame is open already), the execution must not run the frame that was open.
    Session session = greeted();
    ASSERT_EQ(send(dispatcher, session, request("frame", {{"action", "begin"}})), "");
    const std::string message = frameBatch({0}, {"begin", "execute"});
    msgpack::sbuffer reply;
    dispatcher.handle(message.data(), message.size(), session, reply, nullptr);
    const std::string text(reply.data(), reply.size());
    EXPECT_NE(text.find("begin_frame(): "), std::string::npos) << "the begin's own error";
    EXPECT_NE(text.find("batch(): not run: call 0 of the batch failed"), std::string::npos);
    EXPECT_EQ(engine.GetFrameState(), Engine::FrameState::BeginFrame) << "the open frame was not executed";
    EXPECT_EQ(engine.GetFrameCount(), 0);
    EXPECT_NE(send(dispatcher, session, frameBatch({5}, {})).find("names call positions below 0"),
              std::string::npos);
}

TEST_F(DispatcherTest, ABrowsersHelloNeedsTheInspectorsTokenWhereTheServerHasNone) {
    // A Unix socket server has no token of its own; its inspector's connections still need theirs.
    Session wrong;
    wrong.browser = true;
    wrong.requiredToken = "secret";
    EXPECT_EQ(send(dispatcher, wrong, request("hello", {{"api_hash", "hash"}, {"token", "guess"}})),
              "hello(): wrong or missing token");
    EXPECT_TRUE(wrong.closeAfterReply);
    EXPECT_TRUE(wrong.tokenRefused);
    Session missing;
    missing.browser = true;
    missing.requiredToken = "secret";
    EXPECT_EQ(send(dispatcher, missing, request("hello", {{"api_hash", "hash"}})),
              "hello(): wrong or missing token");
    Session right;
    right.browser = true;
    right.requiredToken = "secret";
    EXPECT_EQ(send(dispatcher, right, request("hello", {{"api_hash", "hash"}, {"token", "secret"}})), "");
    EXPECT_TRUE(right.greeted);
    EXPECT_EQ(right.probe, nullptr); // a browser maps no shared memory: no probe was made for it
}

TEST_F(DispatcherTest, BetweenFramesMustBeABool) {
    Session a = greeted();
    msgpack::sbuffer out;
    msgpack::packer<msgpack::sbuffer> packer(&out);
    packer.pack_map(3);
    packer.pack(std::string("op"));
    packer.pack(std::string("batch"));
    packer.pack(std::string("calls"));
    packer.pack_array(0);
    packer.pack(std::string("between_frames"));
    packer.pack(1);
    EXPECT_EQ(send(dispatcher, a, std::string(out.data(), out.size())),
              "batch(): 'between_frames' must be a bool");
}

// The ops the dispatcher answers are exactly those of core/rpc/protocol.json, from which the Python and
// TypeScript clients' request types are generated: an op added to one and not the other fails here.
TEST(DispatcherProtocolTest, AnswersExactlyTheOpsOfTheProtocolSource) {
    std::vector<std::string_view> handled = Dispatcher::handledOps();
    std::vector<std::string_view> declared(protocol::kOps.begin(), protocol::kOps.end());
    std::sort(handled.begin(), handled.end());
    std::sort(declared.begin(), declared.end());
    EXPECT_EQ(handled, declared);
    EXPECT_EQ(std::adjacent_find(handled.begin(), handled.end()), handled.end()) << "an op routed twice";
}
