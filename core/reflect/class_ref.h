#pragma once
// UClass and TSubclassOf<T>: references to reflected classes, the UE spellings. Across the boundary a
// class travels by name; in Python a parameter of these types takes the class object or its name.

#include "core/base/error.h"
#include "core/reflect/type_info.h"

using UClass = sp::reflect::TypeInfo;

// A class that is T or derives from T (checked when set).
template <typename T> class TSubclassOf {
  public:
    TSubclassOf() = default;
    TSubclassOf(const UClass* type) : type_(type) {
        SP_CHECK(!type || type->isChildOf(T::StaticClass()), sp::InvalidArgument, "TSubclassOf<",
                 T::StaticClass().name, ">: class '", type->name, "' does not derive from ",
                 T::StaticClass().name);
    }
    const UClass* Get() const { return type_; }
    const UClass* operator->() const { return type_; }
    explicit operator bool() const { return type_ != nullptr; }

  private:
    const UClass* type_ = nullptr;
};
