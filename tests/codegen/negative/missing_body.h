// expect: tests/codegen/negative/missing_body.h:5: error: 'ANoBody' is marked SPCLASS() but has no SP_GENERATED_BODY()
#include "core/world/actor.h"

SPCLASS()
class ANoBody : public AActor {
public:
    /// Speed.
    SPPROPERTY() double Speed = 0.0;
};
