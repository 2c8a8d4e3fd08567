#include "core/gameplay/navigation_system.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/error.h"
#include "core/gameplay/navigation_subsystem.h"
#include "core/gameplay/point_arrays.h"
#include "core/world/object_access.h"
#include "core/world/world.h"

namespace {

using sp::gameplay::checkFinite;
using sp::gameplay::rowOf;
using sp::gameplay::rowsOf;
using sp::gameplay::toArray;
using sp::navigation::Path;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The most points or paths one call returns (24 bytes a point: 240 MB).
constexpr int64_t kMaxPoints = 10'000'000;

ENavigationQueryResult resultOf(Path::Status status) {
    switch (status) {
    case Path::Status::Success:
        return ENavigationQueryResult::Success;
    case Path::Status::Partial:
        return ENavigationQueryResult::Fail;
    case Path::Status::StartOff:
    case Path::Status::EndOff:
        return ENavigationQueryResult::Invalid;
    case Path::Status::NoMesh:
        break;
    }
    return ENavigationQueryResult::Error;
}

ARecastNavMesh& navDataOf(UObject* context, ARecastNavMesh* navData, const char* function) {
    UWorld& world = sp::world::worldOfContext(context, function);
    if (!navData)
        return *UNavigationSystemV1::GetNavigationSystem(&world)->GetDefaultNavDataInstance();
    SP_CHECK(navData->GetWorld() == &world, sp::InvalidArgument, function, ": NavData ",
             navData->GetDebugName(), " is in another world");
    return *navData;
}

} // namespace

// -- ANavMeshBoundsVolume ------------------------------------------------------------------------------

ANavMeshBoundsVolume::ANavMeshBoundsVolume() {
    BoxComponent = CreateDefaultSubobject<UBoxComponent>("BoxComponent");
    BoxComponent->BoxExtent = FVector{10.0, 10.0, 2.0};
    BoxComponent->CollisionPrimitive = ECollisionPrimitive::NoCollision; // a region, not an obstacle
    BoxComponent->bGenerateOverlapEvents = false;
    BoxComponent->bCanEverAffectNavigation = false;
}

Eigen::AlignedBox3d ANavMeshBoundsVolume::worldBounds() const {
    return BoxComponent->worldBox();
}

// -- ARecastNavMesh ------------------------------------------------------------------------------------

ARecastNavMesh::ARecastNavMesh() : mesh_(std::make_unique<sp::navigation::NavMesh>()), random_(0) {
    accepted_ = settings();
}

ARecastNavMesh::~ARecastNavMesh() = default;

void ARecastNavMesh::SetRandomSeed(int Seed) {
    RandomSeed = Seed;
    random_.seed(uint64_t(uint32_t(Seed)));
}

void ARecastNavMesh::PostPropertyChanged(std::string_view propertyName) {
    if (propertyName == "RandomSeed")
        random_.seed(uint64_t(uint32_t(RandomSeed)));
    // A setting is checked as it is set (with the others as they are), not at the next query: a refused one
    // is undone, and the mesh stays as it was.
    try {
        sp::navigation::validate(settings(), "ARecastNavMesh." + std::string(propertyName));
    } catch (const sp::InvalidArgument&) {
        AgentRadius = accepted_.agentRadius;
        AgentHeight = accepted_.agentHeight;
        AgentMaxSlope = accepted_.maxSlopeDegrees;
        AgentMaxStepHeight = accepted_.maxStepHeight;
        CellSize = accepted_.cellSize;
        CellHeight = accepted_.cellHeight;
        TileSize = accepted_.tileSize;
        MinRegionArea = accepted_.minRegionArea;
        throw;
    }
    accepted_ = settings();
}

sp::navigation::NavMeshSettings ARecastNavMesh::settings() const {
    sp::navigation::NavMeshSettings s;
    s.agentRadius = AgentRadius;
    s.agentHeight = AgentHeight;
    s.maxSlopeDegrees = AgentMaxSlope;
    s.maxStepHeight = AgentMaxStepHeight;
    s.cellSize = CellSize;
    s.cellHeight = CellHeight;
    s.tileSize = TileSize;
    s.minRegionArea = MinRegionArea;
    return s;
}

