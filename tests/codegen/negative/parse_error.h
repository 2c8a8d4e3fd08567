// expect: tests/codegen/negative/parse_error.h:8: error: C++ parse error: unknown type name 'Undeclared'
#include "core/world/actor.h"

SPCLASS()
class AParseError : public AActor {
    SP_GENERATED_BODY()
public:
    SPPROPERTY() Undeclared Value;
};
