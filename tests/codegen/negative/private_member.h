// expect: tests/codegen/negative/private_member.h:9: error: reflected member 'APrivate::Secret' must be public
#include "core/world/actor.h"

SPCLASS()
class APrivate : public AActor {
    SP_GENERATED_BODY()
private:
    /// Hidden.
    SPPROPERTY() int Secret = 0;
};
