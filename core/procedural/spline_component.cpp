#include "core/procedural/spline_component.h"

#include <algorithm>
#include <cmath>

#include "core/base/error.h"

const sp::procedural::SplineCurve& USplineComponent::curve() const {
    if (!(curvePoints_ == SplinePoints)) {
        std::vector<Eigen::Vector3d> points;
        for (const FVector& point : SplinePoints)
            points.push_back(point.toEigen());
        curve_.setPoints(std::move(points));
        curvePoints_ = SplinePoints;
    }
    if (curve_.closedLoop() != bClosedLoop)
        curve_.setClosedLoop(bClosedLoop);
    return curve_;
}

namespace {

double checkedDistance(double distance, const char* function) {
    SP_CHECK(std::isfinite(distance), sp::InvalidArgument, "USplineComponent.", function, "(): Distance ",
             distance, " is not finite");
    return distance;
}

} // namespace

int USplineComponent::checkedIndex(int PointIndex, const char* function) const {
    SP_CHECK(PointIndex >= 0 && PointIndex < GetNumberOfSplinePoints(), sp::InvalidArgument,
             "USplineComponent.", function, "(): PointIndex ", PointIndex, " is out of range [0, ",
             GetNumberOfSplinePoints(), ")");
    return PointIndex;
}

Eigen::Vector3d USplineComponent::toSpace(const Eigen::Vector3d& local, ESplineCoordinateSpace space,
                                          bool direction) const {
    if (space == ESplineCoordinateSpace::Local)
        return local;
    const FTransform transform = GetComponentTransform();
    const Eigen::Vector3d scaled =
        transform.Rotation.toEigen().normalized() * local.cwiseProduct(transform.Scale3D.toEigen());
    return direction ? scaled : scaled + transform.Translation.toEigen();
}

Eigen::Vector3d USplineComponent::fromSpace(const FVector& value, ESplineCoordinateSpace space,
                                            bool direction) const {
    SP_CHECK(value.isFinite(), sp::InvalidArgument, "USplineComponent: a position or tangent must be finite");
    if (space == ESplineCoordinateSpace::Local)
        return value.toEigen();
    const FTransform transform = GetComponentTransform();
    const Eigen::Vector3d relative =
        direction ? value.toEigen() : value.toEigen() - transform.Translation.toEigen();
    return (transform.Rotation.toEigen().normalized().conjugate() * relative)
        .cwiseQuotient(transform.Scale3D.toEigen());
}

void USplineComponent::AddSplinePoint(const FVector& Position, ESplineCoordinateSpace CoordinateSpace,
                                      bool /*bUpdateSpline*/) {
    SplinePoints.push_back(FVector::fromEigen(fromSpace(Position, CoordinateSpace, false)));
}

void USplineComponent::ClearSplinePoints(bool /*bUpdateSpline*/) {
    SplinePoints.clear();
}

void USplineComponent::SetSplinePoints(const std::vector<FVector>& Points,
                                       ESplineCoordinateSpace CoordinateSpace, bool /*bUpdateSpline*/) {
    std::vector<FVector> local;
    for (const FVector& point : Points)
        local.push_back(FVector::fromEigen(fromSpace(point, CoordinateSpace, false)));
    SplinePoints = std::move(local);
}

void USplineComponent::SetClosedLoop(bool bInClosedLoop, bool /*bUpdateSpline*/) {
    bClosedLoop = bInClosedLoop;
}

double USplineComponent::GetSplineLength() const {
    return curve().length();
}

FVector USplineComponent::GetLocationAtDistanceAlongSpline(double Distance,
                                                           ESplineCoordinateSpace CoordinateSpace) const {
    return FVector::fromEigen(
        toSpace(curve().location(curve().keyAtDistance(checkedDistance(Distance, __func__))), CoordinateSpace,
                false));
}

FVector USplineComponent::GetDirectionAtDistanceAlongSpline(double Distance,
                                                            ESplineCoordinateSpace CoordinateSpace) const {
    const Eigen::Vector3d direction =
        toSpace(curve().derivative(curve().keyAtDistance(checkedDistance(Distance, __func__))),
                CoordinateSpace, true);
    return FVector::fromEigen(direction.norm() > 0.0 ? Eigen::Vector3d(direction.normalized()) : direction);
}

