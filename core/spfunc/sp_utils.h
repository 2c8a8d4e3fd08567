#pragma once
// SpUtils: the helpers of the SPEAR paper's Fig. 8 for writing SpFuncs.

#include <initializer_list>
#include <map>
#include <string>
#include <type_traits>

#include "core/reflect/codec.h"
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

    // Reads the object `name` of a bundle (JSON, as Python sent it: a spear.FVector arrives as
    // {"X": .., "Y": .., "Z": ..}) as a T: a reflected struct or enum, a number, a string, or a vector or map
    // of those. Throws InvalidArgument naming the SpFunc being called and the object.
    template <typename T> static T getUnrealObj(const SpFuncDataBundle& bundle, const std::string& name) {
        const sp::reflect::AcceptIntsForEnums json; // JSON has no enums: an enum arrives as its int
        return sp::reflect::decode<T>(unrealObjValue(bundle, name), unrealObjContext(name));
    }

    // Stores `value` as the object `name` of a bundle; Python receives it decoded from JSON (structs as
    // dicts).
    template <typename T>
    static void setUnrealObj(SpFuncDataBundle& bundle, const std::string& name, const T& value) {
        bundle.unreal_obj_strings_[name] = toJsonText(sp::reflect::encode(value));
    }

  private:
    static sp::reflect::Value unrealObjValue(const SpFuncDataBundle& bundle, const std::string& name);
    static std::string unrealObjContext(const std::string& name);
    static std::string toJsonText(const sp::reflect::Value& value);
};
