#pragma once
// The declared type of a reflected property, parameter or result, as data. Generated code builds one for
// every member from the IR's type model (codegen/typecodes.py); whatever converts a Value by its declared
// type (scene files, the in-process dynamic access, the RPC server's typed replies) reads it, so no one
// parses an annotation string. spelling() gives the Python annotation, for messages.

#include <string>
#include <vector>

#include "core/reflect/value.h"

namespace sp::reflect {

struct TypeCode {
    // The IR's kinds (codegen/model.py TypeKind).
    enum class Kind : uint8_t { Void, Bool, Int, Float, Str, Enum, Struct, Object, Class, Array, List, Dict };

    Kind kind = Kind::Void;
    std::string name; // Enum, Struct, Object, Class (its base): the reflected name; Array: a dtype
    // None is a value of it (see codegen/typecodes.py): a nullable object, a class result, a parameter
    // whose default is nullptr.
    bool optional = false;
    std::vector<TypeCode> element; // List and Dict: their element (dict keys are str); empty otherwise

    TypeCode() = default;
    explicit TypeCode(Kind kind_, std::string name_ = {}, bool optional_ = false)
        : kind(kind_), name(std::move(name_)), optional(optional_) {}
    TypeCode(Kind kind_, TypeCode element_) : kind(kind_), element{std::move(element_)} {}

    bool isContainer() const { return kind == Kind::List || kind == Kind::Dict; }
    // A container's element; only valid when isContainer().
    const TypeCode& elementType() const { return element.front(); }
    // The Python annotation: "list[AActor]", "AActor | None", "type[AActor] | None", "NDArray[np.float32]".
    std::string spelling() const;
    // The wire form, read by spear._type_code.TypeCode.from_wire: [kind, name, optional, element or None].
    Value toValue() const;

    friend bool operator==(const TypeCode&, const TypeCode&) = default;
};

// The IR's name of a kind ("object", "list"), as the wire form and Python spell it.
std::string_view kindName(TypeCode::Kind kind);

} // namespace sp::reflect