void ARecastNavMesh::build(const char* function) {
    const sp::navigation::NavMeshSettings wanted = settings();
    sp::navigation::validate(wanted, std::string(function) + " on " + GetDebugName());
    const auto& snapshot = GetWorld()->GetSubsystem<sp::gameplay::NavigationSubsystem>().snapshot();
    auto fresh = std::make_unique<sp::navigation::NavMesh>();
    sp::navigation::BuildStats stats;
    if (!snapshot.region.isEmpty())
        stats = fresh->build(snapshot.soup, snapshot.region, wanted);
    mesh_ = std::move(fresh);
    builtBodies_ = snapshot.bodies;
    builtSettings_ = wanted;
    stale_ = false;
    lastBuildSeconds_ = stats.seconds;
    lastBuildTiles_ = stats.tilesBuilt;
}

sp::navigation::NavMesh& ARecastNavMesh::ensureBuilt(const char* function) {
    SP_CHECK(GetWorld(), sp::InvalidState, function, ": ", GetDebugName(), " is not in a world");
    try {
        return update(function);
    } catch (...) {
        stale_ = true; // a build that failed midway is redone from scratch next time
        throw;
    }
}

sp::navigation::NavMesh& ARecastNavMesh::update(const char* function) {
    if (stale_ || !(settings() == builtSettings_)) {
        build(function);
        return *mesh_;
    }
    if (!bRebuildAutomatically)
        return *mesh_;
    const auto& snapshot = GetWorld()->GetSubsystem<sp::gameplay::NavigationSubsystem>().snapshot();
    // The mesh knows the region it was built over (none: it was not built, there being nothing to build on).
    if (!sp::gameplay::NavigationSubsystem::sameRegion(snapshot.region, mesh_->region())) {
        build(function);
        return *mesh_;
    }
    if (!mesh_->isBuilt())
        return *mesh_; // nothing to build on, as when it was last built
    // Only the tiles under bodies that came, went or moved (a reshaped body comes back with a new id).
    Eigen::AlignedBox3d changed;
    for (const auto& [body, placed] : snapshot.bodies) {
        const auto built = builtBodies_.find(body);
        if (built == builtBodies_.end() || !built->second.pose.isApprox(placed.pose, 0.0)) {
            changed.extend(placed.bounds);
            if (built != builtBodies_.end())
                changed.extend(built->second.bounds);
        }
    }
    for (const auto& [body, placed] : builtBodies_)
        if (!snapshot.bodies.count(body))
            changed.extend(placed.bounds);
    if (changed.isEmpty())
        return *mesh_;
    const sp::navigation::BuildStats stats = mesh_->rebuildTiles(snapshot.soup, changed);
    builtBodies_ = snapshot.bodies;
    lastBuildSeconds_ = stats.seconds;
    lastBuildTiles_ = stats.tilesBuilt;
    return *mesh_;
}

void ARecastNavMesh::RebuildNavigation() {
    build("ARecastNavMesh.RebuildNavigation()");
}

int ARecastNavMesh::GetNumTiles() {
    return ensureBuilt("ARecastNavMesh.GetNumTiles()").tileCount();
}

int ARecastNavMesh::GetNumPolygons() {
    return ensureBuilt("ARecastNavMesh.GetNumPolygons()").polygonCount();
}

double ARecastNavMesh::GetNavigableArea() {
    return ensureBuilt("ARecastNavMesh.GetNavigableArea()").area();
}

Path ARecastNavMesh::findPath(const FVector& start, const FVector& end, const char* function) {
    checkFinite(start, function, "Start");
    checkFinite(end, function, "End");
    sp::navigation::NavMesh& mesh = ensureBuilt(function);
    return mesh.findPath(start.toEigen(), end.toEigen(), mesh.defaultQueryExtent());
}

