// expect: tests/codegen/negative/clamp_not_a_number.h:8: error: ClampMax=wide on 'AGauge::Reading' is not a number
#include "core/world/actor.h"

SPCLASS()
class AGauge : public AActor {
    SP_GENERATED_BODY()
    /// A reading, with a range whose end is not a number.
    SPPROPERTY(meta=(ClampMin=0, ClampMax=wide)) double Reading = 0.0;
};
