#pragma once
// Navigation (UE's NavigationSystem, on Recast/Detour through sp::navigation). An ARecastNavMesh actor is
// the navigation data of one agent profile (radius, height, slope, step); it is built from the world's
// unsimulated collision geometry (see core/gameplay/navigation_subsystem.h for which) inside the world's
// ANavMeshBoundsVolume actors, or around all of that geometry when there is none. It builds on first use
// and, while bRebuildAutomatically, rebuilds the tiles under geometry that appeared, moved or went away
// before its next query. Scenes save its settings; the mesh is rebuilt from them on load (the
// build is deterministic).
//
// UNavigationSystemV1 is the world's navigation system: GetNavigationSystem(WorldContextObject) returns it,
// GetNavDataForAgentName finds an agent's data, and UE's static query functions are here too, working on
// the default navigation data (the first ARecastNavMesh, spawned as "RecastNavMesh-Default" when the
// world has none). Batch queries take and return (N, 3) float64 arrays.

#include <map>
#include <memory>
#include <random>
#include <string>

#include "core/gameplay/navigation_subsystem.h"
#include "core/navigation/nav_mesh.h"
#include "core/physics/body_id.h"
#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "core/world/math.h"
#include "core/world/shape_components.h"

/// What a navigation query ended with (UE's ENavigationQueryResult).
SPENUM()
enum class ENavigationQueryResult : uint8_t {
    /// The start or the end is not on the navigation mesh (within the query extent).
    Invalid = 0,
    /// There is no navigation mesh: no static geometry to build one from.
    Error = 1,
    /// The end cannot be reached from the start; a path leads as close as it can.
    Fail = 2,
    /// A complete path.
    Success = 3,
};

/// Where navigation is built: the box of its BoxComponent (which collides with nothing).
SPCLASS()
class ANavMeshBoundsVolume : public AActor {
    SP_GENERATED_BODY()
  public:
    ANavMeshBoundsVolume();

    /// The volume's box (the root component); BoxExtent and the actor's transform place it.
    SPPROPERTY(ReadOnly, NotNull)
    UBoxComponent* BoxComponent = nullptr;

    // The world-axis box that holds the volume.
    Eigen::AlignedBox3d worldBounds() const;
};

/// Navigation data for one agent profile: a tiled Recast navigation mesh and the queries on it.
SPCLASS()
class ARecastNavMesh : public AActor {
    SP_GENERATED_BODY()
  public:
    ARecastNavMesh();
    ~ARecastNavMesh() override;

    /// The agent profile's name (UNavigationSystemV1.GetNavDataForAgentName finds it by this).
    SPPROPERTY()
    std::string AgentName = "Default";
    /// Clearance kept from walls and edges, metres (>= 0).
    SPPROPERTY()
    double AgentRadius = 0.35;
    /// Headroom the agent needs, metres (> 0).
    SPPROPERTY()
    double AgentHeight = 1.8;
    /// Steepest walkable ground, degrees in (0, 90).
    SPPROPERTY()
    double AgentMaxSlope = 45.0;
    /// Highest ledge the agent steps up or down, metres (>= 0).
    SPPROPERTY()
    double AgentMaxStepHeight = 0.35;
    /// Horizontal voxel size, metres (> 0): smaller is finer and slower to build.
    SPPROPERTY()
    double CellSize = 0.1;
    /// Vertical voxel size, metres (> 0).
    SPPROPERTY()
    double CellHeight = 0.05;
    /// Side of a tile, metres (at least 8 cells): the unit rebuilt when geometry changes.
    SPPROPERTY()
    double TileSize = 12.8;
    /// Walkable islands smaller than this are dropped, square metres (>= 0).
    SPPROPERTY()
    double MinRegionArea = 0.5;
    /// Whether geometry changes rebuild the tiles under them before the next query (else only
    /// RebuildNavigation does).
    SPPROPERTY()
    bool bRebuildAutomatically = true;
    /// Seed of the random points' generator (SetRandomSeed restarts the sequence).
    SPPROPERTY(Setter = SetRandomSeed)
    int RandomSeed = 0;

