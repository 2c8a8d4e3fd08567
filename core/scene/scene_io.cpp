#include "core/scene/scene_io.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/base/progress.h"
#include "core/base/regular_file.h"
#include "core/reflect/registry.h"
#include "core/scene/blueprint.h"
#include "core/world/static_mesh_component.h"
#include "core/world/world.h"

namespace sp::scene {

namespace {

using reflect::Value;
using Json = SceneJson;

constexpr std::string_view kSceneFormat = "spear.scene";
constexpr int kSceneVersion = 1;

// --- property types ---------------------------------------------------------------------------
// Values are saved and loaded by their property's declared type (reflect::TypeCode).

using reflect::TypeCode;
using Kind = TypeCode::Kind;

// The name path of an object inside a scene: "Actor" or "Actor.Component".
std::string objectPath(const reflect::ObjectBase& object) {
    if (const auto* actor = dynamic_cast<const AActor*>(&object))
        return actor->GetName();
    if (const auto* component = dynamic_cast<const UActorComponent*>(&object))
        if (component->GetOwner())
            return component->GetOwner()->GetName() + "." + component->GetName();
    SP_THROW(InvalidArgument, object.GetDebugName(),
             " is neither an actor nor a component and cannot be saved");
}

Json toJson(const Value& value, const TypeCode& type) {
    if (value.isNone())
        return nullptr;
    if (type.kind == Kind::List) {
        Json out = Json::array();
        for (const Value& item : value.as<Value::List>())
            out.push_back(toJson(item, type.elementType()));
        return out;
    }
    if (type.kind == Kind::Dict) {
        Json out = Json::object();
        for (const auto& [key, item] : value.as<Value::Dict>())
            out[key] = toJson(item, type.elementType());
        return out;
    }
    if (const auto* name = value.tryAs<reflect::ClassName>())
        return name->name;
    if (const auto* handle = value.tryAs<reflect::ObjectHandle>()) {
        const reflect::ObjectBase* object = reflect::ObjectTable::find(*handle);
        SP_CHECK(object, InvalidArgument, "refers to a destroyed object");
        return objectPath(*object);
    }
    if (type.kind == Kind::Enum) {
        const reflect::EnumInfo& info = reflect::Registry::get().getEnum(type.name, "toJson()");
        const int64_t number = value.as<reflect::EnumValue>().value;
        const std::string_view entry = info.nameOf(number);
        SP_CHECK(!entry.empty(), InvalidArgument, number, " is not a value of ", info.name);
        return std::string(entry);
    }
    if (type.kind == Kind::Struct) {
        const reflect::TypeInfo& info = reflect::Registry::get().getStruct(type.name, "toJson()");
        Json out = Json::object();
        const auto& fields = value.as<Value::Dict>();
        for (const reflect::PropertyInfo* field : info.allProperties())
            out[field->name] = toJson(fields.at(field->name), field->type);
        return out;
    }
    return std::visit(
        [&](const auto& v) -> Json {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, bool> || std::is_same_v<V, int64_t> ||
                          std::is_same_v<V, double> || std::is_same_v<V, std::string>)
                return v;
            else
                SP_THROW(InvalidArgument, "a ", value.kindName(), " (type ", type.spelling(),
                         ") cannot be saved in a scene");
        },
        value.storage());
}

std::string jsonKind(const Json& j) {
    return j.type_name();
}

// Resolves name paths against the actors being loaded (ActorsByName).

reflect::ObjectBase* resolvePath(std::string_view path, const ActorsByName& actors) {
    const size_t dot = path.find('.');
    auto it = actors.find(path.substr(0, dot));
    SP_CHECK(it != actors.end(), InvalidArgument, "no actor '", path.substr(0, dot), "' in the scene");
    if (dot == std::string_view::npos)
        return it->second;
    const std::string_view componentName = path.substr(dot + 1);
    if (UActorComponent* component = it->second->FindComponentByName(componentName))
        return component;
    SP_THROW(InvalidArgument, "actor '", it->first, "' has no component '", componentName, "'");
}

Value fromJson(const Json& j, const TypeCode& type, const ActorsByName& actors) {
    if (type.optional && j.is_null())
        return Value();
    auto expect = [&](bool ok, std::string_view what) {
        SP_CHECK(ok, InvalidArgument, "expected ", what, " (", type.spelling(), "), got ", jsonKind(j), " ",
                 j.dump());
    };
    switch (type.kind) {
    case Kind::List: {
        expect(j.is_array(), "a list");
        Value::List out;
        for (const Json& item : j)
            out.push_back(fromJson(item, type.elementType(), actors));
        return out;
    }
    case Kind::Dict: {
        expect(j.is_object(), "an object");
        Value::Dict out;
        for (const auto& [key, item] : j.items())
            out.emplace(key, fromJson(item, type.elementType(), actors));
        return out;
    }
    case Kind::Bool:
        expect(j.is_boolean(), "a bool");
        return j.get<bool>();
    case Kind::Int:
        expect(j.is_number_integer(), "an integer");
        return j.get<int64_t>();
    case Kind::Float:
        expect(j.is_number(), "a number");
        return j.get<double>();
    case Kind::Str:
        expect(j.is_string(), "a string");
        return j.get<std::string>();
    case Kind::Class:
        expect(j.is_string(), "a class name");
        return reflect::ClassName{j.get<std::string>()};
    case Kind::Enum: {
        const reflect::EnumInfo& info = reflect::Registry::get().getEnum(type.name, "fromJson()");
        expect(j.is_string(), "an entry name");
        for (const auto& [name, number] : info.entries)
            if (name == j.get<std::string>())
                return reflect::EnumValue{info.name, number};
        SP_THROW(InvalidArgument, "'", j.get<std::string>(), "' is not an entry of ", info.name);
    }
    case Kind::Struct: {
        const reflect::TypeInfo& info = reflect::Registry::get().getStruct(type.name, "fromJson()");
        expect(j.is_object(), "an object");
        Value::Dict out;
        for (const auto& [key, item] : j.items()) {
            const reflect::PropertyInfo* field = info.findProperty(key);
            SP_CHECK(field, InvalidArgument, type.name, " has no field '", key, "'");
            out.emplace(key, fromJson(item, field->type, actors));
        }
        return out;
    }
    case Kind::Object:
        expect(j.is_string(), "an object path");
        return resolvePath(j.get<std::string>(), actors)->GetHandle();
    case Kind::Void:
    case Kind::Array:
        break;
    }
    SP_THROW(InvalidArgument, "type '", type.spelling(), "' cannot be loaded from a scene");
}

// --- saving -----------------------------------------------------------------------------------

Json saveProperties(const reflect::ObjectBase& object, const std::string& where) {
    Json out = Json::object();
    for (const reflect::PropertyInfo* property : object.GetClass().allProperties()) {
        try {
            out[property->name] = toJson(property->get(&object), property->type);
        } catch (const Error& error) {
            SP_THROW(InvalidArgument, where, ": property '", property->name, "': ", error.what());
        }
    }
    return out;
}

// --- loading ----------------------------------------------------------------------------------

const Json& member(const Json& object, const char* key, const std::string& where) {
    SP_CHECK(object.is_object(), InvalidArgument, where, ": expected an object, got ", jsonKind(object));
    auto it = object.find(key);
    SP_CHECK(it != object.end(), InvalidArgument, where, ": missing '", key, "'");
    return *it;
}

} // namespace

