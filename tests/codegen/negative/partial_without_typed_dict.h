// expect: tests/codegen/negative/partial_without_typed_dict.h:6: error: SPSTRUCT(Partial) on 'FOnlySome' needs TypedDict: SPSTRUCT(TypedDict, Partial)
#include "core/reflect/macros.h"

/// Partial is a kind of TypedDict; a plain struct always has all its fields.
USTRUCT(Partial)
struct FOnlySome {
    GENERATED_BODY()

    /// A value.
    UPROPERTY()
    int Value = 0;
};
