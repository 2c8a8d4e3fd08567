#include "core/gameplay/zone_graph.h"

#include <cmath>
#include <optional>

#include "core/base/error.h"
#include "core/gameplay/point_arrays.h"
#include "core/procedural/spline_component.h"
#include "core/world/object_access.h"
#include "core/world/world.h"
#include "core/world/world_subsystem.h"

namespace {

namespace zonegraph = sp::zonegraph;

// Road splines are followed in segments of this length (fewer on very long roads).
constexpr double kRoadStep = 0.5;
constexpr int kMaxRoadSegments = 20'000;
// The most locations one call answers.
constexpr int64_t kMaxLocations = 10'000'000;

// The world's UZoneGraphSubsystem object, made with the world's first use of it.
class ZoneGraphWorldSubsystem : public sp::world::WorldSubsystem {
  public:
    static constexpr int kTickOrder = sp::world::tick_order::kPhysics + 60; // nothing to tick

    explicit ZoneGraphWorldSubsystem(UWorld& world) : system_(new UZoneGraphSubsystem()) {
        system_->InitObject("ZoneGraphSubsystem", &world);
    }
    ~ZoneGraphWorldSubsystem() override { sp::reflect::ObjectTable::rememberName(*system_); }

    UZoneGraphSubsystem& system() { return *system_; }

  private:
    std::unique_ptr<UZoneGraphSubsystem> system_;
};

zonegraph::RoadProfile profileOf(const std::vector<FZoneLaneDesc>& descs) {
    zonegraph::RoadProfile profile;
    for (const FZoneLaneDesc& desc : descs)
        profile.lanes.push_back({desc.Tag, desc.Width, desc.Direction == EZoneLaneDirection::Forward});
    return profile;
}

} // namespace

FZoneGraphLaneLocation sp::gameplay::toLaneLocation(const zonegraph::LaneLocation& location) {

    FZoneGraphLaneLocation out;
    out.LaneIndex = location.lane;
    out.DistanceAlongLane = location.distance;
    out.Position = FVector::fromEigen(location.position);
    out.Direction = FVector::fromEigen(location.direction);
    return out;
}

// -- AZoneGraphData ---------------------------------------------------------------------------------------

struct AZoneGraphData::Impl {
    std::optional<zonegraph::LaneGraph> graph;
    // What the graph was built from: each road's handle, curve revision and transform, then the settings.
    std::vector<double> builtFrom;
    std::vector<sp::reflect::ObjectHandle> roads; // by the graph's road index
    std::uint64_t revision = 0;
};

AZoneGraphData::AZoneGraphData() : impl_(std::make_unique<Impl>()) {
    for (const zonegraph::LaneDesc& lane : zonegraph::RoadProfile::twoWayStreet().lanes)
        LaneProfile.push_back({lane.tag, lane.width,
                               lane.forward ? EZoneLaneDirection::Forward : EZoneLaneDirection::Backward});
}

AZoneGraphData::~AZoneGraphData() = default;

void AZoneGraphData::SetLaneProfile(const std::vector<FZoneLaneDesc>& Profile) {
    SP_CHECK(!Profile.empty(), sp::InvalidArgument, "AZoneGraphData.SetLaneProfile(): Profile has no lanes");
    for (size_t i = 0; i < Profile.size(); ++i) {
        SP_CHECK(std::isfinite(Profile[i].Width) && Profile[i].Width > 0.0, sp::InvalidArgument,
                 "AZoneGraphData.SetLaneProfile(): Profile[", i, "].Width must be > 0, got ",
                 Profile[i].Width);
        SP_CHECK(!Profile[i].Tag.empty(), sp::InvalidArgument, "AZoneGraphData.SetLaneProfile(): Profile[", i,
                 "].Tag is empty");
    }
    LaneProfile = Profile;
}

void AZoneGraphData::SetJunctionTolerance(double Tolerance) {
    sp::checkSetting(std::isfinite(Tolerance) && Tolerance > 0.0, "AZoneGraphData", "JunctionTolerance",
                     "> 0", Tolerance);
    JunctionTolerance = Tolerance;
}

void AZoneGraphData::RebuildGraph() {
    impl_->builtFrom.clear();
    graph("AZoneGraphData.RebuildGraph()");
}