    /// Restarts the random point sequence from Seed.
    SPFUNCTION()
    void SetRandomSeed(int Seed);

    /// Builds the whole navigation mesh now from the current geometry and settings.
    SPFUNCTION()
    void RebuildNavigation();

    /// Returns the number of tiles that hold navigation polygons (building first if needed).
    SPFUNCTION()
    int GetNumTiles();

    /// Returns the number of navigation polygons.
    SPFUNCTION()
    int GetNumPolygons();

    /// Returns the navigable area in square metres (horizontal projection).
    SPFUNCTION()
    double GetNavigableArea();

    /// Returns the seconds the last build or tile rebuild took.
    SPFUNCTION()
    double GetLastBuildSeconds() const { return lastBuildSeconds_; }

    /// Returns the number of tiles the last build or rebuild voxelised.
    SPFUNCTION()
    int GetLastBuildTileCount() const { return lastBuildTiles_; }

    /// Finds the shortest path from Start to End (each projected onto the mesh): its corners as an (N, 3)
    /// array from start to end, and its length in metres. Fail: End is unreachable and the path leads to
    /// the reachable point nearest it; Invalid: Start or End is not on the mesh (no points).
    SPFUNCTION()
    ENavigationQueryResult FindPath(const FVector& Start, const FVector& End,
                                    sp::reflect::SpArray<double>& PathPoints, double& PathLength);

    /// Finds a path for each row of StartPoints and EndPoints ((N, 3) arrays): the corners of all of them
    /// in one (M, 3) array, path i being rows PathStarts[i] to PathStarts[i + 1] (an (N + 1,) int64 array),
    /// with Lengths (N,) and Results (N,) (ENavigationQueryResult values, uint8).
    SPFUNCTION()
    void FindPaths(const sp::reflect::SpArray<double>& StartPoints,
                   const sp::reflect::SpArray<double>& EndPoints, sp::reflect::SpArray<double>& PathPoints,
                   sp::reflect::SpArray<int64_t>& PathStarts, sp::reflect::SpArray<double>& Lengths,
                   sp::reflect::SpArray<uint8_t>& Results);

    /// Returns the length of the shortest path from Start to End in metres, or infinity when End is not
    /// reachable (or either is off the mesh).
    SPFUNCTION()
    double GetGeodesicDistance(const FVector& Start, const FVector& End);

    /// Returns NumPoints points drawn uniformly over the navigable area, as an (N, 3) array.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetRandomPoints(int NumPoints);

    /// Returns, for each row of Origins ((N, 3)), a point drawn uniformly over the navigable area within
    /// Radius metres (horizontally) that is reachable from the origin; a row of NaN where there is none.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetRandomReachablePointsInRadius(const sp::reflect::SpArray<double>& Origins,
                                                                  double Radius);

    /// Projects Point onto the mesh: the nearest navigable point within QueryExtent (half sizes; zero: two
    /// agent radii sideways and an agent height up and down). Returns false when there is none.
    SPFUNCTION()
    bool ProjectPointToNavigation(const FVector& Point, FVector& ProjectedLocation,
                                  const FVector& QueryExtent = FVector());

    /// Returns whether Point is on the navigable area: over it, and at most MaxVerticalDistance metres above
    /// or below its surface.
    SPFUNCTION()
    bool IsNavigable(const FVector& Point, double MaxVerticalDistance = 0.5);

    /// Returns the mesh's surface as triangles, a (T, 3, 3) array of corners (for drawing a map).
    SPFUNCTION()
    sp::reflect::SpArray<double> GetNavMeshTriangles();

    void PostPropertyChanged(std::string_view propertyName) override;

    // Builds or updates the mesh as the settings and bRebuildAutomatically say; `function` names the caller
    // in errors. Returns the mesh (empty when there is no geometry).
    sp::navigation::NavMesh& ensureBuilt(const char* function);
    sp::navigation::Path findPath(const FVector& start, const FVector& end, const char* function);
    std::optional<Eigen::Vector3d> randomPointInRadius(const FVector& origin, double radius,
                                                       bool reachableOnly, const char* function);

  private:
    sp::navigation::NavMeshSettings settings() const;
    void build(const char* function);
    sp::navigation::NavMesh& update(const char* function);

    std::unique_ptr<sp::navigation::NavMesh> mesh_;
    // What the mesh was built from: the bodies' poses and world boxes, and the settings (the region is the
    // mesh's own).
    std::map<sp::physics::BodyId, sp::gameplay::NavigationSubsystem::Placed> builtBodies_;
    sp::navigation::NavMeshSettings builtSettings_;
    // The settings as they were after the last change that passed validate(): a refused change is undone.
    sp::navigation::NavMeshSettings accepted_;
    bool stale_ = true; // settings changed or a rebuild was asked for
    std::mt19937_64 random_;
    double lastBuildSeconds_ = 0.0;
    int lastBuildTiles_ = 0;
};

