#include "core/rpc/request.h"

#include "core/base/error.h"
#include "generated/rpc/cpp/protocol.gen.h"

namespace sp::rpc {

const msgpack::object* mapField(const msgpack::object& map, std::string_view name) {
    if (map.type != msgpack::type::MAP)
        return nullptr;
    for (uint32_t i = 0; i < map.via.map.size; ++i) {
        const auto& kv = map.via.map.ptr[i];
        if (kv.key.type == msgpack::type::STR &&
            std::string_view(kv.key.via.str.ptr, kv.key.via.str.size) == name)
            return &kv.val;
    }
    return nullptr;
}

Request::Request(const msgpack::object& message) {
    SP_CHECK(message.type == msgpack::type::MAP, InvalidArgument, "request: expected a map");
    for (uint32_t i = 0; i < message.via.map.size; ++i) {
        const auto& kv = message.via.map.ptr[i];
        if (kv.key.type == msgpack::type::STR)
            add({std::string_view(kv.key.via.str.ptr, kv.key.via.str.size), &kv.val});
    }
    op_ = text(protocol::field::kOp, "request");
}

void Request::add(Field entry) {
    if (inlineCount_ < kInlineFields)
        inline_[inlineCount_++] = entry;
    else
        more_.push_back(entry);
}

const msgpack::object* Request::field(std::string_view name) const {
    for (size_t i = 0; i < inlineCount_; ++i)
        if (inline_[i].first == name)
            return inline_[i].second;
    for (const auto& [key, value] : more_)
        if (key == name)
            return value;
    return nullptr;
}

const msgpack::object& Request::require(std::string_view name, std::string_view where) const {
    const msgpack::object* value = field(name);
    SP_CHECK(value, InvalidArgument, where, "(): the request has no '", name, "'");
    return *value;
}

std::string_view Request::text(std::string_view name, std::string_view where) const {
    const msgpack::object& value = require(name, where);
    SP_CHECK(value.type == msgpack::type::STR, InvalidArgument, where, "(): '", name, "' must be a string");
    return std::string_view(value.via.str.ptr, value.via.str.size);
}

std::string_view Request::givenContext() const {
    const msgpack::object* given = field(protocol::field::kContext);
    if (given && given->type == msgpack::type::STR)
        return std::string_view(given->via.str.ptr, given->via.str.size);
    return {};
}

} // namespace sp::rpc
