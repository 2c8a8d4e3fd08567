#pragma once
// SpFuncs registered in the constructor (no Initialize() step), over arrays of any size: "echo" returns
// its bundle unchanged (what the benchmarks time), "invert" returns 255 - image for a uint8 image, and
// "center_points" takes (N, 3) points and an FVector "origin" object and returns the points relative to it
// and their centroid as an FVector object; "store" keeps its arrays and "recall" returns them.

#include <cstdint>
#include <map>
#include <string>

#include "core/spfunc/spfunc.h"

/// Array utilities as SpFuncs: echo, invert, center_points, store and recall.
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

  private:
    std::map<std::string, SpPackedArray> stored_; // by "store", for "recall"
};
