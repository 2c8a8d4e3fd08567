#pragma once
// The rule every binding layer applies before touching an engine object on behalf of a user: objects in
// a world may only be used inside a frame (begin_frame or end_frame block). Class default objects live
// outside any world and are always usable. One function, so in-process and RPC behave the same.

#include <string_view>

#include "core/reflect/object_base.h"

class UObject;
class UWorld;

namespace sp::world {

// Throws InvalidState when `object` belongs to a world whose engine is not inside a frame.
void checkObjectAccess(const reflect::ObjectBase& object, std::string_view context);

// The world a static function's WorldContextObject names: the world itself, or the world of an object in
// one (UE's convention). Throws InvalidArgument naming `function` for None or an object in no world, and
// checks access as checkObjectAccess does.
UWorld& worldOfContext(UObject* context, std::string_view function);

} // namespace sp::world