const zonegraph::LaneGraph& AZoneGraphData::graph(const char* function) {
    // The roads in spawn order, and what they and the settings are now.
    std::vector<ASplineActor*> roads;
    std::vector<double> key;
    key.reserve(impl_->builtFrom.size()); // the same size as last time, unless the roads changed
    for (AActor* actor : GetWorld()->find_actors_by_tag(RoadTag))
        if (auto* road = dynamic_cast<ASplineActor*>(actor)) {
            roads.push_back(road);
            const USplineComponent& spline = *road->SplineComponent;
            key.insert(key.end(), {double(road->GetHandle().index), double(road->GetHandle().generation),
                                   double(spline.curveRevision())});
            // Where the road is: its own transform as set, while nothing it is attached to can move it (no
            // trigonometry: a query checks every road), else the transform composed through its parents.
            if (!spline.GetAttachParent()) {
                const FVector &l = spline.RelativeLocation, &s = spline.RelativeScale3D;
                const FRotator& r = spline.RelativeRotation;
                key.insert(key.end(), {0.0, l.X, l.Y, l.Z, r.Pitch, r.Yaw, r.Roll, s.X, s.Y, s.Z});
            } else {
                const FTransform t = spline.GetComponentTransform();
                key.insert(key.end(),
                           {1.0, t.Translation.X, t.Translation.Y, t.Translation.Z, t.Rotation.X,
                            t.Rotation.Y, t.Rotation.Z, t.Rotation.W, t.Scale3D.X, t.Scale3D.Y, t.Scale3D.Z});
            }
        }
    key.push_back(JunctionTolerance);
    for (const FZoneLaneDesc& lane : LaneProfile) {
        key.insert(key.end(), {lane.Width, double(lane.Direction), double(lane.Tag.size())});
        key.insert(key.end(), lane.Tag.begin(), lane.Tag.end());
    }
    if (impl_->graph && key == impl_->builtFrom)
        return *impl_->graph;

    std::vector<zonegraph::RoadInput> inputs;
    for (ASplineActor* road : roads) {
        std::vector<Eigen::Vector3d> line = road->SplineComponent->worldPolyline(kRoadStep, kMaxRoadSegments);
        SP_CHECK(line.size() >= 2, sp::InvalidArgument, function, ": road '", road->GetName(),
                 "' has fewer than two spline points");
        inputs.push_back({road->GetName(), std::move(line)});
    }
    zonegraph::BuildOptions options;
    options.junctionTolerance = JunctionTolerance;
    try {
        impl_->graph = zonegraph::LaneGraph::build(inputs, profileOf(LaneProfile), options);
    } catch (const sp::InvalidArgument& e) {
        // The builder's message names the roads; the caller is the user's function.
        std::string message = e.what();
        constexpr std::string_view kBuilder = "LaneGraph::build(): ";
        if (message.starts_with(kBuilder))
            message.erase(0, kBuilder.size());
        SP_THROW(sp::InvalidArgument, function, ": ", message);
    }
    impl_->builtFrom = std::move(key);
    ++impl_->revision;
    impl_->roads.clear();
    for (ASplineActor* road : roads)
        impl_->roads.push_back(road->GetHandle());
    return *impl_->graph;
}

std::uint64_t AZoneGraphData::graphRevision() const {
    return impl_->revision;
}

ASplineActor* AZoneGraphData::roadOf(int lane) const {
    if (!impl_->graph || lane < 0 || lane >= int(impl_->graph->lanes().size()))
        return nullptr;
    const int road = impl_->graph->lanes()[size_t(lane)].road;
    if (road < 0)
        return nullptr;
    return dynamic_cast<ASplineActor*>(sp::reflect::ObjectTable::find(impl_->roads[size_t(road)]));
}

// -- UZoneGraphSubsystem ----------------------------------------------------------------------------------

UZoneGraphSubsystem* UZoneGraphSubsystem::GetZoneGraphSubsystem(UObject* WorldContextObject) {
    UWorld& world =
        sp::world::worldOfContext(WorldContextObject, "UZoneGraphSubsystem.GetZoneGraphSubsystem()");
    return &of(world);
}

UZoneGraphSubsystem& UZoneGraphSubsystem::of(UWorld& world) {
    return world.GetSubsystem<ZoneGraphWorldSubsystem>().system();
}

AZoneGraphData* UZoneGraphSubsystem::GetZoneGraphData() {
    if (auto* known = dynamic_cast<AZoneGraphData*>(sp::reflect::ObjectTable::find(data_));
        known && known->GetWorld() == GetWorld())
        return known;
    auto* data =
        static_cast<AZoneGraphData*>(GetWorld()->find_actor_by_class(&AZoneGraphData::StaticClass()));
    if (!data)
        data = static_cast<AZoneGraphData*>(GetWorld()->spawn_actor(&AZoneGraphData::StaticClass(), FVector(),
                                                                    FRotator(), "ZoneGraphData-Default"));
    data_ = data->GetHandle();
    return data;
}

const zonegraph::LaneGraph& UZoneGraphSubsystem::graph(const char* function) {
    return GetZoneGraphData()->graph(function);
}

