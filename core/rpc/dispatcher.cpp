#include "core/rpc/dispatcher.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "core/base/error.h"
#include "core/plugin/plugin_loader.h"
#include "core/reflect/object_base.h"
#include "core/reflect/property_path.h"
#include "core/reflect/registry.h"
#include "core/reflect/type_info.h"
#include "core/rpc/request.h"
#include "core/rpc/shared_memory.h"
#include "core/spfunc/sp_func_call.h"
#include "core/world/object_access.h"
#include "generated/rpc/cpp/protocol.gen.h"

namespace sp::rpc {

using reflect::Value;

namespace {
constexpr size_t kSmallReply = 256;

reflect::ObjectBase& requireObject(const Request& request, std::string_view context) {
    Value handle = unpack(request.require(protocol::field::kObject, context), context);
    SP_CHECK(handle.is<reflect::ObjectHandle>(), InvalidArgument, context,
             ": 'object' must be an object reference");
    reflect::ObjectBase& object = reflect::ObjectTable::resolve(handle.as<reflect::ObjectHandle>(), context);
    world::checkObjectAccess(object, context);
    return object;
}

} // namespace

std::string randomSecret() {
    std::random_device random;
    std::string secret;
    for (int i = 0; i < 4; ++i) {
        char word[9];
        std::snprintf(word, sizeof(word), "%08x", unsigned(random()));
        secret += word;
    }
    return secret;
}

bool sameSecret(const std::string& given, const std::string& secret) {
    if (secret.empty())
        return false; // nothing to prove it against (and no length to compare in constant time)
    unsigned char difference = given.size() == secret.size() ? 0 : 1;
    for (size_t i = 0; i < given.size(); ++i)
        difference |= static_cast<unsigned char>(given[i] ^ secret[i % secret.size()]);
    return difference == 0;
}

void packError(msgpack::packer<msgpack::sbuffer>& out, const msgpack::object* id, const char* type,
               const std::string& message) {
    out.pack_map(2);
    out.pack(protocol::reply::kId);
    if (id)
        out.pack(*id);
    else
        out.pack_nil();
    out.pack(protocol::reply::kError);
    out.pack_array(2);
    out.pack(std::string(type));
    out.pack(message);
}

void Dispatcher::handle(const char* data, size_t size, Session& session, msgpack::sbuffer& reply,
                        const ArrayToSharedMemory& toShm, const std::string_view* tail) {
    msgpack::object_handle handle;
    try {
        handle = unpackBounded(data, size);
    } catch (const std::exception& e) {
        // Garbage or a truncated message: say so; a client that never said hello is dropped.
        std::string what = e.what();
        if (dynamic_cast<const msgpack::size_overflow*>(&e))
            what += ": a list, map, string or binary announces more than the message's " +
                    std::to_string(size) + " bytes can hold";
        msgpack::packer<msgpack::sbuffer> out(&reply);
        packError(out, nullptr, "InvalidArgumentError", "request: malformed message (" + what + ")");
        session.closeAfterReply = !session.greeted;
        return;
    }
    if (session.greeted)
        readReplyBuffers(handle.get(), session);
    OpenedSegments opened;
    OpenedSegmentsScope scope(opened);
    SegmentOwnerScope owner(session.peerPid);
    std::optional<RequestTailScope> tailScope;
    if (tail)
        tailScope.emplace(*tail);
    handleOne(handle.get(), session, reply, toShm);
}

void Dispatcher::readReplyBuffers(const msgpack::object& request, Session& session) {
    if (const msgpack::object* dropped = mapField(request, protocol::field::kDroppedBuffers);
        dropped && dropped->type == msgpack::type::ARRAY && session.dropReplyBuffer)
        for (uint32_t i = 0; i < dropped->via.array.size; ++i)
            if (const msgpack::object& name = dropped->via.array.ptr[i]; name.type == msgpack::type::STR)
                session.dropReplyBuffer(std::string(name.via.str.ptr, name.via.str.size));
    if (const msgpack::object* offered = mapField(request, protocol::field::kReplyBuffers);
        offered && offered->type == msgpack::type::ARRAY && session.offerReplyBuffer)
        for (uint32_t i = 0; i < offered->via.array.size; ++i) {
            const msgpack::object& pair = offered->via.array.ptr[i];
            if (pair.type != msgpack::type::ARRAY || pair.via.array.size != 2 ||
                pair.via.array.ptr[0].type != msgpack::type::STR ||
                pair.via.array.ptr[1].type != msgpack::type::POSITIVE_INTEGER)
                continue; // malformed offers are ignored: the reply then uses the server's own segments
            const msgpack::object& name = pair.via.array.ptr[0];
            session.offerReplyBuffer(std::string(name.via.str.ptr, name.via.str.size),
                                     size_t(pair.via.array.ptr[1].via.u64));
        }
}

std::string Dispatcher::allowedPlugin(const std::string& pathOrName) const {
    if (allowAnyPlugin_)
        return pathOrName;
    // Compared as canonical paths, so that "dir/../libx.so" or a link to an allowed library is that library,
    // and the canonical path is what is opened: the file checked is the file loaded.
    const std::string path = plugin::resolve(pathOrName);
    std::error_code error;
    const std::string canonical = std::filesystem::weakly_canonical(path, error).string();
    if (!error &&
        (std::find(allowedPlugins_.begin(), allowedPlugins_.end(), canonical) != allowedPlugins_.end() ||
         plugin::foundInSearchPath(canonical)))
        return canonical;
    SP_THROW(
        InvalidState, "load_plugin(): this server does not load '", pathOrName,
        "' for a client: it loads only the plugins named on its command line (--plugin) or found in its "
        "SPEAR_PLUGIN_PATH; start it with --plugin '",
        pathOrName,
        "', or with --allow-remote-plugin-load to let its clients load any library (its code runs in the "
        "server)");
}

void Dispatcher::endSession(Session& session) {
    // A client that began a frame and went away (killed, or disconnected) would leave the engine inside the
    // frame, and every other client refused ("expected idle") for good: its frame ends here, as a frame
    // whose Python block raised does.
    if (frameOwner_ == &session && engine_.GetFrameState() != engine::Engine::FrameState::Idle)
        engine_.abortFrame();
    if (frameOwner_ == &session)
        frameOwner_ = nullptr;
    if (session.probe)
        session.probe->unlink();
    session.probe.reset();
}

bool Dispatcher::handleOne(const msgpack::object& message, Session& session, msgpack::sbuffer& reply,
                           const ArrayToSharedMemory& toShm, bool inBatch) {
    const msgpack::object* id = mapField(message, protocol::field::kId);
    // The id is echoed as it came; packing a container recurses, so only a scalar is (a client's ids are
    // integers).
    if (id && (id->type == msgpack::type::ARRAY || id->type == msgpack::type::MAP))
        id = nullptr;
    // Built aside and appended whole: an error halfway through packing a result (a shared-memory segment
    // that cannot be made, say) becomes an error reply instead of a truncated one. Small at first: most
    // replies are a few bytes (msgpack-c's default is 8 KiB, allocated for each call of a batch).
    msgpack::sbuffer built(kSmallReply);
    msgpack::packer<msgpack::sbuffer> out(&built);
    try {
        const Request request(message);
        if (request.op() == protocol::op::kBatch) {
            SP_CHECK(session.greeted, InvalidState, "batch(): say hello first");
            // Each level of batch is a C++ stack frame: nested batches could overflow the stack.
            SP_CHECK(!inBatch, InvalidArgument, "batch(): a batch may not contain a batch");
            const msgpack::object& calls = request.require(protocol::field::kCalls, protocol::op::kBatch);
            SP_CHECK(calls.type == msgpack::type::ARRAY, InvalidArgument, "batch(): 'calls' must be a list");
            // Calls the rest of the batch depends on (a client sends a frame's begin with the calls of its
            // block): when one fails, the calls after it are not run, so that they cannot act on a frame
            // that was never begun (or on another client's).
            std::vector<bool> critical(calls.via.array.size, false);
            if (const msgpack::object* list = request.field(protocol::field::kCritical)) {
                SP_CHECK(list->type == msgpack::type::ARRAY, InvalidArgument,
                         "batch(): 'critical' must be a list of call positions");
                for (uint32_t i = 0; i < list->via.array.size; ++i) {
                    const msgpack::object& at = list->via.array.ptr[i];
                    SP_CHECK(at.type == msgpack::type::POSITIVE_INTEGER && at.via.u64 < critical.size(),
                             InvalidArgument, "batch(): 'critical' names call positions below ",
                             critical.size());
                    critical[at.via.u64] = true;
                }
            }
            // "between_frames": the calls may use engine objects outside a frame, without ticking the world
            // (the inspector, looking at a paused simulation; Engine::Inspection).
            std::optional<engine::Engine::Inspection> inspection;
            if (const msgpack::object* between = request.field(protocol::field::kBetweenFrames)) {
                SP_CHECK(between->type == msgpack::type::BOOLEAN, InvalidArgument,
                         "batch(): 'between_frames' must be a bool");
                if (between->via.boolean)
                    inspection.emplace(engine_);
            }
            out.pack_map(2);
            out.pack(protocol::reply::kId);
            id ? out.pack(*id) : out.pack_nil();
            out.pack(protocol::reply::kOk);
            out.pack_array(calls.via.array.size);
            int failedCritical = -1;
            for (uint32_t i = 0; i < calls.via.array.size; ++i) {
                if (failedCritical >= 0) {
                    const msgpack::object* callId = mapField(calls.via.array.ptr[i], protocol::field::kId);
                    const bool scalar =
                        callId && callId->type != msgpack::type::ARRAY && callId->type != msgpack::type::MAP;
                    packError(out, scalar ? callId : nullptr, "InvalidStateError",
                              "batch(): not run: call " + std::to_string(failedCritical) +
                                  " of the batch failed");
                    continue;
                }
                if (!handleOne(calls.via.array.ptr[i], session, built, toShm, true) && critical[i])
                    failedCritical = int(i);
            }
            reply.write(built.data(), built.size());
            return true;
        }
        OpenedSegments* opened = OpenedSegmentsScope::current();
        const size_t openedBefore = opened ? opened->size() : 0;
        const uint64_t faultsBefore = truncationFaults();
        Value result = execute(request, session);
        // {"id", "ok"}, and "kept" when the request's arrays stay with the engine: that is known only once
        // the result is packed and gone, so the map's header is written for two and corrected then.
        const size_t header = built.size();
        out.pack_map(2);
        out.pack(protocol::reply::kId);
        id ? out.pack(*id) : out.pack_nil();
        out.pack(protocol::reply::kOk);
        pack(out, result, toShm);
        // A segment shrank while this request read or wrote it: the server survived (shared_memory.h), but
        // what it read or wrote there is lost, so the request fails.
        std::string fallback;
        SP_CHECK(truncationFaults() == faultsBefore, InvalidArgument,
                 request.context(fallback, [&] { return std::string(request.op()) + "()"; }),
                 ": a shared-memory segment was truncated while the server used it; its contents are lost");
        result = Value(); // the request's values are gone now: what still maps a segment was kept
        std::vector<std::string> kept;
        for (size_t i = openedBefore; opened && i < opened->size(); ++i) {
            const OpenedSegment& entry = (*opened)[i];
            if (auto alive = entry.segment.lock(); alive && alive.use_count() - 1 > entry.othersHolding)
                kept.push_back(entry.name);
        }
        if (!kept.empty()) {
            built.data()[header] = char(0x83); // fixmap of 3 (pack_map(2) wrote 0x82)
            out.pack(protocol::reply::kKept);
            out.pack(kept);
        }
        reply.write(built.data(), built.size());
        return true;
    } catch (const Error& e) {
        built.clear();
        packError(out, id, pythonErrorClass(e), e.what());
    } catch (const msgpack::unpack_error& e) {
        built.clear();
        packError(out, id, "InvalidArgumentError",
                  std::string("request: malformed message (") + e.what() + ")");
        session.closeAfterReply = session.closeAfterReply || !session.greeted;
    } catch (const msgpack::type_error& e) {
        // A field of the wrong msgpack type: the request was malformed, the engine is fine.
        built.clear();
        packError(out, id, "InvalidArgumentError",
                  std::string("request: malformed message (") + e.what() + ")");
        session.closeAfterReply = session.closeAfterReply || !session.greeted;
    } catch (const std::exception& e) {
        // Anything else was thrown by engine or plugin code while running a well-formed request: report it
        // as the in-process engine does (spear.errors.SpearError), naming what failed.
        built.clear();
        packError(out, id, "SpearError", std::string(e.what()));
    }
    reply.write(built.data(), built.size());
    return false;
}

// -- the ops ------------------------------------------------------------------------------------------

const std::vector<Dispatcher::Route>& Dispatcher::routes() {
    static const std::vector<Route> table{
        {protocol::op::kWorld, &Dispatcher::world},
        {protocol::op::kWorlds, &Dispatcher::worlds},
        {protocol::op::kFrame, &Dispatcher::frame},
        {protocol::op::kInspect, &Dispatcher::inspect},
        {protocol::op::kCall, &Dispatcher::call},
        {protocol::op::kCallTyped, &Dispatcher::call},
        {protocol::op::kGet, &Dispatcher::property},
        {protocol::op::kGetTyped, &Dispatcher::property},
        {protocol::op::kSet, &Dispatcher::property},
        {protocol::op::kLoadPlugin, &Dispatcher::loadPlugin},
        {protocol::op::kUnloadPlugin, &Dispatcher::unloadPlugin},
        {protocol::op::kSpFunc, &Dispatcher::spFunc},
        {protocol::op::kSpFuncNames, &Dispatcher::spFuncNames},
        {protocol::op::kIsValid, &Dispatcher::objectQuery},
        {protocol::op::kDescribe, &Dispatcher::objectQuery},
        {protocol::op::kEcho, &Dispatcher::echo},
        {protocol::op::kShmProof, &Dispatcher::shmProof},
        {protocol::op::kShutdown, &Dispatcher::shutdown},
    };
    return table;
}

std::vector<std::string_view> Dispatcher::handledOps() {
    std::vector<std::string_view> ops{protocol::op::kHello, protocol::op::kBatch};
    for (const Route& route : routes())
        ops.push_back(route.op);
    return ops;
}

Value Dispatcher::execute(const Request& request, Session& session) {
    if (request.op() == protocol::op::kHello)
        return hello(request, session);
    if (!session.greeted) {
        session.closeAfterReply = true;
        SP_THROW(InvalidState, request.op(), "(): say hello first");
    }
    for (const Route& route : routes())
        if (route.op == request.op())
            return (this->*route.handler)(request, session);
    SP_THROW(InvalidArgument, "request: unknown op '", request.op(), "'");
}

Value Dispatcher::hello(const Request& request, Session& session) {
    const std::string clientHash = request.string(protocol::field::kApiHash, protocol::op::kHello);
    const msgpack::object* token = request.field(protocol::field::kToken);
    const std::string given = token && token->type == msgpack::type::STR
                                  ? std::string(token->via.str.ptr, token->via.str.size)
                                  : "";
    const std::string& expected = session.browser ? session.requiredToken : token_;
    if ((session.browser || !expected.empty()) && !sameSecret(given, expected)) {
        session.closeAfterReply = true;
        session.tokenRefused = true;
        SP_THROW(InvalidArgument, "hello(): wrong or missing token");
    }
    if (clientHash != apiHash_) {
        session.closeAfterReply = true;
        SP_THROW(InvalidState, "hello(): the client's API (", clientHash, ") does not match the server's (",
                 apiHash_, "); the client's generated stubs come from a different engine build");
    }
    session.greeted = true;
    Value::Dict reply{{std::string(protocol::reply::kApiHash), Value(apiHash_)},
                      {std::string(protocol::reply::kPid), Value(int64_t(::getpid()))},
                      {std::string(protocol::reply::kReplyBuffers), Value(bool(session.offerReplyBuffer))}};
    // A segment holding a nonce only a client that can map the server's segments reads (shm_proof). Where
    // none can be made (no /dev/shm), the reply names none and this connection's replies stay inline; a
    // browser never maps one.
    if (session.browser)
        return Value(std::move(reply));
    try {
        const std::string nonce = randomSecret();
        auto probe = std::make_shared<SharedMemorySegment>(SharedMemorySegment::create(nonce.size()));
        std::memcpy(probe->data(), nonce.data(), nonce.size());
        if (session.probe)
            session.probe->unlink();
        session.probe = std::move(probe);
        session.probeNonce = std::move(nonce);
        reply[std::string(protocol::reply::kShmProbe)] = Value(session.probe->name());
    } catch (const std::exception&) {
    }
    return Value(std::move(reply));
}

Value Dispatcher::shmProof(const Request& request, Session& session) {
    const std::string nonce = request.string(protocol::field::kNonce, protocol::op::kShmProof);
    const bool proven = session.probe && !nonce.empty() && sameSecret(nonce, session.probeNonce);
    if (session.probe)
        session.probe->unlink();
    session.probe.reset();
    session.probeNonce.clear();
    session.sharedMemoryReplies = session.sharedMemoryReplies || proven;
    return Value(session.sharedMemoryReplies);
}

Value Dispatcher::world(const Request& request, Session&) {
    const std::string kind = request.string(protocol::field::kKind, protocol::op::kWorld);
    if (kind == protocol::value::kGame)
        return Value(engine_.GetGameWorld().GetHandle());
    SP_CHECK(kind == protocol::value::kEditor, InvalidArgument,
             "world(): kind must be 'game' or 'editor', got '", kind, "'");
    UWorld* editor = engine_.GetEditorWorld();
    SP_CHECK(editor, InvalidState,
             "get_editor(): this instance runs standalone and has no editor world; "
             "start it with spear.Instance(mode='editor')");
    return Value(editor->GetHandle());
}

Value Dispatcher::worlds(const Request& request, Session&) {
    const std::string action = request.string(protocol::field::kAction, protocol::op::kWorlds);
    if (action == protocol::value::kCreate)
        return Value(engine_.CreateWorld(request.string(protocol::field::kName, "create_world")).GetHandle());
    if (action == protocol::value::kDestroy) {
        // Like create_world, any time the engine is not ticking: no frame needed.
        const Value handle =
            unpack(request.require(protocol::field::kObject, "destroy_world"), "destroy_world()");
        SP_CHECK(handle.is<reflect::ObjectHandle>(), InvalidArgument,
                 "destroy_world(): 'object' must be an object reference");
        auto* world = dynamic_cast<UWorld*>(
            &reflect::ObjectTable::resolve(handle.as<reflect::ObjectHandle>(), "destroy_world()"));
        SP_CHECK(world, InvalidArgument, "destroy_world(): 'world' is not a world");
        engine_.DestroyWorld(*world);
        return Value();
    }
    SP_CHECK(action == protocol::value::kList, InvalidArgument,
             "worlds(): action must be 'create', 'destroy' or 'list', got '", action, "'");
    Value::List handles;
    for (UWorld* world : engine_.GetWorlds())
        handles.emplace_back(world->GetHandle());
    return Value(std::move(handles));
}

Value Dispatcher::inspect(const Request& request, Session& session) {
    (void)session;
    const msgpack::object& port = request.require(protocol::field::kPort, protocol::op::kInspect);
    SP_CHECK(port.type == msgpack::type::POSITIVE_INTEGER && port.via.u64 <= 65535, InvalidArgument,
             "inspect(): port must be an int in [0, 65535]");
    SP_CHECK(inspectHook_, InvalidState, "inspect(): this server does not serve the inspector");
    return Value(inspectHook_(int(port.via.u64)));
}

Value Dispatcher::frame(const Request& request, Session& session) {
    const std::string action = request.string(protocol::field::kAction, protocol::op::kFrame);
    if (action == protocol::value::kBegin)
        engine_.beginFrame();
    else if (action == protocol::value::kExecute)
        engine_.executeFrame();
    else if (action == protocol::value::kBeginEnd)
        engine_.beginEndFrame();
    else if (action == protocol::value::kEnd)
        engine_.endFrame();
    else if (action == protocol::value::kAbort)
        engine_.abortFrame();
    else if (action != protocol::value::kState)
        SP_THROW(InvalidArgument, "frame(): unknown action '", action, "'");
    // The client that last moved a frame owns it until it ends (see endSession).
    if (action != protocol::value::kState)
        frameOwner_ = engine_.GetFrameState() == engine::Engine::FrameState::Idle ? nullptr : &session;
    return Value(Value::Dict{{std::string(protocol::reply::kState),
                              Value(std::string(engine::Engine::toString(engine_.GetFrameState())))},
                             {std::string(protocol::reply::kFrameCount), Value(engine_.GetFrameCount())}});
}

// call {object|class, function, args}; call_typed (the dynamic API) also returns the declared types, so the
// client can build the same Python types the typed proxies do.
Value Dispatcher::call(const Request& request, Session&) {
    const std::string_view op = request.op();
    const std::string_view function = request.text(protocol::field::kFunction, op);
    // Typed proxies name the member as the in-process bindings do ("AActor.GetName()"), so that messages are
    // the same on both transports. Views into the message: a batch of calls builds no strings.
    std::string fallback;
    const std::string_view context =
        request.context(fallback, [&] { return "call_function('" + std::string(function) + "')"; });
    // A static function names its class instead of an object ("class": "UGameplayStatics").
    const bool isStatic = request.field(protocol::field::kClass) != nullptr;
    reflect::ObjectBase* object = isStatic ? nullptr : &requireObject(request, context);
    const reflect::TypeInfo& type =
        isStatic
            ? reflect::Registry::get().getClass(request.string(protocol::field::kClass, context), context)
            : object->GetObjectClass(); // a blueprint's functions, then its native class's
    const reflect::FunctionInfo* info = type.findFunction(function);
    SP_CHECK(info, NotFound, context, ": class '", type.name, "' has no function '", function, "'");
    SP_CHECK(!isStatic || info->isStatic, InvalidArgument, context, ": '", type.name, ".", function,
             "' is not static; call it on an object");
    Value args = request.field(protocol::field::kArgs)
                     ? unpack(*request.field(protocol::field::kArgs), context)
                     : Value(Value::Dict{});
    SP_CHECK(args.is<Value::Dict>(), InvalidArgument, context, ": 'args' must be a map");
    Value result = info->invoke(object, args.as<Value::Dict>());
    if (op == protocol::op::kCall)
        return result;
    // Declared types as data (reflect::TypeCode), by which the client builds typed results.
    Value::Dict outTypes;
    for (const auto& param : info->params)
        if (param.isOut)
            outTypes.emplace(param.name, param.type.toValue());
    if (!outTypes.empty() && info->returnType.kind != reflect::TypeCode::Kind::Void)
        outTypes.emplace("ReturnValue", info->returnType.toValue());
    return Value(Value::Dict{{std::string(protocol::reply::kValue), std::move(result)},
                             {std::string(protocol::reply::kType), info->returnType.toValue()},
                             {std::string(protocol::reply::kOutTypes), Value(std::move(outTypes))}});
}

// get / get_typed {object, property}; set {object, property, value}. `property` is a path
// (core/reflect/property_path.h).
Value Dispatcher::property(const Request& request, Session&) {
    const std::string_view op = request.op();
    const std::string name = request.string(protocol::field::kProperty, op);
    std::string fallback;
    const std::string_view context = request.context(fallback, [&] {
        return (op == protocol::op::kSet ? "set_property('" : "get_property('") + name + "')";
    });
    reflect::ObjectBase& object = requireObject(request, context);
    if (op == protocol::op::kSet) {
        reflect::setPath(object, name, unpack(request.require(protocol::field::kValue, op), context),
                         context);
        return Value();
    }
    reflect::PathValue found = reflect::getPath(object, name, context);
    if (op == protocol::op::kGet)
        return std::move(found.value);
    return Value(Value::Dict{{std::string(protocol::reply::kValue), std::move(found.value)},
                             {std::string(protocol::reply::kType), found.type.toValue()}});
}

Value Dispatcher::loadPlugin(const Request& request, Session&) {
    const std::string path = allowedPlugin(request.string(protocol::field::kPath, request.op()));
    const msgpack::object* hash = request.field(protocol::field::kApiHash);
    const auto& info = plugin::load(path, hash && hash->type == msgpack::type::STR
                                              ? std::string(hash->via.str.ptr, hash->via.str.size)
                                              : "");
    Value::List classes;
    for (const std::string& name : info.classes)
        classes.emplace_back(name);
    return Value(Value::Dict{{std::string(protocol::reply::kName), Value(info.name)},
                             {std::string(protocol::reply::kClasses), Value(std::move(classes))}});
}

Value Dispatcher::unloadPlugin(const Request& request, Session&) {
    plugin::unload(request.string(protocol::field::kName, request.op()));
    return Value();
}

Value Dispatcher::spFunc(const Request& request, Session&) {
    const std::string name = request.string(protocol::field::kName, request.op());
    std::string fallback;
    const std::string_view context =
        request.context(fallback, [&] { return "call_sp_func('" + name + "')"; });
    reflect::ObjectBase& object = requireObject(request, context);
    Value::Dict bundle;
    for (const std::string_view key :
         {protocol::field::kArrays, protocol::field::kUnrealObjs, protocol::field::kInfo})
        if (const msgpack::object* given = request.field(key))
            bundle.emplace(key, unpack(*given, context));
    return spfunc::toValue(
        spfunc::call(object, name, spfunc::bundleFromValue(Value(std::move(bundle)), context)));
}

Value Dispatcher::spFuncNames(const Request& request, Session&) {
    std::string fallback;
    reflect::ObjectBase& object =
        requireObject(request, request.context(fallback, [] { return std::string("get_sp_func_names()"); }));
    Value::List names;
    for (std::string& name : spfunc::funcNames(object))
        names.emplace_back(std::move(name));
    return Value(std::move(names));
}

// is_valid / describe {object}: about an object reference that may be stale.
Value Dispatcher::objectQuery(const Request& request, Session&) {
    const std::string_view op = request.op();
    Value handle = unpack(request.require(protocol::field::kObject, op), op);
    SP_CHECK(handle.is<reflect::ObjectHandle>(), InvalidArgument, op,
             "(): 'object' must be an object reference");
    const reflect::ObjectBase* object = reflect::ObjectTable::find(handle.as<reflect::ObjectHandle>());
    if (op == protocol::op::kIsValid)
        return Value(object != nullptr);
    return Value(object ? object->GetDebugName() : std::string());
}

// Returns its value: for diagnostics, and to measure the transport alone.
Value Dispatcher::echo(const Request& request, Session&) {
    return request.field(protocol::field::kValue) ? unpack(*request.field(protocol::field::kValue), "echo()")
                                                  : Value();
}

Value Dispatcher::shutdown(const Request&, Session& session) {
    session.shutdownRequested = true;
    return Value();
}

} // namespace sp::rpc
