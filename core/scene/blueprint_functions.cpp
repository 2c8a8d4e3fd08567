#include "core/scene/blueprint_functions.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <memory>
#include <set>

#include "core/base/error.h"
#include "core/reflect/registry.h"
#include "core/world/actor.h"

namespace sp::scene {
namespace {

using Json = SceneJson;
using reflect::TypeCode;
using reflect::Value;
using Kind = TypeCode::Kind;

// One call of a function body, or its return.
struct Step {
    std::string component; // the object's component called; empty: the object itself
    std::string function;
    Json args = Json::object(); // argument name -> value as in scene files, "$Name" for a variable
    std::string result;         // the variable the call's result goes to; empty: not kept
    bool isReturn = false;
    Json value;        // a return step's value
    std::string label; // "step 2 (StaticMeshComponent.SetPhysicsLinearVelocity)", for messages
};

struct Definition {
    std::string context; // "BP_Crate.Launch()"
    std::vector<reflect::ParamInfo> params;
    std::vector<Value> defaults; // by parameter; used when hasDefault
    TypeCode returns;
    std::vector<Step> steps;
};

void checkFields(const Json& object, std::initializer_list<std::string_view> known,
                 const std::string& where) {
    SP_CHECK(object.is_object(), InvalidArgument, where, ": expected an object, got ", object.dump());
    for (const auto& [field, value] : object.items())
        SP_CHECK(std::find(known.begin(), known.end(), field) != known.end(), InvalidArgument, where,
                 ": unknown field '", field, "'");
}

// "float", "FVector", "EComponentMobility", "AActor" (an object, or None).
TypeCode parseType(const Json& json, const std::string& where) {
    SP_CHECK(json.is_string(), InvalidArgument, where, ": a type is a name, got ", json.dump());
    const std::string name = json.get<std::string>();
    static const std::map<std::string, Kind, std::less<>> kScalars = {
        {"bool", Kind::Bool}, {"int", Kind::Int}, {"float", Kind::Float}, {"str", Kind::Str}};
    if (auto it = kScalars.find(name); it != kScalars.end())
        return TypeCode(it->second);
    const reflect::Registry& registry = reflect::Registry::get();
    if (const reflect::TypeInfo* type = registry.findType(name))
        return type->kind == reflect::TypeInfo::Kind::Struct ? TypeCode(Kind::Struct, name)
                                                             : TypeCode(Kind::Object, name, true);
    SP_CHECK(registry.findEnum(name), InvalidArgument, where, ": unknown type '", name,
             "' (bool, int, float, str, or a reflected struct, enum or class)");
    return TypeCode(Kind::Enum, name);
}

// The variable a string names ("$Speed" -> "Speed"), or empty for a literal ("$$5" is the string "$5").
std::string variableOf(const Json& json) {
    if (!json.is_string())
        return {};
    const std::string& text = json.get_ref<const std::string&>();
    return text.size() > 1 && text[0] == '$' && text[1] != '$' ? text.substr(1) : std::string();
}

// A literal string with its "$$" escape undone.
Json unescaped(const Json& json) {
    if (json.is_string() && json.get_ref<const std::string&>().starts_with("$$"))
        return json.get_ref<const std::string&>().substr(1);
    return json;
}

// Whether a value of type `from` can stand where `to` is asked for.
bool assignable(const TypeCode& from, const TypeCode& to) {
    if (from.kind == Kind::Int && to.kind == Kind::Float)
        return true;
    if (from.kind == Kind::Object && to.kind == Kind::Object) {
        const reflect::TypeInfo* a = reflect::Registry::get().findType(from.name);
        const reflect::TypeInfo* b = reflect::Registry::get().findType(to.name);
        return a && b && a->isChildOf(*b);
    }
    return from.kind == to.kind && from.name == to.name &&
           (!from.isContainer() || from.elementType() == to.elementType());
}

// The component called `name` of `object` when it is an actor; null otherwise.
UActorComponent* componentNamed(reflect::ObjectBase& object, std::string_view name) {
    auto* actor = dynamic_cast<AActor*>(&object);
    return actor ? actor->FindComponentByName(name) : nullptr;
}

// Checks a value written for `type` at load time: variables known and of a fitting type, literals
// readable (as scene files read them).
void checkValue(const Json& json, const TypeCode& type, const std::map<std::string, TypeCode>& variables,
                const ActorsByName& actors, const std::string& where) {
    if (const std::string name = variableOf(json); !name.empty()) {
        auto it = variables.find(name);
        SP_CHECK(it != variables.end(), InvalidArgument, where, ": '$", name,
                 "' is not a parameter or an earlier step's result");
        SP_CHECK(assignable(it->second, type), InvalidArgument, where, ": '$", name, "' is ",
                 it->second.spelling(), ", not ", type.spelling());
        return;
    }
    if (type.kind == Kind::Struct && json.is_object()) {
        const reflect::TypeInfo& info = reflect::Registry::get().getStruct(type.name, where);
        for (const auto& [field, value] : json.items()) {
            const reflect::PropertyInfo* property = info.findProperty(field);
            SP_CHECK(property, InvalidArgument, where, ": ", type.name, " has no field '", field, "'");
            checkValue(value, property->type, variables, actors, where + "." + field);
        }
        return;
    }
    if (type.kind == Kind::List && json.is_array()) {
        for (const Json& item : json)
            checkValue(item, type.elementType(), variables, actors, where);
        return;
    }
    Value value;
    try {
        value = valueFromJson(unescaped(json), type, actors);
    } catch (const Error&) {
        rethrowWithPrefix(where + ": ");
    }
    // An object named by path ("Self", "Self.StaticMeshComponent") must be of the class asked for there.
    if (const auto* handle = value.tryAs<reflect::ObjectHandle>()) {
        const reflect::ObjectBase* object = reflect::ObjectTable::find(*handle);
        const reflect::TypeInfo* wanted = reflect::Registry::get().findType(type.name);
        SP_CHECK(object && wanted && object->GetObjectClass().isChildOf(*wanted), InvalidArgument, where,
                 ": '", json.get<std::string>(), "' is ",
                 object ? object->GetObjectClass().name : std::string("nothing"), ", not ", type.name);
    }
}

// The Value of a value written for `type`, variables substituted.
Value resolve(const Json& json, const TypeCode& type, const std::map<std::string, Value>& variables,
              const ActorsByName& actors) {
    if (const std::string name = variableOf(json); !name.empty()) {
        const Value& value = variables.at(name); // checked at load
        if (type.kind == Kind::Float && value.is<int64_t>())
            return double(value.as<int64_t>());
        return value;
    }
    if (type.kind == Kind::Struct && json.is_object()) {
        const reflect::TypeInfo& info = reflect::Registry::get().getStruct(type.name, "resolve()");
        Value::Dict fields;
        for (const auto& [field, value] : json.items()) {
            const reflect::PropertyInfo* property = info.findProperty(field);
            SP_CHECK(property, InvalidArgument, type.name, " has no field '", field, "'");
            fields.emplace(field, resolve(value, property->type, variables, actors));
        }
        return fields;
    }
    if (type.kind == Kind::List && json.is_array()) {
        Value::List items;
        for (const Json& item : json)
            items.push_back(resolve(item, type.elementType(), variables, actors));
        return items;
    }
    return valueFromJson(unescaped(json), type, actors);
}

// Whether an argument's Value fits a parameter's type (the calls it flows into check it fully).
bool fits(const Value& value, const TypeCode& type) {
    if (value.isNone())
        return type.optional;
    switch (type.kind) {
    case Kind::Bool:
        return value.is<bool>();
    case Kind::Int:
        return value.is<int64_t>();
    case Kind::Float:
        return value.is<int64_t>() || value.is<double>();
    case Kind::Str:
        return value.is<std::string>();
    case Kind::Enum:
        return value.is<int64_t>() ||
               (value.is<reflect::EnumValue>() && value.as<reflect::EnumValue>().type == type.name);
    case Kind::Struct:
        return value.is<Value::Dict>();
    case Kind::Object:
        return value.is<reflect::ObjectHandle>();
    case Kind::Void:
    case Kind::Class:
    case Kind::Array:
    case Kind::List:
    case Kind::Dict:
        return false; // no parameter has these types: parseType() gives none of them
    }
    return false; // not a Kind (every kind is a case above, so a new one is a -Wswitch error here)
}

Value run(const Definition& definition, reflect::ObjectBase& self, const reflect::CallArgs& args) {
    std::map<std::string, Value> variables;
    for (size_t i = 0; i < definition.params.size(); ++i) {
        const reflect::ParamInfo& param = definition.params[i];
        auto it = args.find(param.name);
        if (it == args.end()) {
            SP_CHECK(param.hasDefault, InvalidArgument, definition.context, ": missing argument '",
                     param.name, "'");
            variables.emplace(param.name, definition.defaults[i]);
            continue;
        }
        SP_CHECK(fits(it->second, param.type), InvalidArgument, definition.context, ": argument '",
                 param.name, "' must be ", param.type.spelling(), ", got ", it->second.repr());
        variables.emplace(param.name, it->second);
    }
    for (const auto& [name, value] : args)
        SP_CHECK(variables.count(name), InvalidArgument, definition.context, ": unexpected argument '", name,
                 "'");

    const ActorsByName actors = selfOf(self);
    for (const Step& step : definition.steps) {
        try {
            if (step.isReturn)
                return resolve(step.value, definition.returns, variables, actors);
            reflect::ObjectBase* target =
                step.component.empty() ? &self : componentNamed(self, step.component);
            SP_CHECK(target, NotFound, "the object has no component '", step.component, "' any more");
            const reflect::FunctionInfo* function = target->GetClass().findFunction(step.function);
            SP_CHECK(function, NotFound, "class '", target->GetClass().name, "' has no function '",
                     step.function, "'");
            reflect::CallArgs callArgs;
            for (const reflect::ParamInfo& param :
                 function->params) // each argument names one (checked at load)
                if (const Json* value = optionalMember(step.args, param.name.c_str()))
                    callArgs.emplace(param.name, resolve(*value, param.type, variables, actors));
            Value result = function->invoke(target, callArgs);
            if (!step.result.empty())
                variables.insert_or_assign(step.result, std::move(result));
        } catch (...) {
            rethrowWithPrefix(definition.context + ": " + step.label + ": ");
        }
    }
    return Value();
}

Step loadStep(const Json& json, size_t index, bool last, Definition& definition,
              reflect::ObjectBase& prototype, std::map<std::string, TypeCode>& variables,
              const std::string& where) {
    Step step;
    const ActorsByName actors = selfOf(prototype);
    if (optionalMember(json, "return")) {
        checkFields(json, {"return"}, where);
        step.isReturn = true;
        step.value = json["return"];
        step.label = "step " + std::to_string(index + 1) + " (return)";
        SP_CHECK(last, InvalidArgument, where, ": a return step must be the last");
        SP_CHECK(definition.returns.kind != Kind::Void, InvalidArgument, where,
                 ": a return step needs 'returns' to declare the result's type");
        checkValue(step.value, definition.returns, variables, actors, where + ": 'return'");
        return step;
    }
    checkFields(json, {"call", "args", "result"}, where);
    const std::string call = stringMember(json, "call", where);
    const size_t dot = call.find('.');
    step.component = dot == std::string::npos ? std::string() : call.substr(0, dot);
    step.function = dot == std::string::npos ? call : call.substr(dot + 1);
    step.label = "step " + std::to_string(index + 1) + " (" + call + ")";
    reflect::ObjectBase* target =
        step.component.empty() ? &prototype : componentNamed(prototype, step.component);
    SP_CHECK(target, InvalidArgument, where, ": '", call, "': ", prototype.GetClass().name,
             " has no component '", step.component, "'");
    const reflect::FunctionInfo* function = target->GetClass().findFunction(step.function);
    SP_CHECK(function && !function->isStatic, InvalidArgument, where, ": '", call, "': class '",
             target->GetClass().name, "' has no function '", step.function, "'");
    for (const reflect::ParamInfo& param : function->params)
        SP_CHECK(!param.isOut, InvalidArgument, where, ": '", call,
                 "' has out-parameters, which a blueprint function cannot take yet");
    if (const Json* args = optionalMember(json, "args")) {
        SP_CHECK(args->is_object(), InvalidArgument, where, ": 'args' must be an object, got ", args->dump());
        step.args = *args;
    }
    for (const reflect::ParamInfo& param : function->params) {
        const Json* value = optionalMember(step.args, param.name.c_str());
        SP_CHECK(value || param.hasDefault, InvalidArgument, where, ": '", call, "' needs argument '",
                 param.name, "'");
        if (value)
            checkValue(*value, param.type, variables, actors, where + ": argument '" + param.name + "'");
    }
    for (const auto& [name, value] : step.args.items())
        SP_CHECK(std::any_of(function->params.begin(), function->params.end(),
                             [&](const reflect::ParamInfo& param) { return param.name == name; }),
                 InvalidArgument, where, ": '", call, "' has no parameter '", name, "'");
    if (optionalMember(json, "result")) {
        step.result = stringMember(json, "result", where);
        SP_CHECK(function->returnType.kind != Kind::Void, InvalidArgument, where, ": '", call,
                 "' returns nothing to keep as '", step.result, "'");
        SP_CHECK(!variables.count(step.result), InvalidArgument, where, ": '", step.result,
                 "' is already a parameter or an earlier result");
        variables.emplace(step.result, function->returnType);
    }
    return step;
}

reflect::FunctionInfo loadFunction(const Json& json, const std::string& className,
                                   reflect::ObjectBase& prototype, const std::string& where) {
    checkFields(json, {"name", "doc", "params", "returns", "body"}, where);
    auto definition = std::make_shared<Definition>();
    reflect::FunctionInfo info;
    info.name = stringMember(json, "name", where);
    const std::string fwhere = where + ": function '" + info.name + "'";
    definition->context = className + "." + info.name + "()";
    // A name Python can call by attribute and keyword that hides nothing the objects have: the class's own
    // functions are not registered yet, so what findFunction finds here is the parent classes' (a parent
    // blueprint's too).
    SP_CHECK(
        info.name[0] != '_' && std::all_of(info.name.begin(), info.name.end(),
                                           [](char c) { return std::isalnum((unsigned char)c) || c == '_'; }),
        InvalidArgument, fwhere, ": a function's name is letters, digits and '_', not starting with '_'");
    const reflect::TypeInfo& type = prototype.GetObjectClass();
    SP_CHECK(!type.findFunction(info.name) && !type.findProperty(info.name), InvalidArgument, fwhere,
             ": the parent class has a member of that name");
    if (const Json* doc = optionalMember(json, "doc")) {
        SP_CHECK(doc->is_string(), InvalidArgument, fwhere, ": 'doc' must be a string, got ", doc->dump());
        info.doc = doc->get<std::string>();
    }
    std::map<std::string, TypeCode> variables;
    if (const Json* params = optionalMember(json, "params")) {
        SP_CHECK(params->is_array(), InvalidArgument, fwhere, ": 'params' must be a list, got ",
                 params->dump());
        for (const Json& entry : *params) {
            checkFields(entry, {"name", "type", "default"}, fwhere + ": params");
            reflect::ParamInfo param;
            param.name = stringMember(entry, "name", fwhere + ": params");
            const std::string pwhere = fwhere + ": parameter '" + param.name + "'";
            SP_CHECK(!variables.count(param.name), InvalidArgument, pwhere, ": declared twice");
            param.type = parseType(entry.value("type", Json()), pwhere);
            Value fallback;
            if (const Json* value = optionalMember(entry, "default")) {
                param.hasDefault = true;
                try {
                    fallback = valueFromJson(*value, param.type, {});
                } catch (const Error&) {
                    rethrowWithPrefix(pwhere + ": 'default': ");
                }
            }
            variables.emplace(param.name, param.type);
            definition->params.push_back(param);
            definition->defaults.push_back(std::move(fallback));
        }
    }
    if (const Json* returns = optionalMember(json, "returns"))
        definition->returns = parseType(*returns, fwhere + ": 'returns'");
    const Json* body = optionalMember(json, "body");
    SP_CHECK(body && body->is_array() && !body->empty(), InvalidArgument, fwhere,
             ": 'body' must be a non-empty list of steps");
    for (size_t i = 0; i < body->size(); ++i)
        definition->steps.push_back(loadStep((*body)[i], i, i + 1 == body->size(), *definition, prototype,
                                             variables, fwhere + ": body[" + std::to_string(i) + "]"));
    SP_CHECK(definition->returns.kind == Kind::Void || definition->steps.back().isReturn, InvalidArgument,
             fwhere, ": declares 'returns' but its last step is not a return");

    info.returnType = definition->returns;
    info.params = definition->params;
    info.invoke = [definition](void* self, const reflect::CallArgs& args) {
        return run(*definition, *static_cast<reflect::ObjectBase*>(self), args);
    };
    return info;
}

} // namespace

ActorsByName selfOf(reflect::ObjectBase& object) {
    auto* actor = dynamic_cast<AActor*>(&object);
    return actor ? ActorsByName{{"Self", actor}} : ActorsByName{};
}

std::vector<reflect::FunctionInfo> loadBlueprintFunctions(const SceneJson& functions,
                                                          const std::string& className,
                                                          reflect::ObjectBase& prototype,
                                                          const std::string& where) {
    SP_CHECK(functions.is_array(), InvalidArgument, where, ": 'functions' must be a list, got ",
             functions.dump());
    std::vector<reflect::FunctionInfo> result;
    std::set<std::string> names;
    for (size_t i = 0; i < functions.size(); ++i) {
        result.push_back(loadFunction(functions[i], className, prototype,
                                      where + ": functions[" + std::to_string(i) + "]"));
        SP_CHECK(names.insert(result.back().name).second, InvalidArgument, where, ": function '",
                 result.back().name, "' is declared twice");
    }
    return result;
}

} // namespace sp::scene
