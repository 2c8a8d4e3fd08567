#pragma once
// Functions a blueprint declares (core/scene/blueprint.h): each a list of reflected calls on the object and
// its components, with typed parameters, named results and a result. They are registered on the
// blueprint's class, so they are called by name as generated functions are (call_function in-process,
// "call" over RPC), and the generator types them in the blueprint's stub class (codegen/blueprints.py):
//
//   "functions": [{"name": "Launch", "doc": "Throws the crate up at Speed m/s; returns where it was.",
//                  "params": [{"name": "Speed", "type": "float", "default": 5.0}],
//                  "returns": "FVector",
//                  "body": [{"call": "GetActorLocation", "result": "Where"},
//                           {"call": "StaticMeshComponent.SetPhysicsLinearVelocity",
//                            "args": {"NewVel": {"X": 0.0, "Y": 0.0, "Z": "$Speed"}}},
//                           {"return": "$Where"}]}]
//
// A step calls a function of the object ("GetActorLocation") or of one of its components by name
// ("StaticMeshComponent.SetPhysicsLinearVelocity"). Arguments are written as in scene files (structs as
// objects, enums by entry name, "Self" or "Self.Component" for objects); a string "$Name" anywhere in them
// stands for a parameter or an earlier step's "result" ("$$" starts a literal "$"). A "return" step, last,
// gives the result when "returns" declares its type. Types are "bool", "int", "float", "str", or the name
// of a reflected struct, enum or class (an object of it, or None).
//
// Everything is checked when the blueprint loads, against an object of it: the targets and functions, the
// argument names and values, that each "$Name" is set before it is used and has the type asked for there,
// and the result. A function that throws when called names the blueprint function and the step.

#include <string>
#include <vector>

#include "core/reflect/type_info.h"
#include "core/scene/scene_io.h"

namespace sp::scene {

// The names a blueprint's values may start their object paths with: "Self", `object` when it is an actor.
ActorsByName selfOf(reflect::ObjectBase& object);

// The functions of a blueprint document's "functions" list for class `className`, checked against
// `prototype` (an object of the class, its components made). Errors are sp::InvalidArgument prefixed by
// `where` and naming the function, step and field.
std::vector<reflect::FunctionInfo> loadBlueprintFunctions(const SceneJson& functions,
                                                          const std::string& className,
                                                          reflect::ObjectBase& prototype,
                                                          const std::string& where);

} // namespace sp::scene
