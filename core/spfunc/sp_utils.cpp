#include "core/spfunc/sp_utils.h"

#include <nlohmann/json.hpp>

#include "core/base/error.h"
#include "core/spfunc/sp_func_call.h"

namespace {
using sp::reflect::Value;
using Json = nlohmann::json;

std::string callContext(const char* outside = "SpUtils::moveFromPackedArrays()") {
    const std::string& current = sp::spfunc::currentCall();
    return current.empty() ? std::string(outside) : current;
}

// JSON <-> Value without a declared type: the codec (decode<T>) then checks the value against T.
Value fromJson(const Json& j) {
    switch (j.type()) {
    case Json::value_t::null:
        return Value();
    case Json::value_t::boolean:
        return Value(j.get<bool>());
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
        return Value(j.get<int64_t>());
    case Json::value_t::number_float:
        return Value(j.get<double>());
    case Json::value_t::string:
        return Value(j.get<std::string>());
    case Json::value_t::array: {
        Value::List items;
        for (const Json& item : j)
            items.push_back(fromJson(item));
        return Value(std::move(items));
    }
    case Json::value_t::object: {
        Value::Dict fields;
        for (const auto& [key, item] : j.items())
            fields.emplace(key, fromJson(item));
        return Value(std::move(fields));
    }
    default:
        SP_THROW(sp::InvalidArgument, "unsupported JSON value ", j.dump());
    }
}

Json toJson(const Value& value) {
    return std::visit(
        [&](const auto& v) -> Json {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, std::monostate>)
                return nullptr;
            else if constexpr (std::is_same_v<V, bool> || std::is_same_v<V, int64_t> ||
                               std::is_same_v<V, double> || std::is_same_v<V, std::string>)
                return v;
            else if constexpr (std::is_same_v<V, sp::reflect::EnumValue>)
                return v.value; // as Python's json writes an IntEnum
            else if constexpr (std::is_same_v<V, Value::List>) {
                Json out = Json::array();
                for (const Value& item : v)
                    out.push_back(toJson(item));
                return out;
            } else if constexpr (std::is_same_v<V, Value::Dict>) {
                Json out = Json::object();
                for (const auto& [key, item] : v)
                    out[key] = toJson(item);
                return out;
            } else
                SP_THROW(sp::InvalidArgument, "SpUtils::setUnrealObj(): a ", value.kindName(),
                         " cannot be sent as JSON (send arrays as packed arrays)");
        },
        value.storage());
}
} // namespace

Value SpUtils::unrealObjValue(const SpFuncDataBundle& bundle, const std::string& name) {
    auto it = bundle.unreal_obj_strings_.find(name);
    if (it == bundle.unreal_obj_strings_.end()) {
        std::string given;
        for (const auto& [key, text] : bundle.unreal_obj_strings_)
            given += (given.empty() ? "'" : ", '") + key + "'";
        SP_THROW(sp::InvalidArgument, unrealObjContext(name), " was not passed (got ",
                 given.empty() ? std::string("no objects") : given, ")");
    }
    try {
        return fromJson(Json::parse(it->second));
    } catch (const Json::exception& e) {
        SP_THROW(sp::InvalidArgument, unrealObjContext(name), " is not valid JSON: ", e.what());
    }
}

std::string SpUtils::unrealObjContext(const std::string& name) {
    return callContext("SpUtils::getUnrealObj()") + ": object '" + name + "'";
}

std::string SpUtils::toJsonText(const Value& value) {
    return toJson(value).dump();
}

void SpUtils::moveFromPackedArrays(std::initializer_list<SpArrayBase*> arrays,
                                   std::map<std::string, SpPackedArray>&& packed) {
    for (SpArrayBase* array : arrays) {
        SP_CHECK(array, sp::InvalidArgument, "SpUtils::moveFromPackedArrays(): null array");
        auto it = packed.find(array->getName());
        if (it == packed.end()) {
            std::string given;
            for (const auto& [name, value] : packed)
                given += (given.empty() ? "'" : ", '") + name + "'";
            SP_THROW(sp::InvalidArgument, callContext(), ": array '", array->getName(),
                     "' was not passed (got ", given.empty() ? std::string("no arrays") : given, ")");
        }
        array->assign(std::move(it->second), callContext());
        packed.erase(it);
    }
}

std::map<std::string, SpPackedArray> SpUtils::moveToPackedArrays(std::initializer_list<SpArrayBase*> arrays) {
    std::map<std::string, SpPackedArray> packed;
    for (SpArrayBase* array : arrays) {
        SP_CHECK(array, sp::InvalidArgument, "SpUtils::moveToPackedArrays(): null array");
        SP_CHECK(!array->getName().empty(), sp::InvalidArgument,
                 "SpUtils::moveToPackedArrays(): an array has no name");
        SP_CHECK(packed.emplace(array->getName(), array->value()).second, sp::InvalidArgument,
                 "SpUtils::moveToPackedArrays(): two arrays are named '", array->getName(), "'");
    }
    return packed;
}
