#pragma once
// Runtime descriptions of reflected types, filled in by generated code (*.gen.cpp). One TypeInfo per
// reflected class or struct (its properties, functions, parent and factory) and one EnumInfo per enum.
// Invokers are plain function pointers over Values so that the dynamic Python path and the RPC server
// share one dispatch mechanism.

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/reflect/type_code.h"
#include "core/reflect/value.h"

namespace sp::reflect {

class ObjectBase;

using CallArgs = Value::Dict;

struct ParamInfo {
    std::string name;
    TypeCode type;
    bool hasDefault = false;
    bool isOut = false; // non-const lvalue reference: returned with the result, not passed in
};

struct PropertyInfo {
    std::string name;
    TypeCode type;
    std::string doc;
    bool readOnly = false;
    // `self` points to the declaring class's ObjectBase (classes) or to the struct itself (structs).
    Value (*get)(const void* self) = nullptr;
    void (*set)(void* self, const Value& value) = nullptr;
};

struct FunctionInfo {
    std::string name;
    std::string doc;
    TypeCode returnType; // with out-parameters: the "ReturnValue" entry's
    std::vector<ParamInfo> params;
    bool isStatic = false;
    bool isConst = false;
    // Converts `args` (by parameter name) to C++ values, calls, and returns the result: the return value,
    // or, when the function has out-parameters, a dict with "ReturnValue" and one entry per out-parameter.
    // Generated functions are plain functions; a blueprint's (core/scene/blueprint_functions.h) carry the
    // steps they run.
    std::function<Value(void* self, const CallArgs& args)> invoke;
};

class TypeInfo {
  public:
    enum class Kind { Class, Struct };

    std::string name;
    std::string doc;
    Kind kind = Kind::Class;
    const TypeInfo* parent = nullptr;
    bool isAbstract = false;
    // SPSTRUCT(TypedDict) without Partial: every field is always present in Python, so an array field
    // left without data is an error when the struct is returned (see checkFieldSet in codec.h).
    bool isCompleteDict = false;
    std::vector<PropertyInfo> properties; // declared by this type only; see findProperty
    std::vector<FunctionInfo> functions;
    ObjectBase* (*create)() = nullptr; // classes that can be instantiated; owned by the caller
    std::string asset;                 // a data-defined class: the file it was loaded from
    // Set only for a data-defined class (a blueprint, core/scene/blueprint.h), which has no generated code:
    // its objects are created by its native class, report this class (ObjectBase::SetDataDefinedClass), and
    // get their data-defined defaults from `initialize` once they are placed.
    std::function<void(ObjectBase&)> initialize;

    bool isDataDefined() const { return bool(initialize); }
    // The nearest class in the parent chain (this one included) that has generated code.
    const TypeInfo& nativeClass() const;
    // True when objects of this class can be created (directly or through the native class).
    bool canCreate() const { return nativeClass().create != nullptr; }
    // Runs the `initialize` of every data-defined class in the chain on `object`, outermost parent first.
    void initializeObject(ObjectBase& object) const;

    bool isChildOf(const TypeInfo& other) const;                           // true for the type itself
    const PropertyInfo* findProperty(std::string_view propertyName) const; // searches the parent chain
    const FunctionInfo* findFunction(std::string_view functionName) const;
    std::vector<const PropertyInfo*> allProperties() const; // parents first
    std::vector<const FunctionInfo*> allFunctions() const;
};

struct EnumInfo {
    std::string name;
    std::string doc;
    std::vector<std::pair<std::string, int64_t>> entries;

    bool contains(int64_t value) const;
    std::string_view nameOf(int64_t value) const; // empty when not an entry
};

// Declared here, specialised by generated code for each reflected enum. (An enum cannot carry a
// generated member the way SP_GENERATED_BODY gives classes StaticClass(), so this is the hook.)
template <typename E> const EnumInfo& StaticEnum();

} // namespace sp::reflect