ENavigationQueryResult ARecastNavMesh::FindPath(const FVector& Start, const FVector& End,
                                                sp::reflect::SpArray<double>& PathPoints,
                                                double& PathLength) {
    const Path path = findPath(Start, End, "ARecastNavMesh.FindPath()");
    PathPoints = toArray(path.points, "PathPoints");
    PathLength = path.length;
    return resultOf(path.status);
}

void ARecastNavMesh::FindPaths(const sp::reflect::SpArray<double>& StartPoints,
                               const sp::reflect::SpArray<double>& EndPoints,
                               sp::reflect::SpArray<double>& PathPoints,
                               sp::reflect::SpArray<int64_t>& PathStarts,
                               sp::reflect::SpArray<double>& Lengths,
                               sp::reflect::SpArray<uint8_t>& Results) {
    constexpr const char* kFunction = "ARecastNavMesh.FindPaths()";
    const int64_t count = rowsOf(StartPoints, kFunction, "StartPoints");
    SP_CHECK(count <= kMaxPoints, sp::InvalidArgument, kFunction, ": ", count, " paths are more than ",
             kMaxPoints);
    SP_CHECK(rowsOf(EndPoints, kFunction, "EndPoints") == count, sp::InvalidArgument, kFunction,
             ": StartPoints has ", count, " rows and EndPoints ", EndPoints.getShape()[0],
             "; they must match");
    sp::navigation::NavMesh& mesh = ensureBuilt(kFunction);
    std::vector<Eigen::Vector3d> points;
    std::vector<int64_t> starts{0};
    std::vector<double> lengths;
    std::vector<uint8_t> results;
    for (int64_t i = 0; i < count; ++i) {
        const Path path = mesh.findPath(rowOf(StartPoints, i).toEigen(), rowOf(EndPoints, i).toEigen(),
                                        mesh.defaultQueryExtent());
        points.insert(points.end(), path.points.begin(), path.points.end());
        starts.push_back(int64_t(points.size()));
        lengths.push_back(path.length);
        results.push_back(uint8_t(resultOf(path.status)));
    }
    PathPoints = toArray(points, "PathPoints");
    PathStarts = sp::reflect::SpArray<int64_t>("PathStarts");
    PathStarts.setDataSource(std::move(starts));
    Lengths = sp::reflect::SpArray<double>("Lengths");
    Lengths.setDataSource(std::move(lengths));
    Results = sp::reflect::SpArray<uint8_t>("Results");
    Results.setDataSource(std::move(results));
}

double ARecastNavMesh::GetGeodesicDistance(const FVector& Start, const FVector& End) {
    const Path path = findPath(Start, End, "ARecastNavMesh.GetGeodesicDistance()");
    return path.status == Path::Status::Success ? path.length : std::numeric_limits<double>::infinity();
}

sp::reflect::SpArray<double> ARecastNavMesh::GetRandomPoints(int NumPoints) {
    constexpr const char* kFunction = "ARecastNavMesh.GetRandomPoints()";
    SP_CHECK(NumPoints >= 0 && NumPoints <= kMaxPoints, sp::InvalidArgument, kFunction, ": NumPoints ",
             NumPoints, " must be in [0, ", kMaxPoints, "]");
    sp::navigation::NavMesh& mesh = ensureBuilt(kFunction);
    SP_CHECK(NumPoints == 0 || mesh.polygonCount() > 0, sp::InvalidState, kFunction, ": ", GetDebugName(),
             " has no navigable area (no static geometry to walk on)");
    std::vector<Eigen::Vector3d> points;
    points.reserve(size_t(NumPoints));
    for (int i = 0; i < NumPoints; ++i)
        points.push_back(*mesh.randomPoint(random_));
    return toArray(points, "points");
}

std::optional<Eigen::Vector3d> ARecastNavMesh::randomPointInRadius(const FVector& origin, double radius,
                                                                   bool reachableOnly, const char* function) {
    checkFinite(origin, function, "Origin");
    SP_CHECK(std::isfinite(radius) && radius >= 0.0, sp::InvalidArgument, function, ": Radius ", radius,
             " must be a finite number >= 0");
    sp::navigation::NavMesh& mesh = ensureBuilt(function);
    return mesh.randomPointInRadius(origin.toEigen(), radius, reachableOnly, mesh.defaultQueryExtent(),
                                    random_);
}

