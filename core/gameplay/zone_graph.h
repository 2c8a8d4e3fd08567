#pragma once
// Lanes (UE's ZoneGraph, on sp::zonegraph's LaneGraph). An AZoneGraphData actor says how the world's roads
// become lanes: the spline actors tagged RoadTag are the roads' centre lines, LaneProfile their
// cross-section, JunctionTolerance how near a road's end must come to another road to join it. The lane graph
// is built from them on first use and again whenever a road spline, its actor's transform or a setting
// changed (the build is deterministic, so scenes save the roads and the settings, and a loaded scene rebuilds
// the same lanes).
//
// UZoneGraphSubsystem is the world's: GetZoneGraphSubsystem(WorldContextObject) returns it, and its queries
// (UE's names where UE has them) work on the world's first AZoneGraphData, spawned as "ZoneGraphData-Default"
// with the defaults when the world has none. Lanes are numbered 0..GetNumLanes() - 1: first each road piece's
// lanes in profile order, then the connector lanes through junctions and U-turns at free road ends. A query
// far from every lane finds nothing (LaneIndex -1), which is an answer, not an error.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/procedural/spline_component.h"
#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "core/world/math.h"
#include "core/zonegraph/lane_graph.h"

/// Which way a lane runs along its road (UE's EZoneLaneDirection).
SPENUM()
enum class EZoneLaneDirection : uint8_t {
    /// Along the road spline's direction.
    Forward = 0,
    /// Against it.
    Backward = 1,
};

/// Which of a lane's links (UE's EZoneLaneLinkType).
SPENUM()
enum class EZoneLaneLinkType : uint8_t {
    /// The lanes it leads into.
    Outgoing = 0,
    /// The lanes that lead into it.
    Incoming = 1,
    /// The lane beside it on its left that runs the same way (none, or one).
    AdjacentLeft = 2,
    /// The lane beside it on its right that runs the same way (none, or one).
    AdjacentRight = 3,
};

/// One lane of a road's cross-section (UE's FZoneLaneDesc).
SPSTRUCT()
struct FZoneLaneDesc {
    SP_GENERATED_BODY()

    /// What uses the lane ("Driving", "Sidewalk", ...); queries filter by it.
    SPPROPERTY()
    std::string Tag = "Driving";
    /// Metres (> 0).
    SPPROPERTY()
    double Width = 3.5;
    /// Which way it runs along the road.
    SPPROPERTY()
    EZoneLaneDirection Direction = EZoneLaneDirection::Forward;
};

/// A point on a lane (UE's FZoneGraphLaneLocation); LaneIndex is -1 when a query found none.
SPSTRUCT()
struct FZoneGraphLaneLocation {
    SP_GENERATED_BODY()

    /// The lane, or -1 (no location).
    SPPROPERTY()
    int LaneIndex = -1;
    /// Metres along the lane from its start.
    SPPROPERTY()
    double DistanceAlongLane = 0.0;
    /// The point on the lane's centre line, world space.
    SPPROPERTY()
    FVector Position;
    /// The unit direction the lane runs in there.
    SPPROPERTY()
    FVector Direction{1.0, 0.0, 0.0};
    /// The lane's up: +Z.
    SPPROPERTY()
    FVector Up{0.0, 0.0, 1.0};
};

/// How the world's roads become lanes, and the lane graph built from them (UE's AZoneGraphData).
SPCLASS()
class AZoneGraphData : public AActor {
    SP_GENERATED_BODY()
  public:
    AZoneGraphData();
    ~AZoneGraphData() override;

    /// Spline actors with this tag are roads (their splines the roads' centre lines).
    SPPROPERTY()
    std::string RoadTag = "Road";
    /// Every road's cross-section, from its right edge to its left edge looking along the spline. The
    /// default: a sidewalk, a driving lane each way (right-hand traffic), a sidewalk: 2 + 3.5 + 3.5 + 2 m.
    SPPROPERTY(Setter = SetLaneProfile)
    std::vector<FZoneLaneDesc> LaneProfile;
    /// A road's end within this many metres of another road joins it there (> 0).
    SPPROPERTY(Setter = SetJunctionTolerance)
    double JunctionTolerance = 1.0;
    /// Whether cameras see the roads: a surface over the lanes and junctions, and lane markings (object ids
    /// name this actor, with material slot 0 road, 1 sidewalk, 2 markings).
    SPPROPERTY()
    bool bDrawRoads = true;
    /// The drawn road's material (over driving lanes and junctions): an AMaterialLibrary name or a built-in
    /// one.
    SPPROPERTY()
    std::string RoadMaterial = "Asphalt";
    /// The drawn sidewalks' material (lanes tagged "Sidewalk").
    SPPROPERTY()
    std::string SidewalkMaterial = "Concrete";
    /// The lane markings' material.
    SPPROPERTY()
    std::string MarkingMaterial = "LaneMarking";

    /// Sets LaneProfile; raises InvalidArgumentError, leaving it as it was, for no lanes, a width not > 0 or
    /// an empty tag.
    SPFUNCTION()
    void SetLaneProfile(const std::vector<FZoneLaneDesc>& Profile);

    /// Sets JunctionTolerance (> 0).
    SPFUNCTION()
    void SetJunctionTolerance(double Tolerance);

    /// Builds the lane graph now from the roads as they are. Raises InvalidArgumentError naming both roads
    /// and the point when two roads cross without a junction (the graph stays as it was).
    SPFUNCTION()
    void RebuildGraph();

