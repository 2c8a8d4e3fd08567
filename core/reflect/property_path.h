#pragma once
// Property paths, the dynamic API's reach into an object (SPEAR's get_property / set_property): one
// implementation for both transports, so that a path means the same and fails with the same words in-process
// and over RPC.
//
//   "RelativeLocation"                          a property
//   "RelativeLocation.Z"                        a field of a struct property
//   "RootComponent.RelativeLocation.Z"          through an object reference, on the object it names
//   "Tags[1]", "Materials[0]", "Settings[key]"  an element of a list (by index) or a dict (by key)
//
// Segments compose ("Wheels[2].RelativeScale3D.X"); a dict key may be quoted ("Map['a.b']").

#include <string_view>

#include "core/reflect/object_base.h"
#include "core/reflect/type_code.h"
#include "core/reflect/value.h"

namespace sp::reflect {

struct PathValue {
    Value value;
    TypeCode type; // the declared type of what the path names
};

// Reads `path` on `object`. Throws NotFound naming the segment that is not there and where it was looked
// for (a class's property, a struct's field, a list's index, a dict's key, an object reference that is
// None), InvalidArgument for a path that does not parse; `context` opens every message.
PathValue getPath(ObjectBase& object, std::string_view path, std::string_view context);

// Writes `value` to `path` on `object`: the property holding the path's last segment (on the last object the
// path reaches) is read, changed where the path points and written back whole through its setter, which
// validates it as any write does. A dict gains a key it did not have. Throws as getPath(), and
// InvalidArgument when that property is read-only.
void setPath(ObjectBase& object, std::string_view path, Value value, std::string_view context);

} // namespace sp::reflect