sp::reflect::SpArray<double>
ARecastNavMesh::GetRandomReachablePointsInRadius(const sp::reflect::SpArray<double>& Origins, double Radius) {
    constexpr const char* kFunction = "ARecastNavMesh.GetRandomReachablePointsInRadius()";
    const int64_t count = rowsOf(Origins, kFunction, "Origins");
    SP_CHECK(count <= kMaxPoints, sp::InvalidArgument, kFunction, ": ", count, " origins are more than ",
             kMaxPoints);
    SP_CHECK(std::isfinite(Radius) && Radius >= 0.0, sp::InvalidArgument, kFunction, ": Radius ", Radius,
             " must be a finite number >= 0");
    sp::navigation::NavMesh& mesh = ensureBuilt(kFunction);
    std::vector<Eigen::Vector3d> points;
    for (int64_t i = 0; i < count; ++i)
        points.push_back(mesh.randomPointInRadius(rowOf(Origins, i).toEigen(), Radius, true,
                                                  mesh.defaultQueryExtent(), random_)
                             .value_or(Eigen::Vector3d::Constant(kNaN)));
    return toArray(points, "points");
}

bool ARecastNavMesh::ProjectPointToNavigation(const FVector& Point, FVector& ProjectedLocation,
                                              const FVector& QueryExtent) {
    constexpr const char* kFunction = "ARecastNavMesh.ProjectPointToNavigation()";
    checkFinite(Point, kFunction, "Point");
    checkFinite(QueryExtent, kFunction, "QueryExtent");
    sp::navigation::NavMesh& mesh = ensureBuilt(kFunction);
    const Eigen::Vector3d extent =
        QueryExtent == FVector{} ? mesh.defaultQueryExtent() : QueryExtent.toEigen().cwiseAbs();
    const auto projected = mesh.project(Point.toEigen(), extent);
    ProjectedLocation = projected ? FVector::fromEigen(*projected) : Point;
    return projected.has_value();
}

bool ARecastNavMesh::IsNavigable(const FVector& Point, double MaxVerticalDistance) {
    constexpr const char* kFunction = "ARecastNavMesh.IsNavigable()";
    checkFinite(Point, kFunction, "Point");
    SP_CHECK(std::isfinite(MaxVerticalDistance) && MaxVerticalDistance >= 0.0, sp::InvalidArgument, kFunction,
             ": MaxVerticalDistance ", MaxVerticalDistance, " must be a finite number >= 0");
    return ensureBuilt(kFunction).isNavigable(Point.toEigen(), MaxVerticalDistance);
}

sp::reflect::SpArray<double> ARecastNavMesh::GetNavMeshTriangles() {
    const auto triangles = ensureBuilt("ARecastNavMesh.GetNavMeshTriangles()").triangles();
    sp::reflect::SpArray<double> array("triangles");
    array.resize({int64_t(triangles.size()), 3, 3});
    double* out = array.data();
    for (const auto& triangle : triangles)
        for (const Eigen::Vector3d& corner : triangle)
            for (int k = 0; k < 3; ++k)
                *out++ = corner[k];
    return array;
}

// -- UNavigationSystemV1 -------------------------------------------------------------------------------

UNavigationSystemV1* UNavigationSystemV1::GetNavigationSystem(UObject* WorldContextObject) {
    UWorld& world =
        sp::world::worldOfContext(WorldContextObject, "UNavigationSystemV1.GetNavigationSystem()");
    return &world.GetSubsystem<sp::gameplay::NavigationSubsystem>().navigationSystem();
}

ARecastNavMesh* UNavigationSystemV1::GetNavDataForAgentName(const std::string& AgentName) const {
    for (AActor* actor : GetWorld()->find_actors_by_class(&ARecastNavMesh::StaticClass()))
        if (auto* data = static_cast<ARecastNavMesh*>(actor); data->AgentName == AgentName)
            return data;
    return nullptr;
}

