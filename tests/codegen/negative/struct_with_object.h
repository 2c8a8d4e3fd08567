// expect: tests/codegen/negative/struct_with_object.h:9: error: struct field 'FHolder::Owner' cannot hold an object reference; structs are plain values
#include "core/world/actor.h"

SPSTRUCT()
struct FHolder {
    SP_GENERATED_BODY()

    /// Owner.
    SPPROPERTY() AActor* Owner = nullptr;
};
