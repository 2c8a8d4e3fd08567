#pragma once
// Request: one RPC request's op and top-level fields, read from the msgpack map once, with accessors whose
// errors name the op ("call(): the request has no 'function'"). The dispatcher's handlers read fields
// through it instead of scanning the raw message in every branch.
//
// A batch holds one Request per call, so reading one allocates nothing: the fields of a request (six or
// fewer from spear's client) are kept inline, and names are views into the message.

#include <msgpack.hpp>

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sp::rpc {

class Request {
  public:
    // Throws InvalidArgument when `message` is not a map or has no string "op".
    explicit Request(const msgpack::object& message);

    std::string_view op() const { return op_; }
    // The field's value, or nullptr; the first of repeated keys.
    const msgpack::object* field(std::string_view name) const;
    // The field's value; throws InvalidArgument naming `where` ("<where>(): the request has no 'x'").
    const msgpack::object& require(std::string_view name, std::string_view where) const;
    // A string field's value, a view into the message; throws InvalidArgument when it is missing or not a
    // string.
    std::string_view text(std::string_view name, std::string_view where) const;
    std::string string(std::string_view name, std::string_view where) const {
        return std::string(text(name, where));
    }
    // The context a client names the request by ("AMyActor.my_sp_func()", as the in-process bindings
    // would), or the one `fallback()` makes into `storage` when the client gave none (built only then: a
    // batch of calls builds no strings); the view is of the message or of `storage`.
    template <class Fallback> std::string_view context(std::string& storage, Fallback&& fallback) const {
        if (const std::string_view given = givenContext(); !given.empty())
            return given;
        storage = fallback();
        return storage;
    }

  private:
    using Field = std::pair<std::string_view, const msgpack::object*>;
    static constexpr size_t kInlineFields = 8;

    std::string_view givenContext() const;
    void add(Field entry);

    std::array<Field, kInlineFields> inline_{};
    size_t inlineCount_ = 0;
    std::vector<Field> more_; // fields past the inline ones (not from spear's client)
    std::string_view op_;
};

// The value of `name` in a msgpack map (nullptr when absent, or when `map` is not a map).
const msgpack::object* mapField(const msgpack::object& map, std::string_view name);

} // namespace sp::rpc
