#pragma once
// Typed SPFUNCTIONs returning TypedDicts, for tests/python/test_typed_results.py: a complete TypedDict
// (every key promised to Python), a partial one (keys only for what was produced), and a function that
// forgets a field of a complete result, which the engine must report instead of handing back a dict
// without the key.

#include <cstdint>

#include "core/spfunc/spfunc.h"

/// Values and how often each was seen; both are always present.
SPSTRUCT(TypedDict)
struct FMeasurement {
    SP_GENERATED_BODY()

    /// The distinct values, (K,).
    SPPROPERTY()
    SpArray<float> Values;
    /// How often each value was seen, (K,).
    SPPROPERTY()
    SpArray<int64_t> Counts;
};

/// Values, and their counts only when asked for.
SPSTRUCT(TypedDict, Partial)
struct FPartialMeasurement {
    SP_GENERATED_BODY()

    /// The distinct values, (K,).
    SPPROPERTY()
    SpArray<float> Values;
    /// How often each value was seen, (K,); present only when counted.
    SPPROPERTY()
    SpArray<int64_t> Counts;
};

/// Counts the distinct values of an array.
SPCLASS()
class AMeasurer : public AActor {
    SP_GENERATED_BODY()
public:
    /// The last complete measurement; never set, so reading it breaks the TypedDict's promise (a
    /// property, not a function result: the struct's own converters must catch it).
    SPPROPERTY(ReadOnly)
    FMeasurement Unset;

    /// The distinct values of Samples and their counts.
    SPFUNCTION()
    FMeasurement Measure(const SpArray<float>& Samples);

    /// The distinct values of Samples, and their counts when bCount.
    SPFUNCTION()
    FPartialMeasurement MeasureSome(const SpArray<float>& Samples, bool bCount);

    /// A faulty function: fills Values but forgets Counts.
    SPFUNCTION()
    FMeasurement MeasureForgetful(const SpArray<float>& Samples);
};
