#pragma once
// Blueprints: classes defined by data. A blueprint asset is a JSON file that names a native parent class,
// property defaults for the object and for its components (by component name), and extra components:
//
//   {"format": "spear.blueprint", "version": 1, "parent": "AActor", "doc": "...",
//    "properties": {"Tags": ["axes"]},
//    "components": [
//      {"name": "Root", "class": "USceneComponent"},
//      {"name": "XAxis", "class": "UStaticMeshComponent", "attach_parent": "Root",
//       "properties": {"RelativeLocation": {"X": 50, "Y": 0, "Z": 0}, ...}}]}
//
// Values are written as in scene files (core/scene/scene_io.h); object references name the object's own
// components as "Self.Component". A component entry whose name the parent class already creates gives that
// component's defaults ("class", if present, must match it); any other entry creates a component ("class"
// required), attached to "attach_parent" when given (otherwise the first scene component is the root and
// later ones attach to it, as for any actor).
//
// "functions" declares functions made of reflected calls (core/scene/blueprint_functions.h).
//
// Loading registers a runtime class named after the file ("BP_Axes.json" -> "BP_Axes") whose parent is
// the parent class. Objects of it are created by the native class, report the blueprint class
// (ObjectBase::GetObjectClass), and get the blueprint's defaults before they begin play. Loading builds
// one object of the class to check every field, so a bad asset fails on load, not on spawn.

#include <memory>
#include <string>
#include <string_view>

#include "core/reflect/type_info.h"

class UObject;
class UWorld;

namespace sp::scene {

// Loads the blueprint at `path` (once per file; later calls return the same class) and registers its class.
// Errors name `function` and the path: sp::NotFound when the file does not exist, sp::InvalidArgument when it
// is not valid JSON or a field is wrong (unknown parent, property or component class).
const reflect::TypeInfo& loadBlueprint(const std::string& path, std::string_view function);

} // namespace sp::scene
