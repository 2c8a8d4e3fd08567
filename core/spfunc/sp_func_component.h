#pragma once
// USpFuncComponent: a component that holds SpFuncs, functions registered at run time under a name, each
// taking and returning an SpFuncDataBundle (the SPEAR paper's Fig. 8). Python calls them as methods of the
// owning actor (`my_actor.my_sp_func(arrays={...})`) or, type-checked, through `call_sp_func`.
// SpFuncs complement SPFUNCTIONs: they can be added and removed while the engine runs and take arrays of
// any dtype and shape, at the price of being untyped.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/spfunc/sp_func_data_bundle.h"
#include "core/world/actor_component.h"

/// Holds SpFuncs: named functions over bundles of arrays, registered at run time by C++ code.
SPCLASS()
class USpFuncComponent : public UActorComponent {
    SP_GENERATED_BODY()
  public:
    using SpFunc = std::function<SpFuncDataBundle(SpFuncDataBundle&)>;

    // Registers `func` under `name`. Throws InvalidArgument when the name is empty or already taken.
    void registerFunc(const std::string& name, SpFunc func);
    // Removes the SpFunc; throws NotFound when none has this name.
    void unregisterFunc(const std::string& name);
    bool hasFunc(const std::string& name) const { return funcs_.count(name) != 0; }

    // Calls the SpFunc `name`; `context` names the call in errors ("AMyActor.my_sp_func()").
    SpFuncDataBundle callFunc(const std::string& name, SpFuncDataBundle& args, std::string_view context);

    /// Returns the names of the SpFuncs registered now, sorted.
    SPFUNCTION()
    std::vector<std::string> GetFuncNames() const;

  private:
    std::map<std::string, SpFunc> funcs_;
};
