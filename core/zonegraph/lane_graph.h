#pragma once
// LaneGraph: the lanes of a road network (in the spirit of UE's ZoneGraph), built from road centre lines and
// a cross-section profile, and the queries an agent needs: the nearest lane location to a point (by a grid of
// the lanes' segments, not a scan), a location moved along its lane, and the lanes a lane links to.
//
// Building: where a road ends on another road (at its end or anywhere along it) there is a junction; roads
// are cut into pieces at their junctions, and each piece gets the profile's lanes side by side (offset from
// the centre line to the right, looking along the road; a lane running against the road has its points
// reversed). Lanes stop short of a junction by half the profile's width and a corner radius (room to turn),
// and inside it every lane arriving links to every lane of the same tag leaving on another piece, through a
// connector lane (a cubic curve from the one's end to the other's start). At a road's free end the arriving
// lanes turn back onto the leaving lanes of the same tag (a U-turn connector), and a closed road's lanes link
// end to start. Two roads that cross with no junction are an error: where they meet is unknown (a bridge? a
// crossing?), so one must end there. Deterministic: the same roads in the same order give the same lanes in
// the same order.
//
// World coordinates, metres, Z up; "right" of a direction d is d x Z. Pure logic: no engine objects.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace sp::zonegraph {

// One lane of a road's cross-section.
struct LaneDesc {
    std::string tag = "Driving"; // what uses the lane ("Driving", "Sidewalk", ...): queries filter by it
    double width = 3.5;          // metres, > 0
    bool forward = true;         // runs along the road's direction (else against it)
};

// A road's cross-section: its lanes from the road's right edge to its left edge, looking along the road.
struct RoadProfile {
    std::vector<LaneDesc> lanes;
    double totalWidth() const;
    // Right-hand traffic: a sidewalk, a lane each way, a sidewalk (2 + 3.5 + 3.5 + 2 metres).
    static RoadProfile twoWayStreet();
};

// A road to build lanes along: its centre line as a polyline (at least two points, dense enough to follow
// its curves), first and last point equal for a closed road.
struct RoadInput {
    std::string name; // for errors ("road 'Main' crosses road 'Side' at ...")
    std::vector<Eigen::Vector3d> points;
};

struct BuildOptions {
    // A road end within this distance of another road joins it (metres).
    double junctionTolerance = 1.0;
    // Lanes stop this much further from a junction than the roads' half width (metres), so that the tightest
    // turn through it (the right turn from the rightmost lane) has about this radius plus the sidewalk's
    // width: room for a car's turning circle (a 4.2 m car steering 35 degrees needs 3.7 m).
    double cornerRadius = 3.0;
    // Connector lanes are sampled with this many segments.
    int connectorSegments = 8;
};

struct Lane {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> distances; // arc length at each point, from 0 to the lane's length
    double width = 0.0;
    int tag = 0;               // index into LaneGraph::tagNames()
    int road = -1;             // the input road the lane runs along; -1 for a connector inside a junction
    int junction = -1;         // the junction a connector crosses; -1 for a road lane
    std::vector<int> next;     // lanes this one leads into (outgoing links)
    std::vector<int> prev;     // lanes that lead into this one (incoming links)
    int left = -1, right = -1; // the neighbouring lanes of the same piece that run the same way
    int piece = -1; // the road piece a road lane is on (its lanes are consecutive, in profile order); -1 for
                    // a connector
    int slot = -1;  // the lane's place in the road profile (0: the right edge); -1 for a connector

    double length() const { return distances.back(); }
};

// A point on a lane.
struct LaneLocation {
    int lane = -1;
    double distance = 0.0; // along the lane from its start, metres
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX(); // unit tangent, the way the lane runs
};

struct Junction {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    std::vector<int> roads; // the input roads that meet there
};

class LaneGraph {
  public:
    // Throws InvalidArgument naming the road for a road with fewer than two distinct points, a bad profile
    // (no lanes, a width not > 0, an empty tag), and two roads that cross without a junction (naming both
    // and the point).
    static LaneGraph build(const std::vector<RoadInput>& roads, const RoadProfile& profile,
                           const BuildOptions& options = {});

    const std::vector<Lane>& lanes() const { return lanes_; }
    const std::vector<Junction>& junctions() const { return junctions_; }
    const std::vector<std::string>& tagNames() const { return tagNames_; }
    const RoadProfile& profile() const { return profile_; }
    // The tag's index, or -1 when no lane has it.
    int tagIndex(const std::string& name) const;

    // The point of `lane` at `distance` along it (clamped to the lane).
    LaneLocation locationAt(int lane, double distance) const;
    // `location` moved `advance` metres along its lane (negative: backwards), stopping at the lane's ends.
    LaneLocation advanced(const LaneLocation& location, double advance) const;

    // The nearest point on a lane to `point` within `maxDistance` metres (3-D distance to the lane's centre
    // line), among lanes whose tag is `tag` (-1: any) and, given a heading, on segments that run within 90
    // degrees of it on the ground (a car finds its own side of the road). None when there is none that near.
    std::optional<LaneLocation> nearest(const Eigen::Vector3d& point, double maxDistance, int tag = -1,
                                        const Eigen::Vector3d* heading = nullptr) const;
    // The same by scanning every segment of every lane: the reference the grid is tested and measured
    // against.
    std::optional<LaneLocation> nearestByScan(const Eigen::Vector3d& point, double maxDistance, int tag = -1,
                                              const Eigen::Vector3d* heading = nullptr) const;

  private:
    void index();
    LaneLocation locationOnSegment(int lane, int segment, const Eigen::Vector3d& point) const;
    double squaredDistanceToSegment(int lane, int segment, const Eigen::Vector3d& point) const;
    // Whether the segment runs within 90 degrees of `heading` (always, for no heading).
    bool runsAlong(int lane, int segment, const Eigen::Vector3d* heading) const;

    std::vector<Lane> lanes_;
    std::vector<Junction> junctions_;
    std::vector<std::string> tagNames_;
    RoadProfile profile_;
    // The grid: each cell (of cellSize_ metres, on X and Y) lists the (lane, segment) pairs whose bounding
    // boxes overlap it.
    double cellSize_ = 8.0;
    std::unordered_map<uint64_t, std::vector<std::array<int, 2>>> cells_;
    Eigen::Vector2i minCell_ = Eigen::Vector2i::Zero(), maxCell_ = Eigen::Vector2i::Zero();
};

} // namespace sp::zonegraph
