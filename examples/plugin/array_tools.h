#pragma once
// SpFuncs registered in the constructor (no Initialize() step), over arrays of any size: "echo" returns
// its bundle unchanged (what the benchmarks time), "invert" returns 255 - image for a uint8 image.

#include <cstdint>

#include "core/spfunc/spfunc.h"

/// Array utilities as SpFuncs: echo and invert.
UCLASS()
class AArrayTools : public AActor {
    GENERATED_BODY()
public:
    AArrayTools();

    /// Calls answered so far.
    UPROPERTY(VisibleAnywhere)
    int64_t CallCount = 0;

    /// Holds the SpFuncs (created in the constructor, so never None).
    UPROPERTY(VisibleAnywhere, NotNull)
    USpFuncComponent* SpFuncComponent = nullptr;
};
