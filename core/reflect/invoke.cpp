#include "core/reflect/invoke.h"

#include <string>

namespace sp::reflect {

void checkArguments(const CallArgs& args, std::initializer_list<const char*> names,
                    std::string_view context) {
    for (const auto& [name, value] : args) {
        bool known = false;
        for (const char* expected : names)
            known = known || name == expected;
        if (!known) {
            std::string list;
            for (const char* expected : names)
                list += (list.empty() ? "" : ", ") + std::string(expected);
            SP_THROW(InvalidArgument, context, ": unexpected argument '", name,
                     "' (parameters: ", list.empty() ? "none" : list, ")");
        }
    }
}

const Value& requireArgument(const CallArgs& args, const char* name, std::string_view context) {
    const Value* value = findArgument(args, name);
    SP_CHECK(value, InvalidArgument, context, ": missing argument '", name, "'");
    return *value;
}

} // namespace sp::reflect
