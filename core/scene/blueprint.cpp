#include "core/scene/blueprint.h"

#include <filesystem>
#include <map>
#include <vector>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/base/regular_file.h"
#include "core/reflect/registry.h"
#include "core/scene/blueprint_functions.h"
#include "core/scene/scene_io.h"
#include "core/world/actor.h"
#include "core/world/new_object.h"

namespace sp::scene {

namespace {

using Json = SceneJson;

constexpr std::string_view kBlueprintFormat = "spear.blueprint";
constexpr int kBlueprintVersion = 1;

// A loaded blueprint: its registered class and the document its objects are initialised from. Blueprints
// live as long as the process, because the registry and objects point at their classes.
struct Blueprint {
    reflect::TypeInfo type;
    Json document;
};

std::map<std::string, std::unique_ptr<Blueprint>>& blueprints() { // by canonical path
    static std::map<std::string, std::unique_ptr<Blueprint>> loaded;
    return loaded;
}

// Applies the defaults and components of `document` to `object`, a new object of the blueprint's class.
void applyBlueprint(const Json& document, reflect::ObjectBase& object, const std::string& where) {
    auto* actor = dynamic_cast<AActor*>(&object);
    const ActorsByName self = selfOf(object);
    const Json* components = optionalMember(document, "components");
    SP_CHECK(!components || components->is_array(), InvalidArgument, where,
             ": 'components' must be a list, got ", components->type_name());
    SP_CHECK(!components || components->empty() || actor, InvalidArgument, where,
             ": 'components' needs an actor parent class, not ", object.GetClass().name);
    const std::vector<Json> entries = components ? components->get<std::vector<Json>>() : std::vector<Json>{};

    // 1. Components, so that attachment and references can name any of them.
    std::vector<std::string> wheres;
    for (size_t i = 0; i < entries.size(); ++i) {
        const Json& entry = entries[i];
        const std::string name =
            stringMember(entry, "name", where + ": components[" + std::to_string(i) + "]");
        const std::string cwhere = where + ": component '" + name + "'";
        UActorComponent* existing = actor->FindComponentByName(name);
        const reflect::TypeInfo* type = nullptr;
        if (optionalMember(entry, "class")) {
            const std::string className = stringMember(entry, "class", cwhere);
            type = reflect::Registry::get().findType(className);
            SP_CHECK(type, InvalidArgument, cwhere, ": class '", className, "' is not registered");
            SP_CHECK(type->isChildOf(UActorComponent::StaticClass()) && type->create, InvalidArgument, cwhere,
                     ": class '", className, "' is not a component class that can be created");
        }
        if (existing) {
            SP_CHECK(!type || type == &existing->GetClass(), InvalidArgument, cwhere, ": class '", type->name,
                     "' differs from the class '", existing->GetClass().name, "' that ",
                     object.GetClass().name, " creates");
        } else {
            SP_CHECK(type, InvalidArgument, cwhere, ": missing 'class' (", object.GetClass().name,
                     " creates no component '", name, "')");
            actor->CreateComponent(*type, name);
        }
        wheres.push_back(cwhere);
    }
    for (size_t i = 0; i < entries.size(); ++i) {
        const Json& entry = entries[i];
        UActorComponent* component = actor->FindComponentByName(entry["name"].get<std::string>());
        const Json* parent = optionalMember(entry, "attach_parent");
        if (parent && !parent->is_null()) {
            SP_CHECK(parent->is_string(), InvalidArgument, wheres[i],
                     ": 'attach_parent' must be a component name or null, got ", parent->dump());
            auto* scene = dynamic_cast<USceneComponent*>(component);
            auto* target =
                dynamic_cast<USceneComponent*>(actor->FindComponentByName(parent->get<std::string>()));
            SP_CHECK(scene, InvalidArgument, wheres[i], ": only scene components can be attached");
            SP_CHECK(target && target != scene, InvalidArgument, wheres[i], ": attach_parent '",
                     parent->get<std::string>(), "' is not another scene component of this actor");
            if (scene->GetAttachParent() != target)
                scene->AttachToComponent(target, false);
        }
    }

    // 2. Properties, now that every component exists.
    if (const Json* properties = optionalMember(document, "properties"))
        loadObjectProperties(object, *properties, self, where);
    for (size_t i = 0; i < entries.size(); ++i)
        if (const Json* properties = optionalMember(entries[i], "properties"))
            loadObjectProperties(*actor->FindComponentByName(entries[i]["name"].get<std::string>()),
                                 *properties, self, wheres[i]);
}

Json readBlueprintFile(const std::string& path, std::string_view function, const std::string& where) {
    // A regular file of bounded size only: a FIFO or /dev/zero named here would hang the engine
    // (core/base/regular_file.h).
    const std::string text = readRegularFile(path, function, "blueprint");
    try {
        return Json::parse(text);
    } catch (const nlohmann::json::exception& error) { // a parse error, or a number out of range
        SP_THROW(InvalidArgument, where, " is not valid JSON: ", jsonErrorWithoutContents(error, text));
    }
}

} // namespace

const reflect::TypeInfo& loadBlueprint(const std::string& path, std::string_view function) {
    const std::string where = std::string(function) + ": blueprint '" + path + "'";
    // Keyed by the file itself, however it was named (a relative name, a /Game/ name, an absolute path).
    const std::string file = findAsset(path);
    std::error_code ignored;
    std::string key = std::filesystem::weakly_canonical(file, ignored).string();
    if (key.empty())
        key = file;
    if (auto it = blueprints().find(key); it != blueprints().end()) {
        // Still registered: the cached class. Gone from the registry (its native class came from a plugin
        // that was unloaded): load it afresh, which then finds the parent class, or says it is missing.
        if (reflect::Registry::get().findType(it->second->type.name) == &it->second->type)
            return it->second->type;
        blueprints().erase(it);
    }

    Json document = readBlueprintFile(file, function, where);
    SP_CHECK(document.is_object(), InvalidArgument, where, ": expected a JSON object, got ",
             document.type_name());
    const Json* format = optionalMember(document, "format");
    SP_CHECK(format && *format == kBlueprintFormat, InvalidArgument, where, ": 'format' must be \"",
             kBlueprintFormat, "\", got ", format ? format->dump() : "nothing");
    const Json* version = optionalMember(document, "version");
    SP_CHECK(version && *version == kBlueprintVersion, InvalidArgument, where, ": 'version' ",
             version ? version->dump() : "(missing)", " is not supported (expected ", kBlueprintVersion, ")");
    const std::string parentName = stringMember(document, "parent", where);
    const reflect::TypeInfo* parent = reflect::Registry::get().findType(parentName);
    SP_CHECK(parent && parent->kind == reflect::TypeInfo::Kind::Class, InvalidArgument, where,
             ": 'parent': class '", parentName, "' is not registered");
    SP_CHECK(parent->canCreate(), InvalidArgument, where, ": 'parent': class '", parentName,
             "' is abstract and cannot be a blueprint's parent");
    const std::string name = std::filesystem::path(file).stem().string();
    SP_CHECK(!reflect::Registry::get().findType(name), InvalidArgument, where, ": class name '", name,
             "' is already registered");
    for (const auto& [field, value] : document.items())
        SP_CHECK(field == "format" || field == "version" || field == "parent" || field == "doc" ||
                     field == "properties" || field == "components" || field == "functions",
                 InvalidArgument, where, ": unknown field '", field, "'");

    auto blueprint = std::make_unique<Blueprint>();
    blueprint->document = std::move(document);
    reflect::TypeInfo& type = blueprint->type;
    type.name = name;
    type.asset = key; // scene files name it, so that a scene loads its blueprints itself
    type.doc = blueprint->document.value("doc", "Blueprint " + name + " (" + path + ").");
    type.kind = reflect::TypeInfo::Kind::Class;
    type.parent = parent;
    const Json& doc = blueprint->document;
    type.initialize = [&doc, spawnWhere = "blueprint '" + path + "'"](reflect::ObjectBase& object) {
        applyBlueprint(doc, object, spawnWhere);
    };

    // Check every field now by building one object (outside any world), so a bad asset never spawns; the
    // functions are checked against it too (their targets are its components).
    {
        std::unique_ptr<UObject> trial = sp::world::newObject(*parent, "Default__" + name, nullptr);
        trial->SetDataDefinedClass(type);
        applyBlueprint(doc, *trial, where);
        if (const Json* functions = optionalMember(doc, "functions"))
            type.functions = loadBlueprintFunctions(*functions, name, *trial, where);
        reflect::ObjectTable::rememberName(*trial);
    }

    reflect::Registry::get().add(type);
    return blueprints().emplace(key, std::move(blueprint)).first->second->type;
}

} // namespace sp::scene
