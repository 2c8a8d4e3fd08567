// expect: tests/codegen/negative/malformed_macro.h:9: error: malformed SPPROPERTY(Setter =) on 'Speed': specifier 'Setter' has no value
#include "core/world/actor.h"

SPCLASS()
class AMalformed : public AActor {
    SP_GENERATED_BODY()
public:
    /// Speed.
    SPPROPERTY(Setter =) double Speed = 0.0;
};