int UZoneGraphSubsystem::checkedLane(int LaneIndex, const char* function) {
    const int count = int(graph(function).lanes().size());
    SP_CHECK(LaneIndex >= 0 && LaneIndex < count, sp::InvalidArgument, function, ": LaneIndex ", LaneIndex,
             " is not a lane (there are ", count, ")");
    return LaneIndex;
}

int UZoneGraphSubsystem::GetNumLanes() {
    return int(graph("UZoneGraphSubsystem.GetNumLanes()").lanes().size());
}

int UZoneGraphSubsystem::GetNumJunctions() {
    return int(graph("UZoneGraphSubsystem.GetNumJunctions()").junctions().size());
}

std::vector<std::string> UZoneGraphSubsystem::GetLaneTags() {
    return graph("UZoneGraphSubsystem.GetLaneTags()").tagNames();
}

namespace {

// The tag's index ("" any: -1); an unknown tag is an error naming the ones there are.
int tagOf(const zonegraph::LaneGraph& graph, const std::string& tag, const char* function) {
    if (tag.empty())
        return -1;
    const int index = graph.tagIndex(tag);
    if (index < 0) {
        std::string known;
        for (const std::string& name : graph.tagNames())
            known += (known.empty() ? "" : ", ") + name;
        SP_THROW(sp::InvalidArgument, function, ": no lane has tag '", tag,
                 "' (the lanes' tags: ", known.empty() ? "none, there are no lanes" : known, ")");
    }
    return index;
}

void checkDistance(double distance, const char* function, const char* name) {
    SP_CHECK(!std::isnan(distance) && distance >= 0.0, sp::InvalidArgument, function, ": ", name, " ",
             distance, " must be >= 0");
}

} // namespace

bool UZoneGraphSubsystem::FindNearestLane(const FVector& Location, double MaxDistance, const std::string& Tag,
                                          FZoneGraphLaneLocation& OutLaneLocation, double& OutDistance) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.FindNearestLane()";
    sp::gameplay::checkFinite(Location, kFunction, "Location");
    checkDistance(MaxDistance, kFunction, "MaxDistance");
    const zonegraph::LaneGraph& lanes = graph(kFunction);
    const auto found = lanes.nearest(Location.toEigen(), MaxDistance, tagOf(lanes, Tag, kFunction));
    OutLaneLocation = found ? sp::gameplay::toLaneLocation(*found) : FZoneGraphLaneLocation();
    OutDistance = found ? (found->position - Location.toEigen()).norm() : 0.0;
    return found.has_value();
}

FZoneGraphLaneLocation UZoneGraphSubsystem::FindNearestLaneLocationByName(const FVector& Location,
                                                                          const std::string& TagName,
                                                                          double MaxDistance) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.FindNearestLaneLocationByName()";
    sp::gameplay::checkFinite(Location, kFunction, "Location");
    checkDistance(MaxDistance, kFunction, "MaxDistance");
    const zonegraph::LaneGraph& lanes = graph(kFunction);
    const auto found = lanes.nearest(Location.toEigen(), MaxDistance, tagOf(lanes, TagName, kFunction));
    return found ? sp::gameplay::toLaneLocation(*found) : FZoneGraphLaneLocation();
}

void UZoneGraphSubsystem::FindNearestLanes(const sp::reflect::SpArray<double>& Locations, double MaxDistance,
                                           const std::string& Tag,
                                           sp::reflect::SpArray<int64_t>& OutLaneIndices,
                                           sp::reflect::SpArray<double>& OutPositions,
                                           sp::reflect::SpArray<double>& OutDistancesAlongLane) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.FindNearestLanes()";
    const int64_t count = sp::gameplay::rowsOf(Locations, kFunction, "Locations");
    SP_CHECK(count <= kMaxLocations, sp::InvalidArgument, kFunction, ": ", count, " locations are more than ",
             kMaxLocations);
    checkDistance(MaxDistance, kFunction, "MaxDistance");
    const zonegraph::LaneGraph& lanes = graph(kFunction);
    const int tag = tagOf(lanes, Tag, kFunction);
    sp::reflect::SpArray<int64_t> indices("OutLaneIndices");
    sp::reflect::SpArray<double> positions("OutPositions"), distances("OutDistancesAlongLane");
    indices.resize({count});
    positions.resize({count, 3});
    distances.resize({count});
    for (int64_t i = 0; i < count; ++i) {
        const auto found = lanes.nearest(sp::gameplay::rowOf(Locations, i).toEigen(), MaxDistance, tag);
        indices.data()[i] = found ? found->lane : -1;
        const Eigen::Vector3d at = found ? found->position : Eigen::Vector3d::Constant(std::nan(""));
        std::copy(at.data(), at.data() + 3, positions.data() + 3 * i);
        distances.data()[i] = found ? found->distance : std::nan("");
    }
    OutLaneIndices = std::move(indices);
    OutPositions = std::move(positions);
    OutDistancesAlongLane = std::move(distances);
}

