#pragma once
// A typed SPFUNCTION beside Fig. 8's SpFunc: the generator knows the names and dtypes of its arrays, so
// the Python stub reads
//     def Filter(self, *, Points: NDArray[np.float32], Center: FVector, Radius: float) -> FPointFilterResult
// mypy rejects a float64 array or a misspelt argument, and the engine rejects a wrong shape at run time.

#include <cstdint>

#include "core/spfunc/spfunc.h"
#include "core/world/math.h"

/// The points of a cloud that lie within a sphere.
SPSTRUCT(TypedDict)
struct FPointFilterResult {
    SP_GENERATED_BODY()

    /// The points inside the sphere, (M, 3).
    SPPROPERTY()
    SpArray<float> Points;

    /// Their rows in the input, (M,).
    SPPROPERTY()
    SpArray<int64_t> Indices;
};

/// Keeps the points of a cloud that lie within a sphere; counts the points it has seen.
UCLASS()
class APointFilter : public AActor {
    GENERATED_BODY()
public:
    /// Points seen by Filter() so far.
    UPROPERTY(VisibleAnywhere)
    int64_t PointsSeen = 0;

    /// Returns the rows of Points, an (N, 3) float32 array, within Radius of Center.
    UFUNCTION(BlueprintCallable)
    FPointFilterResult Filter(const SpArray<float>& Points, const FVector& Center, float Radius);
};
