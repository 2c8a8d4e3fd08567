#pragma once
// USplineComponent: a curve through points (UE's SplineComponent), for paths, roads and procedural
// placement: cubic Hermite segments with automatic (Catmull-Rom) tangents unless a point is given its own
// (core/procedural/spline_curve.h), open or closed, evaluated by distance along it or by input key. Points
// are kept in the component's space (SplinePoints, saved with scenes); functions take and return local or
// world coordinates as their CoordinateSpace says. Tangents set with SetTangentAtSplinePoint live until
// the points change, and are not saved.

#include <vector>

#include "core/procedural/spline_curve.h"
#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "core/world/math.h"
#include "core/world/scene_component.h"

/// Which space a spline function's positions and directions are in.
SPENUM()
enum class ESplineCoordinateSpace : uint8_t {
    /// The spline component's own space.
    Local = 0,
    /// World space.
    World = 1,
};

/// A curve through points.
SPCLASS()
class USplineComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// The points, in the component's space (metres).
    SPPROPERTY()
    std::vector<FVector> SplinePoints;

    /// Whether the last point joins the first.
    SPPROPERTY()
    bool bClosedLoop = false;

    /// Draws the curve in camera images as a glowing tube (a debug line for looking at paths and roads; it is
    /// drawn like any object, in every modality, casting no shadow).
    SPPROPERTY()
    bool bDrawDebug = false;

    /// The debug line's thickness in metres (> 0).
    SPPROPERTY(Setter = SetDebugLineThickness)
    double DebugLineThickness = 0.05;

    /// The debug line's colour (linear; it glows with it).
    SPPROPERTY()
    FLinearColor DebugLineColor{1.0f, 0.75f, 0.0f, 1.0f};

    /// Sets DebugLineThickness (finite, > 0).
    SPFUNCTION()
    void SetDebugLineThickness(double Thickness);

    /// Adds a point at the end. bUpdateSpline is accepted for UE compatibility (the curve is always current).
    SPFUNCTION()
    void AddSplinePoint(const FVector& Position, ESplineCoordinateSpace CoordinateSpace,
                        bool bUpdateSpline = true);

    /// Removes every point.
    SPFUNCTION()
    void ClearSplinePoints(bool bUpdateSpline = true);

    /// Replaces the points.
    SPFUNCTION()
    void SetSplinePoints(const std::vector<FVector>& Points, ESplineCoordinateSpace CoordinateSpace,
                         bool bUpdateSpline = true);

    /// Returns the number of points.
    SPFUNCTION()
    int GetNumberOfSplinePoints() const { return int(SplinePoints.size()); }

    /// Makes the spline a closed loop or an open curve.
    SPFUNCTION()
    void SetClosedLoop(bool bInClosedLoop, bool bUpdateSpline = true);

    /// Returns true for a closed loop.
    SPFUNCTION()
    bool IsClosedLoop() const { return bClosedLoop; }

    /// Returns the length of the curve in metres (in the component's space, before its scale).
    SPFUNCTION()
    double GetSplineLength() const;

    /// Returns the point at Distance metres along the curve (clamped to it).
    SPFUNCTION()
    FVector GetLocationAtDistanceAlongSpline(double Distance, ESplineCoordinateSpace CoordinateSpace) const;

    /// Returns the unit direction of the curve at Distance metres along it.
    SPFUNCTION()
    FVector GetDirectionAtDistanceAlongSpline(double Distance, ESplineCoordinateSpace CoordinateSpace) const;

    /// Returns the rotation whose X axis follows the curve at Distance metres along it (no roll).
    SPFUNCTION()
    FRotator GetRotationAtDistanceAlongSpline(double Distance, ESplineCoordinateSpace CoordinateSpace) const;

    /// Returns the curve at input key InKey (point index + fraction of the way to the next point).
    SPFUNCTION()
    FVector GetLocationAtSplineInputKey(double InKey, ESplineCoordinateSpace CoordinateSpace) const;

    /// Returns point PointIndex.
    SPFUNCTION()
    FVector GetLocationAtSplinePoint(int PointIndex, ESplineCoordinateSpace CoordinateSpace) const;

    /// Returns the tangent at point PointIndex (its own, or the automatic one).
    SPFUNCTION()
    FVector GetTangentAtSplinePoint(int PointIndex, ESplineCoordinateSpace CoordinateSpace) const;

    /// Gives point PointIndex a tangent of its own.
    SPFUNCTION()
    void SetTangentAtSplinePoint(int PointIndex, const FVector& InTangent,
                                 ESplineCoordinateSpace CoordinateSpace, bool bUpdateSpline = true);

    /// Returns the distance along the curve at point PointIndex.
    SPFUNCTION()
    double GetDistanceAlongSplineAtSplinePoint(int PointIndex) const;

    /// Returns the points at each of Distances (a 1-D float64 array, metres along the curve) as an (N, 3)
    /// float64 array: many evaluations in one call.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetLocationsAtDistances(const sp::reflect::SpArray<double>& Distances,
                                                         ESplineCoordinateSpace CoordinateSpace) const;

    // The curve in world space as a polyline of segments `step` metres long along it (fewer, evenly spaced,
    // when that would be more than maxSegments), both ends included; empty when there are no points. For
    // whoever follows or draws the curve (procedural generation, the debug line).
    std::vector<Eigen::Vector3d> worldPolyline(double step, int maxSegments) const;
    // Changes whenever the curve's shape in the component's space does (points, loop, own tangents).
    std::uint64_t curveRevision() const { return curve().revision(); }

  private:
    // The curve of SplinePoints and bClosedLoop, rebuilt when they changed (by any path: a setter, the
    // registry, a scene file); own tangents survive only while the points stay the same.
    const sp::procedural::SplineCurve& curve() const;
    int checkedIndex(int PointIndex, const char* function) const;
    Eigen::Vector3d toSpace(const Eigen::Vector3d& local, ESplineCoordinateSpace space, bool direction) const;
    Eigen::Vector3d fromSpace(const FVector& value, ESplineCoordinateSpace space, bool direction) const;

    mutable sp::procedural::SplineCurve curve_;
    mutable std::vector<FVector> curvePoints_;
};

/// An actor whose root is a spline (a path, a road's centre line).
SPCLASS()
class ASplineActor : public AActor {
    SP_GENERATED_BODY()
  public:
    ASplineActor();

    /// The spline (the root component).
    SPPROPERTY(ReadOnly, NotNull)
    USplineComponent* SplineComponent = nullptr;
};
