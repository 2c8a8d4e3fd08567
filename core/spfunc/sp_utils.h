#pragma once
// SpUtils: the helpers of the SPEAR paper's Fig. 8 for writing SpFuncs.

#include <initializer_list>
#include <map>
#include <string>
#include <type_traits>

#include "core/reflect/sp_array.h"
#include "core/spfunc/sp_func_data_bundle.h"
#include "core/world/actor.h"

// Fig. 8 spells the array type without a namespace.
using sp::reflect::SpArray;
using sp::reflect::SpArrayBase;

class SpUtils {
  public:
    // Creates a component owned by `owner` (UE's CreateDefaultSubobject); use in constructors.
    template <typename T> static T* createComponent(AActor* owner, std::string name) {
        static_assert(std::is_base_of_v<UActorComponent, T>, "createComponent() creates components");
        return owner->CreateDefaultSubobject<T>(std::move(name));
    }

    // Fills each array from the packed array of the same name, without copying. Throws InvalidArgument
    // naming the SpFunc being called and the array when one is missing or has another dtype.
    static void moveFromPackedArrays(std::initializer_list<SpArrayBase*> arrays,
                                     std::map<std::string, SpPackedArray>&& packed);

    // Packs each array under its name, sharing its storage.
    static std::map<std::string, SpPackedArray>
    moveToPackedArrays(std::initializer_list<SpArrayBase*> arrays);
};