double UZoneGraphSubsystem::GetLaneLength(int LaneIndex) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.GetLaneLength()";
    return graph(kFunction).lanes()[size_t(checkedLane(LaneIndex, kFunction))].length();
}

double UZoneGraphSubsystem::GetLaneWidth(int LaneIndex) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.GetLaneWidth()";
    return graph(kFunction).lanes()[size_t(checkedLane(LaneIndex, kFunction))].width;
}

std::string UZoneGraphSubsystem::GetLaneTag(int LaneIndex) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.GetLaneTag()";
    const zonegraph::LaneGraph& lanes = graph(kFunction);
    return lanes.tagNames()[size_t(lanes.lanes()[size_t(checkedLane(LaneIndex, kFunction))].tag)];
}

ASplineActor* UZoneGraphSubsystem::GetLaneRoad(int LaneIndex) {
    return GetZoneGraphData()->roadOf(checkedLane(LaneIndex, "UZoneGraphSubsystem.GetLaneRoad()"));
}

FZoneGraphLaneLocation UZoneGraphSubsystem::CalculateLocationAlongLane(int LaneIndex, double Distance) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.CalculateLocationAlongLane()";
    SP_CHECK(std::isfinite(Distance), sp::InvalidArgument, kFunction, ": Distance ", Distance,
             " is not finite");
    return sp::gameplay::toLaneLocation(
        graph(kFunction).locationAt(checkedLane(LaneIndex, kFunction), Distance));
}

FZoneGraphLaneLocation UZoneGraphSubsystem::AdvanceLaneLocation(const FZoneGraphLaneLocation& InLaneLocation,
                                                                double AdvanceDistance) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.AdvanceLaneLocation()";
    SP_CHECK(std::isfinite(AdvanceDistance), sp::InvalidArgument, kFunction, ": AdvanceDistance ",
             AdvanceDistance, " is not finite");
    SP_CHECK(std::isfinite(InLaneLocation.DistanceAlongLane), sp::InvalidArgument, kFunction,
             ": InLaneLocation.DistanceAlongLane ", InLaneLocation.DistanceAlongLane, " is not finite");
    const int lane = checkedLane(InLaneLocation.LaneIndex, kFunction);
    return sp::gameplay::toLaneLocation(
        graph(kFunction).locationAt(lane, InLaneLocation.DistanceAlongLane + AdvanceDistance));
}

std::vector<int> UZoneGraphSubsystem::GetLinkedLanes(int LaneIndex, EZoneLaneLinkType Type) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.GetLinkedLanes()";
    const zonegraph::Lane& lane = graph(kFunction).lanes()[size_t(checkedLane(LaneIndex, kFunction))];
    switch (Type) {
    case EZoneLaneLinkType::Outgoing:
        return lane.next;
    case EZoneLaneLinkType::Incoming:
        return lane.prev;
    case EZoneLaneLinkType::AdjacentLeft:
        return lane.left >= 0 ? std::vector<int>{lane.left} : std::vector<int>{};
    case EZoneLaneLinkType::AdjacentRight:
        return lane.right >= 0 ? std::vector<int>{lane.right} : std::vector<int>{};
    }
    SP_THROW(sp::InvalidArgument, kFunction, ": Type ", int(Type), " is not an EZoneLaneLinkType");
}

sp::reflect::SpArray<double> UZoneGraphSubsystem::GetLanePoints(int LaneIndex) {
    constexpr const char* kFunction = "UZoneGraphSubsystem.GetLanePoints()";
    return sp::gameplay::toArray(graph(kFunction).lanes()[size_t(checkedLane(LaneIndex, kFunction))].points,
                                 "points");
}

void UZoneGraphSubsystem::GetAllLanePoints(sp::reflect::SpArray<double>& OutPoints,
                                           sp::reflect::SpArray<int64_t>& OutStarts) {
    const zonegraph::LaneGraph& lanes = graph("UZoneGraphSubsystem.GetAllLanePoints()");
    std::vector<Eigen::Vector3d> points;
    sp::reflect::SpArray<int64_t> starts("OutStarts");
    starts.resize({int64_t(lanes.lanes().size()) + 1});
    for (size_t l = 0; l < lanes.lanes().size(); ++l) {
        starts.data()[l] = int64_t(points.size());
        points.insert(points.end(), lanes.lanes()[l].points.begin(), lanes.lanes()[l].points.end());
    }
    starts.data()[lanes.lanes().size()] = int64_t(points.size());
    OutPoints = sp::gameplay::toArray(points, "OutPoints");
    OutStarts = std::move(starts);
}