    // The graph for the roads as they are now, rebuilt first when they or the settings changed; `function`
    // names the caller in errors.
    const sp::zonegraph::LaneGraph& graph(const char* function);
    // The road actor a lane runs along (nullptr for a connector), as of the last build.
    ASplineActor* roadOf(int lane) const;
    // Counts the graph's builds: whoever draws the lanes redraws them when it changed.
    std::uint64_t graphRevision() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The world's lanes (UE's UZoneGraphSubsystem): queries on its first AZoneGraphData.
SPCLASS(Abstract)
class UZoneGraphSubsystem : public UObject {
    SP_GENERATED_BODY()
  public:
    /// Returns the zone graph subsystem of WorldContextObject's world.
    SPFUNCTION(NotNull)
    static UZoneGraphSubsystem* GetZoneGraphSubsystem(UObject* WorldContextObject);

    /// Returns the world's first AZoneGraphData, spawned (as "ZoneGraphData-Default") when it has none.
    SPFUNCTION(NotNull)
    AZoneGraphData* GetZoneGraphData();

    /// Returns the number of lanes (building the graph first if needed).
    SPFUNCTION()
    int GetNumLanes();

    /// Returns the number of junctions.
    SPFUNCTION()
    int GetNumJunctions();

    /// Returns the lane tags in use, in profile order.
    SPFUNCTION()
    std::vector<std::string> GetLaneTags();

    /// Finds the nearest point on a lane tagged Tag ("" for any) to Location within MaxDistance metres:
    /// true with OutLaneLocation and OutDistance (metres from Location), or false when there is none. Raises
    /// InvalidArgumentError for a tag no lane has (naming the tags there are).
    SPFUNCTION()
    bool FindNearestLane(const FVector& Location, double MaxDistance, const std::string& Tag,
                         FZoneGraphLaneLocation& OutLaneLocation, double& OutDistance);

    /// The nearest location on a lane tagged TagName to Location within MaxDistance metres; LaneIndex -1 when
    /// there is none (the form the paper's control_city_sample calls).
    SPFUNCTION()
    FZoneGraphLaneLocation FindNearestLaneLocationByName(const FVector& Location, const std::string& TagName,
                                                         double MaxDistance = 50.0);

    /// Finds the nearest lane location for each row of Locations ((N, 3) float64) in one call:
    /// OutLaneIndices (N,) int64 (-1 where none is within MaxDistance), OutPositions (N, 3) and
    /// OutDistancesAlongLane (N,) (NaN where none is).
    SPFUNCTION()
    void FindNearestLanes(const sp::reflect::SpArray<double>& Locations, double MaxDistance,
                          const std::string& Tag, sp::reflect::SpArray<int64_t>& OutLaneIndices,
                          sp::reflect::SpArray<double>& OutPositions,
                          sp::reflect::SpArray<double>& OutDistancesAlongLane);

    /// Returns the lane's length in metres.
    SPFUNCTION()
    double GetLaneLength(int LaneIndex);

    /// Returns the lane's width in metres.
    SPFUNCTION()
    double GetLaneWidth(int LaneIndex);

    /// Returns the lane's tag.
    SPFUNCTION()
    std::string GetLaneTag(int LaneIndex);

    /// Returns the road actor the lane runs along, or None for a connector through a junction or a U-turn.
    SPFUNCTION()
    ASplineActor* GetLaneRoad(int LaneIndex);

    /// Returns the location Distance metres along the lane (clamped to it).
    SPFUNCTION()
    FZoneGraphLaneLocation CalculateLocationAlongLane(int LaneIndex, double Distance);

    /// Returns InLaneLocation moved AdvanceDistance metres along its lane (negative: back), stopping at the
    /// lane's ends.
    SPFUNCTION()
    FZoneGraphLaneLocation AdvanceLaneLocation(const FZoneGraphLaneLocation& InLaneLocation,
                                               double AdvanceDistance);

    /// Returns the lanes linked to the lane by Type.
    SPFUNCTION()
    std::vector<int> GetLinkedLanes(int LaneIndex, EZoneLaneLinkType Type);

    /// Returns the lane's centre line, an (N, 3) float64 array from its start to its end.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetLanePoints(int LaneIndex);

    /// Returns every lane's centre line at once (for drawing a map): OutPoints (M, 3), lane i being rows
    /// OutStarts[i] to OutStarts[i + 1] (an (N + 1,) int64 array).
    SPFUNCTION()
    void GetAllLanePoints(sp::reflect::SpArray<double>& OutPoints, sp::reflect::SpArray<int64_t>& OutStarts);

    // The world's subsystem, for the engine's own code (no frame check: it runs inside the world's tick).
    static UZoneGraphSubsystem& of(UWorld& world);

  private:
    const sp::zonegraph::LaneGraph& graph(const char* function);
    int checkedLane(int LaneIndex, const char* function);

    // The AZoneGraphData GetZoneGraphData() found last: still the world's first while it lives (actors keep
    // their spawn order), so a query does not look through every actor for it.
    sp::reflect::ObjectHandle data_;
};

namespace sp::gameplay {
// A lane graph's location as the reflected struct.
FZoneGraphLaneLocation toLaneLocation(const sp::zonegraph::LaneLocation& location);
} // namespace sp::gameplay
