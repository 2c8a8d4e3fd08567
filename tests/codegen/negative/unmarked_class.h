// expect: tests/codegen/negative/unmarked_class.h:8: error: SPPROPERTY() on 'Speed' in 'APlain', which is not reflected (mark the class SPCLASS())
#include "core/world/actor.h"

class APlain : public AActor {
public:
    /// Speed.
    SPPROPERTY()
    double Speed = 0.0;
};