FRotator USplineComponent::GetRotationAtDistanceAlongSpline(double Distance,
                                                            ESplineCoordinateSpace CoordinateSpace) const {
    const FVector d = GetDirectionAtDistanceAlongSpline(checkedDistance(Distance, __func__), CoordinateSpace);
    return FRotator{std::atan2(d.Z, std::hypot(d.X, d.Y)) * 180.0 / M_PI, std::atan2(d.Y, d.X) * 180.0 / M_PI,
                    0.0};
}

FVector USplineComponent::GetLocationAtSplineInputKey(double InKey,
                                                      ESplineCoordinateSpace CoordinateSpace) const {
    SP_CHECK(std::isfinite(InKey), sp::InvalidArgument,
             "USplineComponent.GetLocationAtSplineInputKey(): InKey ", InKey, " is not finite");
    return FVector::fromEigen(toSpace(curve().location(InKey), CoordinateSpace, false));
}

FVector USplineComponent::GetLocationAtSplinePoint(int PointIndex,
                                                   ESplineCoordinateSpace CoordinateSpace) const {
    return FVector::fromEigen(
        toSpace(curve().point(checkedIndex(PointIndex, "GetLocationAtSplinePoint")), CoordinateSpace, false));
}

FVector USplineComponent::GetTangentAtSplinePoint(int PointIndex,
                                                  ESplineCoordinateSpace CoordinateSpace) const {
    return FVector::fromEigen(
        toSpace(curve().tangent(checkedIndex(PointIndex, "GetTangentAtSplinePoint")), CoordinateSpace, true));
}

void USplineComponent::SetTangentAtSplinePoint(int PointIndex, const FVector& InTangent,
                                               ESplineCoordinateSpace CoordinateSpace,
                                               bool /*bUpdateSpline*/) {
    const int index = checkedIndex(PointIndex, "SetTangentAtSplinePoint");
    const Eigen::Vector3d tangent = fromSpace(InTangent, CoordinateSpace, true);
    curve(); // current with the points first, so that the tangent is not dropped by a rebuild
    curve_.setTangent(index, tangent);
}

double USplineComponent::GetDistanceAlongSplineAtSplinePoint(int PointIndex) const {
    return curve().distanceAtPoint(checkedIndex(PointIndex, "GetDistanceAlongSplineAtSplinePoint"));
}

sp::reflect::SpArray<double>
USplineComponent::GetLocationsAtDistances(const sp::reflect::SpArray<double>& Distances,
                                          ESplineCoordinateSpace CoordinateSpace) const {
    const auto& shape = Distances.getShape();
    SP_CHECK(shape.size() == 1, sp::InvalidArgument,
             "USplineComponent.GetLocationsAtDistances(): Distances must be a 1-D array, got ", shape.size(),
             " dimensions");
    sp::reflect::SpArray<double> locations("locations");
    locations.resize({shape[0], 3});
    const double* in = Distances.data();
    double* out = locations.data();
    for (int64_t i = 0; i < shape[0]; ++i) {
        SP_CHECK(std::isfinite(in[i]), sp::InvalidArgument,
                 "USplineComponent.GetLocationsAtDistances(): Distances[", i, "] = ", in[i],
                 " is not finite");
        const Eigen::Vector3d p =
            toSpace(curve().location(curve().keyAtDistance(in[i])), CoordinateSpace, false);
        out[3 * i] = p.x();
        out[3 * i + 1] = p.y();
        out[3 * i + 2] = p.z();
    }
    return locations;
}

std::vector<Eigen::Vector3d> USplineComponent::worldPolyline(double step, int maxSegments) const {
    std::vector<Eigen::Vector3d> line;
    if (curve().pointCount() == 0)
        return line;
    const double length = curve().length();
    const int steps = int(std::clamp(std::ceil(length / step), 1.0, double(std::max(maxSegments, 1))));
    line.reserve(size_t(steps) + 1);
    for (int i = 0; i <= steps; ++i)
        line.push_back(toSpace(curve().location(curve().keyAtDistance(length * i / steps)),
                               ESplineCoordinateSpace::World, false));
    return line;
}

void USplineComponent::SetDebugLineThickness(double Thickness) {
    sp::checkSetting(std::isfinite(Thickness) && Thickness > 0.0, "USplineComponent", "DebugLineThickness",
                     "> 0", Thickness);
    DebugLineThickness = Thickness;
}

ASplineActor::ASplineActor() {
    SplineComponent = CreateDefaultSubobject<USplineComponent>("SplineComponent");
}
