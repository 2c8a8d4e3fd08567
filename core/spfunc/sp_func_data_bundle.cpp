#include "core/spfunc/sp_func_data_bundle.h"

#include "core/base/error.h"

namespace sp::spfunc {

using reflect::Value;

Value toValue(SpFuncDataBundle bundle) {
    Value::Dict arrays;
    for (auto& [name, array] : bundle.packed_arrays_)
        arrays.emplace(name, Value(std::move(array)));
    Value::Dict objects;
    for (auto& [name, text] : bundle.unreal_obj_strings_)
        objects.emplace(name, Value(std::move(text)));
    return Value(Value::Dict{{"arrays", Value(std::move(arrays))},
                             {"unreal_objs", Value(std::move(objects))},
                             {"info", Value(std::move(bundle.info_))}});
}

namespace {
const Value::Dict* optionalDict(const Value::Dict& bundle, const char* key, std::string_view context) {
    auto it = bundle.find(key);
    if (it == bundle.end() || it->second.is<std::monostate>())
        return nullptr;
    SP_CHECK(it->second.is<Value::Dict>(), InvalidArgument, context, ": '", key, "' must be a dict");
    return &it->second.as<Value::Dict>();
}
} // namespace

SpFuncDataBundle bundleFromValue(const Value& value, std::string_view context) {
    SP_CHECK(value.is<Value::Dict>(), InvalidArgument, context,
             ": expected a dict with 'arrays', 'unreal_objs' and 'info'");
    const auto& dict = value.as<Value::Dict>();
    for (const auto& [key, item] : dict)
        SP_CHECK(key == "arrays" || key == "unreal_objs" || key == "info", InvalidArgument, context,
                 ": unexpected key '", key, "' (expected 'arrays', 'unreal_objs' and 'info')");
    SpFuncDataBundle bundle;
    if (const Value::Dict* arrays = optionalDict(dict, "arrays", context)) {
        for (const auto& [name, item] : *arrays) {
            SP_CHECK(item.is<reflect::ArrayValue>(), InvalidArgument, context, ": arrays['", name,
                     "'] must be a numpy array");
            bundle.packed_arrays_.emplace(name, item.as<reflect::ArrayValue>());
        }
    }
    if (const Value::Dict* objects = optionalDict(dict, "unreal_objs", context)) {
        for (const auto& [name, item] : *objects) {
            SP_CHECK(item.is<std::string>(), InvalidArgument, context, ": unreal_objs['", name,
                     "'] must be a JSON string");
            bundle.unreal_obj_strings_.emplace(name, item.as<std::string>());
        }
    }
    if (auto it = dict.find("info"); it != dict.end() && !it->second.is<std::monostate>()) {
        SP_CHECK(it->second.is<std::string>(), InvalidArgument, context, ": 'info' must be a string");
        bundle.info_ = it->second.as<std::string>();
    }
    return bundle;
}

} // namespace sp::spfunc
