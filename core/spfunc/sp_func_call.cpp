#include "core/spfunc/sp_func_call.h"

#include <algorithm>

#include "core/base/error.h"
#include "core/spfunc/sp_func_component.h"
#include "core/world/actor.h"

namespace sp::spfunc {

namespace detail {
extern thread_local std::string currentCall;
} // namespace detail

namespace {
// The SpFunc components reachable from `object`, in the order they are searched.
std::vector<USpFuncComponent*> components(reflect::ObjectBase& object) {
    if (auto* component = dynamic_cast<USpFuncComponent*>(&object))
        return {component};
    std::vector<USpFuncComponent*> found;
    if (auto* actor = dynamic_cast<AActor*>(&object))
        for (const auto& component : actor->GetComponentList())
            if (auto* spFuncs = dynamic_cast<USpFuncComponent*>(component.get()))
                found.push_back(spFuncs);
    return found;
}
} // namespace

std::vector<std::string> funcNames(reflect::ObjectBase& object) {
    std::vector<std::string> names;
    for (USpFuncComponent* component : components(object))
        for (std::string& name : component->GetFuncNames())
            names.push_back(std::move(name));
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

SpFuncDataBundle call(reflect::ObjectBase& object, const std::string& name, SpFuncDataBundle args) {
    const std::string context = object.GetClass().name + "." + name + "()";
    for (USpFuncComponent* component : components(object)) {
        if (!component->hasFunc(name))
            continue;
        try {
            return component->callFunc(name, args, context);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            // Whatever else an SpFunc's code throws (std::out_of_range from a map's at(), ...) becomes an
            // engine error naming the SpFunc, the same on both transports.
            SP_THROW(Error, context, ": ", e.what());
        }
    }
    std::string known;
    for (const std::string& n : funcNames(object))
        known += (known.empty() ? "'" : ", '") + n + "'";
    SP_THROW(NotFound, context, ": ", object.GetDebugName(), " has no SpFunc named '", name, "' (it has ",
             known.empty() ? std::string("none") : known, ")");
}

const std::string& currentCall() {
    return detail::currentCall;
}

} // namespace sp::spfunc
