#pragma once
// SpFuncDataBundle: what an SpFunc takes and returns (the SPEAR paper's Fig. 8). Named arrays of any dtype
// (packed_arrays_), named objects as JSON text (unreal_obj_strings_), and a free-form string (info_).
// In Python the same bundle is the dict {"arrays": {...}, "unreal_objs": {...}, "info": "..."}.

#include <map>
#include <string>
#include <string_view>

#include "core/reflect/value.h"

// A packed array is an untyped, named-by-key array: dtype, shape and shared storage, never copied when
// it moves between C++, numpy and shared memory.
using SpPackedArray = sp::reflect::ArrayValue;

struct SpFuncDataBundle {
    std::map<std::string, SpPackedArray> packed_arrays_;
    std::map<std::string, std::string> unreal_obj_strings_;
    std::string info_;
};

namespace sp::spfunc {

// The bundle as a Value: Dict{"arrays": Dict of arrays, "unreal_objs": Dict of strings, "info": string}.
reflect::Value toValue(SpFuncDataBundle bundle);
// The inverse; every missing field is empty. Throws InvalidArgument naming `context` and the bad field.
SpFuncDataBundle bundleFromValue(const reflect::Value& value, std::string_view context);

} // namespace sp::spfunc