const Json* optionalMember(const Json& object, const char* key) {
    if (!object.is_object())
        return nullptr;
    auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

std::string stringMember(const Json& object, const char* key, const std::string& where) {
    const Json& value = member(object, key, where);
    SP_CHECK(value.is_string() && !value.get<std::string>().empty(), InvalidArgument, where, ": '", key,
             "' must be a non-empty string, got ", value.dump());
    return value.get<std::string>();
}

namespace {

const reflect::TypeInfo& classMember(const Json& object, const reflect::TypeInfo& base,
                                     const std::string& where) {
    const std::string name = stringMember(object, "class", where);
    const reflect::TypeInfo* type = reflect::Registry::get().findType(name);
    SP_CHECK(type, InvalidArgument, where, ": class '", name, "' is not registered");
    SP_CHECK(type->isChildOf(base) && type->canCreate(), InvalidArgument, where, ": class '", name,
             "' is not a ", base.name, " class that can be created");
    return *type;
}

} // namespace

Value valueFromJson(const Json& json, const TypeCode& type, const ActorsByName& actors) {
    return fromJson(json, type, actors);
}

void loadObjectProperties(reflect::ObjectBase& object, const Json& properties, const ActorsByName& actors,
                          const std::string& where) {
    SP_CHECK(properties.is_object(), InvalidArgument, where, ": 'properties' must be an object, got ",
             jsonKind(properties));
    const reflect::TypeInfo& type = object.GetClass();
    for (const auto& [name, json] : properties.items()) {
        const reflect::PropertyInfo* property = type.findProperty(name);
        SP_CHECK(property, InvalidArgument, where, ": ", type.name, " has no property '", name, "'");
        try {
            if (property->readOnly) {
                // Set by construction; a different value means the file does not match the class.
                const Json actual = toJson(property->get(&object), property->type);
                SP_CHECK(actual == json, InvalidArgument, "read-only property is ", actual.dump(),
                         " after construction, not ", json.dump());
                continue;
            }
            property->set(&object, fromJson(json, property->type, actors));
        } catch (const NotFound& error) { // a file it names (a mesh): the kind a missing file has everywhere
            SP_THROW(NotFound, where, ": property '", name, "': ", error.what());
        } catch (const Error& error) {
            SP_THROW(InvalidArgument, where, ": property '", name, "': ", error.what());
        }
    }
}

SceneJson saveScene(const UWorld& world) {
    Json actors = Json::array();
    for (AActor* actor : world.find_actors()) {
        if (!actor->GetStreamingLevelName().empty())
            continue; // in its level's file
        const std::string where = "actor '" + actor->GetName() + "'";
        Json entry = Json::object();
        entry["name"] = actor->GetName();
        entry["class"] = actor->GetObjectClass().name;
        if (actor->GetObjectClass().isDataDefined())
            entry["blueprint"] = actor->GetObjectClass().asset;
        entry["properties"] = saveProperties(*actor, where);
        Json components = Json::array();
        for (const auto& component : actor->GetComponentList()) {
            Json c = Json::object();
            c["name"] = component->GetName();
            c["class"] = component->GetObjectClass().name;
            const auto* scene = dynamic_cast<const USceneComponent*>(component.get());
            c["attach_parent"] =
                scene && scene->GetAttachParent() ? Json(scene->GetAttachParent()->GetName()) : Json(nullptr);
            c["properties"] =
                saveProperties(*component, where + ": component '" + component->GetName() + "'");
            components.push_back(std::move(c));
        }
        entry["components"] = std::move(components);
        actors.push_back(std::move(entry));
    }
    Json scene = Json::object();
    scene["format"] = kSceneFormat;
    scene["version"] = kSceneVersion;
    scene["actors"] = std::move(actors);
    if (!world.GetStreamingLevels().empty()) {
        Json levels = Json::array();
        for (const UWorld::StreamingLevel& level : world.GetStreamingLevels())
            levels.push_back(
                Json{{"name", level.name}, {"path", level.declaredPath}, {"loaded", level.loaded}});
        scene["levels"] = std::move(levels);
    }
    return scene;
}

std::string sceneToString(const SceneJson& scene) {
    return scene.dump(2) + "\n";
}

namespace {

// Checks the document's header and builds its actors, with their components, attachments and properties,
// outside the world. `inWorld`: the names must not be used by the world's actors either.
// `directory` is the scene file's folder (empty for a document not read from a file): the meshes it names
// by relative paths are looked for there first (UStaticMeshComponent::SceneFolderScope).
std::vector<std::unique_ptr<AActor>> stageActors(UWorld& world, const Json& scene, const std::string& root,
                                                 bool inWorld, const std::string& directory) {
    SP_CHECK(scene.is_object(), InvalidArgument, root, ": expected a JSON object, got ", jsonKind(scene));
    const Json& format = member(scene, "format", root);
    SP_CHECK(format == kSceneFormat, InvalidArgument, root, ": 'format' must be \"", kSceneFormat, "\", got ",
             format.dump());
    const Json& version = member(scene, "version", root);
    SP_CHECK(version == kSceneVersion, InvalidArgument, root, ": 'version' ", version.dump(),
             " is not supported (expected ", kSceneVersion, ")");
    const Json& actorList = member(scene, "actors", root);
    SP_CHECK(actorList.is_array(), InvalidArgument, root, ": 'actors' must be a list, got ",
             jsonKind(actorList));

    // Each actor counts twice: its structure, then its properties (which may import meshes).
    base::Progress progress(root + ": loading " + std::to_string(actorList.size()) + " actors",
                            2.0 * double(actorList.size()));

    // 1. Structure: every actor and component, so that references can point anywhere in the scene.
    std::vector<std::unique_ptr<AActor>> staged;
    ActorsByName byName;
    std::vector<std::string> wheres;
    for (size_t i = 0; i < actorList.size(); ++i) {
        const Json& entry = actorList[i];
        std::string where = root + ": actors[" + std::to_string(i) + "]";
        const std::string name = stringMember(entry, "name", where);
        where += " '" + name + "'";
        SP_CHECK(!byName.contains(name), InvalidArgument, where, ": the name is used by another actor");
        SP_CHECK(!inWorld || !world.find_actor_by_name(name), InvalidArgument, where,
                 ": the name is used by an actor of the world");
        // An actor of a blueprint names its asset: loading the scene loads the blueprint if needed.
        if (const auto blueprint = entry.find("blueprint");
            blueprint != entry.end() && blueprint->is_string() &&
            !reflect::Registry::get().findType(stringMember(entry, "class", where)))
            loadBlueprint(blueprint->get<std::string>(), where);
        const reflect::TypeInfo& type = classMember(entry, AActor::StaticClass(), where);
        staged.push_back(world.NewActorDeferred(type, name));
        AActor& actor = *staged.back();
        byName.emplace(name, &actor);
        const Json& components = member(entry, "components", where);
        SP_CHECK(components.is_array(), InvalidArgument, where, ": 'components' must be a list");
        for (const Json& c : components) {
            const std::string componentName = stringMember(c, "name", where + ": component");
            const std::string cwhere = where + ": component '" + componentName + "'";
            const reflect::TypeInfo& ctype = classMember(c, UActorComponent::StaticClass(), cwhere);
            UActorComponent* existing = world.get_component_by_name(&actor, componentName);
            if (existing)
                SP_CHECK(&existing->GetClass() == &ctype, InvalidArgument, cwhere, ": class '", ctype.name,
                         "' differs from the class '", existing->GetClass().name, "' that ", type.name,
                         " creates");
            else
                actor.CreateComponent(ctype, componentName);
        }
        // Attachment once all of the actor's components exist (a parent may come after its child).
        for (const Json& c : components) {
            const std::string componentName = c["name"].get<std::string>();
            const std::string cwhere = where + ": component '" + componentName + "'";
            auto* component =
                dynamic_cast<USceneComponent*>(world.get_component_by_name(&actor, componentName));
            const Json& parent = c.contains("attach_parent") ? c["attach_parent"] : Json(nullptr);
            if (!component) {
                SP_CHECK(parent.is_null(), InvalidArgument, cwhere,
                         ": only scene components can be attached");
                continue;
            }
            if (parent.is_null()) {
                component->DetachFromComponent(false);
                continue;
            }
            SP_CHECK(parent.is_string(), InvalidArgument, cwhere, ": 'attach_parent' must be a name or null");
            auto* target = dynamic_cast<USceneComponent*>(
                world.get_component_by_name(&actor, parent.get<std::string>()));
            SP_CHECK(target, InvalidArgument, cwhere, ": attach_parent '", parent.get<std::string>(),
                     "' is not a scene component of this actor");
            if (component->GetAttachParent() != target)
                component->AttachToComponent(target, false);
        }
        wheres.push_back(std::move(where));
        progress.advance();
    }

    // 2. Properties, now that every reference target exists; a relative mesh file is looked for in the
    // scene's folder first (UStaticMeshComponent::SetStaticMesh()).
    const UStaticMeshComponent::SceneFolderScope meshFolder(directory);
    for (size_t i = 0; i < actorList.size(); ++i) {
        progress.advance();
        const Json& entry = actorList[i];
        AActor& actor = *staged[i];
        if (entry.contains("properties"))
            loadObjectProperties(actor, entry["properties"], byName, wheres[i]);
        for (const Json& c : entry["components"]) {
            const std::string componentName = c["name"].get<std::string>();
            UActorComponent* component = world.get_component_by_name(&actor, componentName);
            if (c.contains("properties"))
                loadObjectProperties(*component, c["properties"], byName,
                                     wheres[i] + ": component '" + componentName + "'");
        }
    }

    return staged;
}

std::vector<UWorld::StreamingLevel> sceneLevels(const Json& scene, const std::string& root,
                                                const std::string& directory) {
    std::vector<UWorld::StreamingLevel> levels;
    const auto list = scene.find("levels");
    if (list == scene.end())
        return levels;
    SP_CHECK(list->is_array(), InvalidArgument, root, ": 'levels' must be a list, got ", jsonKind(*list));
    for (size_t i = 0; i < list->size(); ++i) {
        const Json& entry = (*list)[i];
        const std::string where = root + ": levels[" + std::to_string(i) + "]";
        SP_CHECK(entry.is_object(), InvalidArgument, where, ": expected an object, got ", jsonKind(entry));
        UWorld::StreamingLevel level;
        level.name = stringMember(entry, "name", where);
        level.declaredPath = stringMember(entry, "path", where);
        SP_CHECK(!level.name.empty() && !level.declaredPath.empty(), InvalidArgument, where,
                 ": 'name' and 'path' must not be empty");
        for (const UWorld::StreamingLevel& other : levels)
            SP_CHECK(other.name != level.name, InvalidArgument, where, ": level '", level.name,
                     "' is declared twice");
        const std::filesystem::path declared(level.declaredPath);
        level.path = declared.is_absolute() || directory.empty()
                         ? level.declaredPath
                         : (std::filesystem::path(directory) / declared).lexically_normal().string();
        const auto loaded = entry.find("loaded");
        SP_CHECK(loaded == entry.end() || loaded->is_boolean(), InvalidArgument, where,
                 ": 'loaded' must be true or false");
        level.loaded = loaded != entry.end() && loaded->get<bool>();
        levels.push_back(std::move(level));
    }
    return levels;
}

} // namespace

void loadScene(UWorld& world, const SceneJson& scene, std::string_view source, const std::string& directory) {
    const std::string root(source);
    std::vector<std::unique_ptr<AActor>> staged = stageActors(world, scene, root, false, directory);
    std::vector<UWorld::StreamingLevel> levels = sceneLevels(scene, root, directory);
    // The levels marked loaded are read and built now too, with the scene's own actors, so that one that
    // fails leaves the world as it was; their names must be free among all of them.
    std::set<std::string, std::less<>> names;
    for (const auto& actor : staged)
        names.insert(actor->GetName());
    for (const UWorld::StreamingLevel& level : levels) {
        if (!level.loaded)
            continue;
        const std::string where = root + ": streaming level '" + level.name + "'";
        for (auto& actor :
             stageActors(world, readSceneFile(level.path, where), where, false, sceneFolder(level.path))) {
            SP_CHECK(names.insert(actor->GetName()).second, InvalidArgument, where, ": actor '",
                     actor->GetName(),
                     "': the name is used by another actor of the scene or its loaded levels");
            actor->SetStreamingLevelName(level.name);
            staged.push_back(std::move(actor));
        }
    }
    // Only now does the world change, once every actor has begun play (ReplaceActors: one that fails to,
    // as one whose physics settings Bullet refuses, leaves the world as it was).
    try {
        world.ReplaceActors(std::move(staged));
    } catch (const Error&) {
        rethrowWithPrefix(root + ": ");
    }
    world.SetStreamingLevels(std::move(levels));
}

std::vector<std::unique_ptr<AActor>> stageLevel(UWorld& world, const SceneJson& scene,
                                                std::string_view source, const std::string& directory) {
    return stageActors(world, scene, std::string(source), true, directory);
}

std::string jsonErrorWithoutContents(const nlohmann::json::exception& error, std::string_view text) {
    std::string message = error.what();
    // A number past a double's range (1e400): the library names the token, not where it is. Found again (the
    // first number so spelt is where parsing stopped), it gives the line and column; the token is not echoed.
    if (message.rfind("[json.exception.out_of_range.406] number overflow parsing '", 0) == 0) {
        const std::size_t open = message.find('\'') + 1;
        const std::string token = message.substr(open, message.rfind('\'') - open);
        std::string where;
        if (const std::size_t at = text.find(token); !token.empty() && at != std::string_view::npos) {
            const std::string_view before = text.substr(0, at);
            const std::size_t line = std::size_t(std::count(before.begin(), before.end(), '\n')) + 1;
            const std::size_t lineStart = before.rfind('\n');
            const std::size_t column = lineStart == std::string_view::npos ? at : at - lineStart - 1;
            where = " at line " + std::to_string(line) + ", column " + std::to_string(column);
        }
        return "a number" + where + " is out of a double's range (at most about 1.8e308)";
    }
    if (const std::size_t tag = message.find("] ");
        message.rfind("[json.exception", 0) == 0 && tag != std::string::npos)
        message.erase(0, tag + 2);
    if (const std::size_t lastRead = message.find("; last read"); lastRead != std::string::npos)
        message.erase(lastRead);
    return message;
}

std::string sceneFolder(const std::string& path) {
    // Absolute, so that what is resolved against it (meshes, loaded later) survives a change of directory.
    std::error_code error;
    const std::filesystem::path folder = std::filesystem::path(findAsset(path)).parent_path();
    const std::filesystem::path absolute = std::filesystem::absolute(folder, error);
    return (error ? folder : absolute).lexically_normal().string();
}

SceneJson readSceneFile(const std::string& path, std::string_view function) {
    // A regular file of bounded size only: a FIFO or /dev/zero named here would hang the engine
    // (core/base/regular_file.h).
    const std::string text = readRegularFile(findAsset(path), function, "scene file");
    try {
        return Json::parse(text);
    } catch (const nlohmann::json::exception& error) { // a parse error, or a number out of range
        SP_THROW(InvalidArgument, function, ": scene file '", path,
                 "' is not valid JSON: ", jsonErrorWithoutContents(error, text));
    }
}

} // namespace sp::scene