/// The world's navigation system (UE's UNavigationSystemV1).
SPCLASS(Abstract)
class UNavigationSystemV1 : public UObject {
    SP_GENERATED_BODY()
  public:
    /// Returns the navigation system of WorldContextObject's world.
    SPFUNCTION(NotNull)
    static UNavigationSystemV1* GetNavigationSystem(UObject* WorldContextObject);

    /// Returns the navigation data of agent profile AgentName, or None.
    SPFUNCTION()
    ARecastNavMesh* GetNavDataForAgentName(const std::string& AgentName) const;

    /// Returns the default navigation data: the world's first ARecastNavMesh, spawned (as
    /// "RecastNavMesh-Default") when it has none.
    SPFUNCTION(NotNull)
    ARecastNavMesh* GetDefaultNavDataInstance();

    /// Rebuilds every navigation data of the world now.
    SPFUNCTION()
    void Build();

    /// Finds the shortest path from PathStart to PathEnd on NavData (None: the default): its corners
    /// ((N, 3)) and length. Unlike UE, which returns a UNavigationPath, the points come back directly.
    SPFUNCTION()
    static ENavigationQueryResult
    FindPathToLocationSynchronously(UObject* WorldContextObject, const FVector& PathStart,
                                    const FVector& PathEnd, sp::reflect::SpArray<double>& PathPoints,
                                    double& PathLength, ARecastNavMesh* NavData = nullptr);

    /// Computes the length of the shortest path from PathStart to PathEnd on NavData (None: the default).
    SPFUNCTION()
    static ENavigationQueryResult GetPathLength(UObject* WorldContextObject, const FVector& PathStart,
                                                const FVector& PathEnd, double& PathLength,
                                                ARecastNavMesh* NavData = nullptr);

    /// Draws a point reachable from Origin within Radius metres; returns false when there is none.
    SPFUNCTION()
    static bool K2_GetRandomReachablePointInRadius(UObject* WorldContextObject, const FVector& Origin,
                                                   FVector& RandomLocation, double Radius,
                                                   ARecastNavMesh* NavData = nullptr);

    /// Draws a navigable point within Radius metres of Origin, reachable or not; returns false when there is
    /// none.
    SPFUNCTION()
    static bool K2_GetRandomLocationInNavigableRadius(UObject* WorldContextObject, const FVector& Origin,
                                                      FVector& RandomLocation, double Radius,
                                                      ARecastNavMesh* NavData = nullptr);

    /// Projects Point onto NavData within QueryExtent (zero: the agent's default extent); returns false when
    /// no navigable point is that close.
    SPFUNCTION()
    static bool K2_ProjectPointToNavigation(UObject* WorldContextObject, const FVector& Point,
                                            FVector& ProjectedLocation, ARecastNavMesh* NavData = nullptr,
                                            const FVector& QueryExtent = FVector());
};

namespace sp::gameplay {

// The default navigation data of `world` when it has navigation (an ARecastNavMesh or an
// ANavMeshBoundsVolume; spawning the data for a bounds volume), else nullptr: moves use it to path-find.
ARecastNavMesh* defaultNavigationIfAny(UWorld& world);

} // namespace sp::gameplay
