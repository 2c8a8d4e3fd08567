#include "core/reflect/invoke.h"

#include <string>

namespace sp::reflect {

// Names that are not input parameters are refused: a misspelt keyword must not be ignored.
void ValueCall::rejectArgument(const std::string& name) const {
    std::string list;
    for (const ParamDesc& param : params_)
        list += (list.empty() ? "" : ", ") + std::string(param.name);
    SP_THROW(InvalidArgument, context_, ": unexpected argument '", name,
             "' (parameters: ", list.empty() ? "none" : list, ")");
}

const Value& requireArgument(const CallArgs& args, const char* name, std::string_view context) {
    const Value* value = findArgument(args, name);
    SP_CHECK(value, InvalidArgument, context, ": missing argument '", name, "'");
    return *value;
}

} // namespace sp::reflect
