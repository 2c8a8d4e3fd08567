#include "core/reflect/type_code.h"

namespace sp::reflect {

std::string_view kindName(TypeCode::Kind kind) {
    switch (kind) {
    case TypeCode::Kind::Void:
        return "void";
    case TypeCode::Kind::Bool:
        return "bool";
    case TypeCode::Kind::Int:
        return "int";
    case TypeCode::Kind::Float:
        return "float";
    case TypeCode::Kind::Str:
        return "str";
    case TypeCode::Kind::Enum:
        return "enum";
    case TypeCode::Kind::Struct:
        return "struct";
    case TypeCode::Kind::Object:
        return "object";
    case TypeCode::Kind::Class:
        return "class";
    case TypeCode::Kind::Array:
        return "array";
    case TypeCode::Kind::List:
        return "list";
    case TypeCode::Kind::Dict:
        return "dict";
    }
    return "?";
}

std::string TypeCode::spelling() const {
    std::string text;
    switch (kind) {
    case Kind::Void:
        return "None";
    case Kind::Bool:
    case Kind::Int:
    case Kind::Float:
    case Kind::Str:
        text = kindName(kind);
        break;
    case Kind::Enum:
    case Kind::Struct:
    case Kind::Object:
        text = name;
        break;
    case Kind::Class:
        text = "type[" + name + "]";
        break;
    case Kind::Array:
        text = "NDArray[np." + name + "]";
        break;
    case Kind::List:
        text = "list[" + elementType().spelling() + "]";
        break;
    case Kind::Dict:
        text = "dict[str, " + elementType().spelling() + "]";
        break;
    }
    return optional ? text + " | None" : text;
}

Value TypeCode::toValue() const {
    return Value(Value::List{Value(std::string(kindName(kind))), Value(name), Value(optional),
                             isContainer() ? elementType().toValue() : Value()});
}

} // namespace sp::reflect
