#pragma once
// Scene files: a world's actors and components written through the reflection registry, so every
// reflected property of every actor and component round-trips with no per-class code. The format
// (JSON, 2-space indent, properties in declaration order, parents first):
//
//   {"format": "spear.scene", "version": 1, "actors": [
//     {"name": "Floor", "class": "AStaticMeshActor", "properties": {"Tags": [], ...},
//      "components": [{"name": "StaticMeshComponent", "class": "UStaticMeshComponent",
//                      "attach_parent": null, "properties": {"RelativeLocation": {"X": 0, ...}, ...}}]}]}
//
// Enums are written by entry name, structs as objects, object references as name paths ("Floor" for an
// actor, "Floor.StaticMeshComponent" for a component, null for None), classes by name. Read-only
// properties are written for the reader's benefit and checked, not set, on load (construction gives
// them their value). Saving what was loaded gives the same bytes.
//
// A scene may declare streaming levels after its actors: "levels": [{"name": "Kitchen", "path":
// "kitchen.json", "loaded": false}] (paths relative to the scene file). A level's own actors are not
// written with the scene's: they are in the level's file.

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

class AActor;
class UWorld;

namespace sp::reflect {
class ObjectBase;
class Value;
struct TypeCode;
} // namespace sp::reflect

namespace sp::scene {

using SceneJson = nlohmann::ordered_json;

// The world's actors as a scene document.
SceneJson saveScene(const UWorld& world);

// "parse error at line 3, column 7: syntax error while parsing value - invalid literal": the parser's
// message without the text it last read, so that naming a file that is not JSON (a key, /etc/shadow)
// tells where it stopped being JSON, never what the file holds. A number past a double's range ("1e400"),
// which the parser reports by its text alone, is found in `text` for its line and column.
std::string jsonErrorWithoutContents(const nlohmann::json::exception& error, std::string_view text);
// The scene document as text (what save_scene writes): 2-space indent and a final newline.
std::string sceneToString(const SceneJson& scene);
// Replaces the world's actors and streaming levels by those of the scene document, and loads the levels
// it marks loaded. Everything is checked and built before the world is touched, so a bad document
// leaves the world as it was. `source` names the document in messages ("scene 'x.json'"); errors are
// sp::InvalidArgument naming the actor, component and property. Relative level paths are read from
// `directory` (the scene file's folder), where relative mesh paths are looked for first too.
void loadScene(UWorld& world, const SceneJson& scene, std::string_view source,
               const std::string& directory = "");
// The actors of a streaming level's document, built and checked but not in the world (UWorld::AddActors
// puts them in): the document's "levels" are not read, and its names must not be used in the world.
// `directory` is the level file's folder, where its meshes named by relative paths are looked for first.
std::vector<std::unique_ptr<AActor>> stageLevel(UWorld& world, const SceneJson& scene,
                                                std::string_view source, const std::string& directory);
// The folder of the scene file `path` names (through the asset search path, core/base/asset_path.h).
std::string sceneFolder(const std::string& path);
// Actors by name, for resolving object references ("Actor" or "Actor.Component") in property values.
using ActorsByName = std::map<std::string, AActor*, std::less<>>;
// Sets each property of `properties` (a JSON object of name -> value in the scene-file format) on
// object; read-only properties are checked, not set. Errors are sp::InvalidArgument prefixed by `where`
// and naming the property. Blueprints (core/scene/blueprint.h) share this with scene files.
void loadObjectProperties(reflect::ObjectBase& object, const SceneJson& properties,
                          const ActorsByName& actors, const std::string& where);
// A value written as in scene files (enums by entry name, structs as objects, objects as name paths
// resolved against `actors`), as the Value a property or parameter of declared `type` takes. Errors are
// sp::InvalidArgument naming what was expected and what was found.
reflect::Value valueFromJson(const SceneJson& json, const reflect::TypeCode& type,
                             const ActorsByName& actors);
// Members of a JSON object, shared by scene files and blueprints: `key`'s value, or null when `object` is
// not an object or has no `key`; `key`'s value, a non-empty string, or sp::InvalidArgument prefixed by
// `where` when `object` is not an object, has no `key` or its value is not a non-empty string.
const SceneJson* optionalMember(const SceneJson& object, const char* key);
std::string stringMember(const SceneJson& object, const char* key, const std::string& where);
// Reads and parses a scene file; sp::NotFound when it does not exist, sp::InvalidArgument when it is
// not JSON. `function` names the caller in messages.
SceneJson readSceneFile(const std::string& path, std::string_view function);

} // namespace sp::scene
