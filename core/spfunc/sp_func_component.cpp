#include "core/spfunc/sp_func_component.h"

#include "core/base/error.h"
#include "core/spfunc/sp_func_call.h"

namespace sp::spfunc::detail {
// The SpFunc running on this thread, so that SpUtils can name it in errors without being told.
thread_local std::string currentCall;
} // namespace sp::spfunc::detail

void USpFuncComponent::registerFunc(const std::string& name, SpFunc func) {
    SP_CHECK(!name.empty(), sp::InvalidArgument, "USpFuncComponent::registerFunc(): the name is empty");
    SP_CHECK(func, sp::InvalidArgument, "USpFuncComponent::registerFunc('", name,
             "'): the function is empty");
    SP_CHECK(!funcs_.count(name), sp::InvalidArgument, "USpFuncComponent::registerFunc(): '", name,
             "' is already registered on ", GetDebugName());
    funcs_.emplace(name, std::move(func));
}

void USpFuncComponent::unregisterFunc(const std::string& name) {
    SP_CHECK(funcs_.erase(name) == 1, sp::NotFound, "USpFuncComponent::unregisterFunc(): no SpFunc named '",
             name, "' on ", GetDebugName());
}

SpFuncDataBundle USpFuncComponent::callFunc(const std::string& name, SpFuncDataBundle& args,
                                            std::string_view context) {
    auto it = funcs_.find(name);
    SP_CHECK(it != funcs_.end(), sp::NotFound, context, ": no SpFunc named '", name, "' on ", GetDebugName());
    // Copy the function: an SpFunc may unregister itself while it runs.
    SpFunc func = it->second;
    struct Scope {
        std::string previous;
        explicit Scope(std::string_view now) : previous(std::move(sp::spfunc::detail::currentCall)) {
            sp::spfunc::detail::currentCall = std::string(now);
        }
        ~Scope() { sp::spfunc::detail::currentCall = std::move(previous); }
    } scope(context);
    return func(args);
}

std::vector<std::string> USpFuncComponent::GetFuncNames() const {
    std::vector<std::string> names;
    for (const auto& [name, func] : funcs_)
        names.push_back(name);
    return names;
}
