#pragma once
// Helpers that generated invokers call. They keep the generated code short and put every check, and
// every message, in one place.

#include <span>
#include <string_view>
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

// Throws InvalidArgument "<context>: missing argument '<name>'".
const Value& requireArgument(const CallArgs& args, const char* name, std::string_view context);

template <typename T> void checkNotNull(const T& result, std::string_view context) {
    if constexpr (std::is_pointer_v<T>)
        SP_CHECK(result != nullptr, InvalidState, context, ": returned None although it is declared NotNull");
}

// An object or class argument without a nullptr default: None is refused.
template <typename T> void checkNotNone(const T& argument, std::string_view context) {
    SP_CHECK(static_cast<bool>(argument), InvalidArgument, context, " must not be None");
}

// -- Generated call bodies ----------------------------------------------------------------------------
// Each reflected function, property getter and setter has one generated body (<header stem>.gen.h), a
// template over the boundary it is reached through: ValueCall here (the registry: dynamic calls and the RPC
// server) or sp::pybind::PyCall (the in-process bindings). The body checks the call, decodes arguments,
// calls, checks the result and notifies property changes; the boundary only converts values in and out.

// One input parameter of a function, as the body hands it to the boundary.
struct ParamDesc {
    const char* name;
    const char* context; // "AActor.SetActorLocation(): argument 'NewLocation'", for messages
    bool required;       // no C++ default
};

// The result tuple of a function with out-parameters: {api module, class, tuple}
// ("AActor.GetActorBoundsResult").
struct ResultTupleDesc {
    const char* apiModule;
    const char* owner;
    const char* name;
};

// One field of a function's results: "ReturnValue" or an out-parameter.
template <typename T> struct Output {
    const char* name;
    const T& value;
};
template <typename T> Output(const char*, const T&) -> Output<T>;

// The registry's boundary: arguments by name in a Value dict, results as Values.
class ValueCall {
  public:
    using Args = const CallArgs&;
    using Result = Value;
    using Input = Value; // a property setter's value

    ValueCall(Args args, std::string_view context, std::span<const ParamDesc> params)
        : args_(args), context_(context), params_(params) {
        for (const auto& [name, value] : args) {
            bool known = false;
            for (const ParamDesc& param : params)
                known = known || name == param.name;
            if (!known)
                rejectArgument(name);
        }
    }
    bool given(std::size_t index) const { return findArgument(args_, params_[index].name) != nullptr; }
    template <typename T> T arg(std::size_t index) const {
        const ParamDesc& param = params_[index];
        return decode<T>(requireArgument(args_, param.name, context_), param.context);
    }
    // The object a function is called on: the registry passes the declaring class's ObjectBase as void*.
    template <typename T> static T* object(void* self, std::string_view) { return selfCast<T>(self); }
    template <typename T> static T input(const Value& value, std::string_view context) {
        return decode<T>(value, context);
    }
    template <typename T, typename V> static Value result(const V& value) { return encode(value); }
    static Value none() { return {}; }
    template <typename... T> static Value outputs(const ResultTupleDesc&, const Output<T>&... fields) {
        Value::Dict out;
        (out.emplace(fields.name, encode(fields.value)), ...);
        return Value(std::move(out));
    }

  private:
    [[noreturn]] void rejectArgument(const std::string& name) const;

    const CallArgs& args_;
    std::string_view context_;
    std::span<const ParamDesc> params_;
};

} // namespace sp::reflect
