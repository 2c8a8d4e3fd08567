#pragma once
// Helpers that generated invokers call. They keep the generated code short and put every check, and
// every message, in one place.

#include <initializer_list>
#include <type_traits>

#include "core/base/error.h"
#include "core/reflect/codec.h"
#include "core/reflect/object_base.h"

namespace sp::reflect {

// Registry invokers receive `self` as void*: for classes it is the ObjectBase*, for structs the struct.
template <typename T> T* selfCast(std::conditional_t<std::is_const_v<T>, const void*, void*> self) {
    using Plain = std::remove_const_t<T>;
    if constexpr (std::is_base_of_v<ObjectBase, Plain>) {
        using Base = std::conditional_t<std::is_const_v<T>, const ObjectBase, ObjectBase>;
        return static_cast<T*>(static_cast<Base*>(self));
    } else {
        return static_cast<T*>(self);
    }
}

template <typename T> void notifyPropertyChanged(T* object, std::string_view name) {
    if constexpr (std::is_base_of_v<ObjectBase, T>)
        object->PostPropertyChanged(name);
}

// Rejects names that are not input parameters (a misspelt keyword must not be ignored).
void checkArguments(const CallArgs& args, std::initializer_list<const char*> names, std::string_view context);

// Throws InvalidArgument "<context>: missing argument '<name>'".
const Value& requireArgument(const CallArgs& args, const char* name, std::string_view context);

// Like decode(), but None is an error: used for object and class parameters without a nullptr default.
template <typename T> T decodeNonNull(const Value& value, std::string_view context) {
    if (value.isNone())
        SP_THROW(InvalidArgument, context, " must not be None");
    return decode<T>(value, context);
}

template <typename T> void checkNotNull(const T& result, std::string_view context) {
    if constexpr (std::is_pointer_v<T>)
        SP_CHECK(result != nullptr, InvalidState, context, ": returned None although it is declared NotNull");
}

} // namespace sp::reflect
