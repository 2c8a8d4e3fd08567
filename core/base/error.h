#pragma once
// The engine's error types. Every check in the engine throws one of these with a message that names
// the function and the bad value ("UWorld::SpawnActor(): class 'AFoo' is not registered"); the Python
// layer maps each type to one Python exception class in a single place.

#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sp {

class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A value of the wrong type or out of range.
class InvalidArgument : public Error {
  public:
    using Error::Error;
};

// An unknown class, property, function, asset or name.
class NotFound : public Error {
  public:
    using Error::Error;
};

// A handle whose object was destroyed.
class StaleObject : public Error {
  public:
    using Error::Error;
};

// A call that is not allowed in the engine's current state (outside a frame, moving a static body, ...).
class InvalidState : public Error {
  public:
    using Error::Error;
};

// The spear.errors class that stands for `error` in Python ("NotFoundError", ...; "SpearError" for any
// other engine error). The in-process bindings and the RPC server both use it, so both raise the same.
const char* pythonErrorClass(const std::exception& error);

// Inside a catch block: throws the exception being handled again, as the same sp error type with
// `prefix` before its message (who was doing what when it failed); anything that is not an sp::Error is
// rethrown as it is.
[[noreturn]] void rethrowWithPrefix(const std::string& prefix);

namespace detail {
template <typename... Args> std::string concat(const Args&... args) {
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}
} // namespace detail

// Throws Type (spelled as visible at the call site) with the streamed message: SP_THROW(NotFound,
// "UWorld::SpawnActor(): class '", name, "' ...").
#define SP_THROW(Type, ...) throw Type(::sp::detail::concat(__VA_ARGS__))

// Checks a condition and throws E with the message when it does not hold.
#define SP_CHECK(cond, Type, ...)                                                                            \
    do {                                                                                                     \
        if (!(cond))                                                                                         \
            SP_THROW(Type, __VA_ARGS__);                                                                     \
    } while (false)

// The check of a validated setter (SPPROPERTY(Setter = ...)): throws InvalidArgument "<Owner>.<Property>
// must be <range>, got <value>", the one message every such setter gives, in-process and over RPC.
template <typename T>
void checkSetting(bool ok, std::string_view owner, std::string_view property, std::string_view range,
                  const T& value) {
    SP_CHECK(ok, InvalidArgument, owner, ".", property, " must be ", range, ", got ", value);
}

} // namespace sp
