// expect: tests/codegen/negative/overload.h:13: error: 'AOverload::Move' is overloaded; reflected functions cannot be overloaded (give each a distinct name)
#include "core/world/actor.h"

SPCLASS()
class AOverload : public AActor {
    SP_GENERATED_BODY()
public:
    /// Moves by an offset.
    SPFUNCTION()
    void Move(const FVector& Offset);
    /// Moves by a distance.
    SPFUNCTION()
    void Move(double Distance);
};
