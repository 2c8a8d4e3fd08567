// expect: tests/codegen/negative/not_an_object.h:5: error: SPCLASS 'FLoose' must derive from UObject (or another reflected class)
#include "core/reflect/macros.h"

SPCLASS()
class FLoose {
    SP_GENERATED_BODY()
};
