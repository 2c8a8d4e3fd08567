#include "core/rpc/request.h"

#include "core/base/error.h"

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
    fields_.reserve(message.via.map.size);
    for (uint32_t i = 0; i < message.via.map.size; ++i) {
        const auto& kv = message.via.map.ptr[i];
        if (kv.key.type == msgpack::type::STR)
            fields_.emplace_back(std::string_view(kv.key.via.str.ptr, kv.key.via.str.size), &kv.val);
    }
    op_ = string("op", "request");
}

const msgpack::object* Request::field(std::string_view name) const {
    for (const auto& [key, value] : fields_)
        if (key == name)
            return value;
    return nullptr;
}

const msgpack::object& Request::require(std::string_view name, std::string_view where) const {
    const msgpack::object* value = field(name);
    SP_CHECK(value, InvalidArgument, where, "(): the request has no '", name, "'");
    return *value;
}

std::string Request::string(std::string_view name, std::string_view where) const {
    const msgpack::object& value = require(name, where);
    SP_CHECK(value.type == msgpack::type::STR, InvalidArgument, where, "(): '", name, "' must be a string");
    return std::string(value.via.str.ptr, value.via.str.size);
}

std::string Request::context(std::string fallback) const {
    const msgpack::object* given = field("context");
    if (given && given->type == msgpack::type::STR && given->via.str.size > 0)
        return std::string(given->via.str.ptr, given->via.str.size);
    return fallback;
}

} // namespace sp::rpc
