#include "core/spfunc/sp_utils.h"

#include "core/base/error.h"
#include "core/spfunc/sp_func_call.h"

namespace {
std::string callContext() {
    const std::string& current = sp::spfunc::currentCall();
    return current.empty() ? std::string("SpUtils::moveFromPackedArrays()") : current;
}
} // namespace

void SpUtils::moveFromPackedArrays(std::initializer_list<SpArrayBase*> arrays,
                                   std::map<std::string, SpPackedArray>&& packed) {
    for (SpArrayBase* array : arrays) {
        SP_CHECK(array, sp::InvalidArgument, "SpUtils::moveFromPackedArrays(): null array");
        auto it = packed.find(array->getName());
        if (it == packed.end()) {
            std::string given;
            for (const auto& [name, value] : packed)
                given += (given.empty() ? "'" : ", '") + name + "'";
            SP_THROW(sp::InvalidArgument, callContext(), ": array '", array->getName(),
                     "' was not passed (got ", given.empty() ? std::string("no arrays") : given, ")");
        }
        array->assign(std::move(it->second), callContext());
        packed.erase(it);
    }
}

std::map<std::string, SpPackedArray> SpUtils::moveToPackedArrays(std::initializer_list<SpArrayBase*> arrays) {
    std::map<std::string, SpPackedArray> packed;
    for (SpArrayBase* array : arrays) {
        SP_CHECK(array, sp::InvalidArgument, "SpUtils::moveToPackedArrays(): null array");
        SP_CHECK(!array->getName().empty(), sp::InvalidArgument,
                 "SpUtils::moveToPackedArrays(): an array has no name");
        SP_CHECK(packed.emplace(array->getName(), array->value()).second, sp::InvalidArgument,
                 "SpUtils::moveToPackedArrays(): two arrays are named '", array->getName(), "'");
    }
    return packed;
}
