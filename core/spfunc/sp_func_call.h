#pragma once
// Calling SpFuncs on behalf of Python (in-process and RPC alike): an object's SpFuncs are its own when it
// is a USpFuncComponent, and those of its USpFuncComponents when it is an actor (so that Fig. 8 calls
// `my_actor.my_sp_func(...)` on the actor that owns the component).

#include <string>
#include <vector>

#include "core/reflect/object_base.h"
#include "core/spfunc/sp_func_data_bundle.h"

namespace sp::spfunc {

// The names of every SpFunc reachable from `object`, sorted and unique.
std::vector<std::string> funcNames(reflect::ObjectBase& object);

// Calls the SpFunc `name` of `object`. Throws NotFound (listing the names there are) when it has none.
SpFuncDataBundle call(reflect::ObjectBase& object, const std::string& name, SpFuncDataBundle args);

// The SpFunc being called on this thread ("AMyActor.my_sp_func()"), for error messages; empty outside.
const std::string& currentCall();

} // namespace sp::spfunc
