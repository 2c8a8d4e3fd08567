// expect: tests/codegen/negative/raw_pointer.h:9: error: property 'ARawPointer::Data': pointer type 'float *' is not supported; only pointers to reflected classes cross the boundary
#include "core/world/actor.h"

SPCLASS()
class ARawPointer : public AActor {
    SP_GENERATED_BODY()
public:
    /// Raw data.
    SPPROPERTY() float* Data = nullptr;
};
