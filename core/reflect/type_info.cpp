#include "core/reflect/type_info.h"

#include <algorithm>

namespace sp::reflect {

bool TypeInfo::isChildOf(const TypeInfo& other) const {
    for (const TypeInfo* type = this; type; type = type->parent)
        if (type == &other)
            return true;
    return false;
}

const PropertyInfo* TypeInfo::findProperty(std::string_view propertyName) const {
    for (const TypeInfo* type = this; type; type = type->parent)
        for (const auto& property : type->properties)
            if (property.name == propertyName)
                return &property;
    return nullptr;
}

const FunctionInfo* TypeInfo::findFunction(std::string_view functionName) const {
    for (const TypeInfo* type = this; type; type = type->parent)
        for (const auto& function : type->functions)
            if (function.name == functionName)
                return &function;
    return nullptr;
}

const TypeInfo& TypeInfo::nativeClass() const {
    const TypeInfo* type = this;
    while (type->isDataDefined() && type->parent)
        type = type->parent;
    return *type;
}

void TypeInfo::initializeObject(ObjectBase& object) const {
    if (!isDataDefined())
        return;
    if (parent)
        parent->initializeObject(object);
    initialize(object);
}

namespace {
template <typename Member, typename Pick>
std::vector<const Member*> collect(const TypeInfo* type, Pick pick) {
    std::vector<const TypeInfo*> chain;
    for (; type; type = type->parent)
        chain.push_back(type);
    std::vector<const Member*> members;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        for (const auto& member : pick(**it))
            members.push_back(&member);
    return members;
}
} // namespace

std::vector<const PropertyInfo*> TypeInfo::allProperties() const {
    return collect<PropertyInfo>(
        this, [](const TypeInfo& t) -> const auto& { return t.properties; });
}

std::vector<const FunctionInfo*> TypeInfo::allFunctions() const {
    return collect<FunctionInfo>(
        this, [](const TypeInfo& t) -> const auto& { return t.functions; });
}

bool EnumInfo::contains(int64_t value) const {
    return std::any_of(entries.begin(), entries.end(),
                       [&](const auto& entry) { return entry.second == value; });
}

std::string_view EnumInfo::nameOf(int64_t value) const {
    for (const auto& [entryName, entryValue] : entries)
        if (entryValue == value)
            return entryName;
    return {};
}

} // namespace sp::reflect
