#include "core/reflect/registry.h"

#include "core/base/error.h"

namespace sp::reflect {

Registry& Registry::get() {
    static Registry registry;
    return registry;
}

void Registry::add(const TypeInfo& type) {
    auto [it, inserted] = types_.emplace(type.name, &type);
    SP_CHECK(inserted || it->second == &type, InvalidArgument,
             "Registry::add(): two different types are named '", type.name, "'");
}

void Registry::add(const EnumInfo& info) {
    auto [it, inserted] = enums_.emplace(info.name, &info);
    SP_CHECK(inserted || it->second == &info, InvalidArgument,
             "Registry::add(): two different enums are named '", info.name, "'");
}

void Registry::remove(const TypeInfo& type) {
    if (auto it = types_.find(type.name); it != types_.end() && it->second == &type)
        types_.erase(it);
}

void Registry::remove(const EnumInfo& info) {
    if (auto it = enums_.find(info.name); it != enums_.end() && it->second == &info)
        enums_.erase(it);
}

const TypeInfo* Registry::findType(std::string_view name) const {
    auto it = types_.find(name);
    return it == types_.end() ? nullptr : it->second;
}

const EnumInfo* Registry::findEnum(std::string_view name) const {
    auto it = enums_.find(name);
    return it == enums_.end() ? nullptr : it->second;
}

const TypeInfo& Registry::getStruct(std::string_view name, std::string_view context) const {
    const TypeInfo* type = findType(name);
    SP_CHECK(type && type->kind == TypeInfo::Kind::Struct, NotFound, context, ": struct '", name,
             "' is not registered");
    return *type;
}

const EnumInfo& Registry::getEnum(std::string_view name, std::string_view context) const {
    const EnumInfo* info = findEnum(name);
    SP_CHECK(info, NotFound, context, ": enum '", name, "' is not registered");
    return *info;
}

const TypeInfo& Registry::getClass(std::string_view name, std::string_view context,
                                   const std::string& asset) const {
    const TypeInfo* type = findType(name);
    if (!type && !asset.empty() && loader_) {
        const TypeInfo& loaded = loader_(asset, context);
        SP_CHECK(loaded.name == name, InvalidArgument, context, ": asset '", asset, "' defines class '",
                 loaded.name, "', not '", name, "'");
        type = &loaded;
    }
    SP_CHECK(type && type->kind == TypeInfo::Kind::Class, NotFound, context, ": class '", name,
             "' is not registered");
    return *type;
}

const TypeInfo& Registry::loadClass(const std::string& asset, std::string_view context) const {
    SP_CHECK(loader_, InvalidState, context, ": no class loader is installed to load '", asset,
             "' (the engine installs the blueprint loader)");
    return loader_(asset, context);
}

std::vector<const TypeInfo*> Registry::types() const {
    std::vector<const TypeInfo*> result;
    for (const auto& [name, type] : types_)
        result.push_back(type);
    return result;
}

std::vector<const EnumInfo*> Registry::enums() const {
    std::vector<const EnumInfo*> result;
    for (const auto& [name, info] : enums_)
        result.push_back(info);
    return result;
}

std::vector<const TypeInfo*> Registry::derivedClasses(const TypeInfo& base) const {
    std::vector<const TypeInfo*> result;
    for (const auto& [name, type] : types_)
        if (type->isChildOf(base))
            result.push_back(type);
    return result;
}

} // namespace sp::reflect
