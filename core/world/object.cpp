#include "core/world/object.h"

#include "core/reflect/type_info.h"

std::string UObject::GetClassName() const {
    return GetClass().name;
}

std::string UObject::GetDebugName() const {
    return GetClass().name + " '" + name_ + "'";
}
