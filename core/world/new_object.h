#pragma once
// newObject: the one way the engine makes a reflected object of a class known at run time, native or
// data-defined (a blueprint, core/scene/blueprint.h, whose type carries its defaults).

#include <memory>
#include <string>

#include "core/reflect/type_info.h"

class UObject;
class UWorld;

namespace sp::world {

// Creates an object of `type` called `name` in `world` (nullptr: outside any world), with the defaults of a
// data-defined class applied. An actor is not in the world yet: UWorld adds it.
std::unique_ptr<UObject> newObject(const reflect::TypeInfo& type, std::string name, UWorld* world);

} // namespace sp::world