ARecastNavMesh* UNavigationSystemV1::GetDefaultNavDataInstance() {
    if (AActor* existing = GetWorld()->find_actor_by_class(&ARecastNavMesh::StaticClass()))
        return static_cast<ARecastNavMesh*>(existing);
    return static_cast<ARecastNavMesh*>(GetWorld()->spawn_actor(&ARecastNavMesh::StaticClass(), FVector(),
                                                                FRotator(), "RecastNavMesh-Default"));
}

void UNavigationSystemV1::Build() {
    for (AActor* actor : GetWorld()->find_actors_by_class(&ARecastNavMesh::StaticClass()))
        static_cast<ARecastNavMesh*>(actor)->RebuildNavigation();
}

ENavigationQueryResult UNavigationSystemV1::FindPathToLocationSynchronously(
    UObject* WorldContextObject, const FVector& PathStart, const FVector& PathEnd,
    sp::reflect::SpArray<double>& PathPoints, double& PathLength, ARecastNavMesh* NavData) {
    constexpr const char* kFunction = "UNavigationSystemV1.FindPathToLocationSynchronously()";
    const Path path =
        navDataOf(WorldContextObject, NavData, kFunction).findPath(PathStart, PathEnd, kFunction);
    PathPoints = toArray(path.points, "PathPoints");
    PathLength = path.length;
    return resultOf(path.status);
}

ENavigationQueryResult UNavigationSystemV1::GetPathLength(UObject* WorldContextObject,
                                                          const FVector& PathStart, const FVector& PathEnd,
                                                          double& PathLength, ARecastNavMesh* NavData) {
    constexpr const char* kFunction = "UNavigationSystemV1.GetPathLength()";
    const Path path =
        navDataOf(WorldContextObject, NavData, kFunction).findPath(PathStart, PathEnd, kFunction);
    PathLength = path.length;
    return resultOf(path.status);
}

bool UNavigationSystemV1::K2_GetRandomReachablePointInRadius(UObject* WorldContextObject,
                                                             const FVector& Origin, FVector& RandomLocation,
                                                             double Radius, ARecastNavMesh* NavData) {
    constexpr const char* kFunction = "UNavigationSystemV1.K2_GetRandomReachablePointInRadius()";
    const auto point = navDataOf(WorldContextObject, NavData, kFunction)
                           .randomPointInRadius(Origin, Radius, true, kFunction);
    RandomLocation = point ? FVector::fromEigen(*point) : Origin;
    return point.has_value();
}

bool UNavigationSystemV1::K2_GetRandomLocationInNavigableRadius(UObject* WorldContextObject,
                                                                const FVector& Origin,
                                                                FVector& RandomLocation, double Radius,
                                                                ARecastNavMesh* NavData) {
    constexpr const char* kFunction = "UNavigationSystemV1.K2_GetRandomLocationInNavigableRadius()";
    const auto point = navDataOf(WorldContextObject, NavData, kFunction)
                           .randomPointInRadius(Origin, Radius, false, kFunction);
    RandomLocation = point ? FVector::fromEigen(*point) : Origin;
    return point.has_value();
}

bool UNavigationSystemV1::K2_ProjectPointToNavigation(UObject* WorldContextObject, const FVector& Point,
                                                      FVector& ProjectedLocation, ARecastNavMesh* NavData,
                                                      const FVector& QueryExtent) {
    constexpr const char* kFunction = "UNavigationSystemV1.K2_ProjectPointToNavigation()";
    return navDataOf(WorldContextObject, NavData, kFunction)
        .ProjectPointToNavigation(Point, ProjectedLocation, QueryExtent);
}

namespace sp::gameplay {

ARecastNavMesh* defaultNavigationIfAny(UWorld& world) {
    if (AActor* existing = world.find_actor_by_class(&ARecastNavMesh::StaticClass()))
        return static_cast<ARecastNavMesh*>(existing);
    if (!world.find_actor_by_class(&ANavMeshBoundsVolume::StaticClass()))
        return nullptr;
    return UNavigationSystemV1::GetNavigationSystem(&world)->GetDefaultNavDataInstance();
}

} // namespace sp::gameplay
