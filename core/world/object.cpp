#include "core/world/object.h"

#include "core/reflect/type_info.h"

std::string UObject::GetClassName() const {
    return GetObjectClass().name;
}

std::string UObject::GetDebugName() const {
    return GetObjectClass().name + " '" + name_ + "'";
}
