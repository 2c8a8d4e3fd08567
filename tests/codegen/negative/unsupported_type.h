// expect: tests/codegen/negative/unsupported_type.h:11: error: parameter 'Items' of 'AUnsupported::Take': type 'const std::set<int>' is not supported across the boundary; reflect it with SPSTRUCT()
#include <set>

#include "core/world/actor.h"

SPCLASS()
class AUnsupported : public AActor {
    SP_GENERATED_BODY()
public:
    /// Takes a set.
    SPFUNCTION() void Take(const std::set<int>& Items);
};
