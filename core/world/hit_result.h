#pragma once
// FHitResult: where a trace met the world. Reflected structs cannot hold object references, so the
// actor and component that were hit come back beside it (UWorld.line_trace_single's out-parameters).

#include "core/world/math.h"

/// The result of a trace: whether it hit, and where.
SPSTRUCT()
struct FHitResult {
    SP_GENERATED_BODY()

    /// True when the trace hit something.
    SPPROPERTY()
    bool bBlockingHit = false;
    /// Where the trace hit, in world space (metres); the trace end when nothing was hit.
    SPPROPERTY()
    FVector Location;
    /// The same point as Location (UE keeps both for swept shapes).
    SPPROPERTY()
    FVector ImpactPoint;
    /// Unit surface normal at the hit, facing the trace start.
    SPPROPERTY()
    FVector ImpactNormal;
    /// The same vector as ImpactNormal (UE keeps both for swept shapes).
    SPPROPERTY()
    FVector Normal;
    /// Distance from TraceStart to Location in metres.
    SPPROPERTY()
    double Distance = 0.0;
    /// Fraction of the way from TraceStart to TraceEnd where the hit lies, in [0, 1].
    SPPROPERTY()
    double Time = 1.0;
    /// Start of the trace.
    SPPROPERTY()
    FVector TraceStart;
    /// End of the trace.
    SPPROPERTY()
    FVector TraceEnd;

    friend bool operator==(const FHitResult&, const FHitResult&) = default;
};
