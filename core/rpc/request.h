#pragma once
// Request: one RPC request's op and top-level fields, read from the msgpack map once, with accessors whose
// errors name the op ("call(): the request has no 'function'"). The dispatcher's handlers read fields
// through it instead of scanning the raw message in every branch.

#include <msgpack.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sp::rpc {

class Request {
  public:
    // Throws InvalidArgument when `message` is not a map or has no string "op".
    explicit Request(const msgpack::object& message);

    const std::string& op() const { return op_; }
    // The field's value, or nullptr; the first of repeated keys.
    const msgpack::object* field(std::string_view name) const;
    // The field's value; throws InvalidArgument naming `where` ("<where>(): the request has no 'x'").
    const msgpack::object& require(std::string_view name, std::string_view where) const;
    // A string field's value; throws InvalidArgument when it is missing or not a string.
    std::string string(std::string_view name, std::string_view where) const;
    // The context a client names the request by ("AMyActor.my_sp_func()", as the in-process bindings
    // would), or `fallback`.
    std::string context(std::string fallback) const;

  private:
    std::vector<std::pair<std::string_view, const msgpack::object*>> fields_;
    std::string op_;
};

// The value of `name` in a msgpack map (nullptr when absent, or when `map` is not a map).
const msgpack::object* mapField(const msgpack::object& map, std::string_view name);

} // namespace sp::rpc
