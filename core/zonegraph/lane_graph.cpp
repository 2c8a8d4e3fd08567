#include "core/zonegraph/lane_graph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>

#include <Eigen/Geometry>

#include "core/base/error.h"
#include "core/zonegraph/polyline.h"

namespace sp::zonegraph {

namespace {

// Centre-line points closer than this to the line through their neighbours add nothing (metres).
constexpr double kSimplifyTolerance = 0.0005;

// A road's centre line with its arc lengths.
struct Polyline {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> s; // arc length at each point
    bool closed = false;

    double length() const { return s.back(); }

    // The point at arc length `at` (wrapping around a closed line, clamped on an open one).
    Eigen::Vector3d at(double at) const {
        if (closed)
            at = std::fmod(std::fmod(at, length()) + length(), length());
        return pointAtArcLength(points, s, at);
    }

    // The horizontal unit direction of the line at arc length `at`.
    Eigen::Vector3d direction(double at) const {
        const double step = std::min(0.05, 0.25 * length());
        Eigen::Vector3d d = this->at(closed ? at + step : std::min(at + step, length())) -
                            this->at(closed ? at - step : std::max(at - step, 0.0));
        d.z() = 0.0;
        return d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitX();
    }

    // The arc length of the point of the line nearest `p`, and the distance to it.
    std::pair<double, double> project(const Eigen::Vector3d& p) const {
        double bestS = 0.0, best = std::numeric_limits<double>::infinity();
        for (size_t i = 1; i < points.size(); ++i) {
            const double t = nearestOnSegment(points[i - 1], points[i], p);
            const double d = (points[i - 1] + t * (points[i] - points[i - 1]) - p).norm();
            if (d < best) {
                best = d;
                bestS = s[i - 1] + t * (s[i] - s[i - 1]);
            }
        }
        return {bestS, best};
    }
};

// The points of `points` that a line through them needs to stay within `tolerance` of them all
// (Douglas-Peucker): a spline sampled every half metre along a straight street is two points again, and its
// lanes one segment each.
std::vector<Eigen::Vector3d> simplified(const std::vector<Eigen::Vector3d>& points, double tolerance) {
    if (points.size() <= 2)
        return points;
    std::vector<bool> keep(points.size(), false);
    keep.front() = keep.back() = true;
    std::vector<std::pair<size_t, size_t>> spans{{0, points.size() - 1}};
    while (!spans.empty()) {
        const auto [first, last] = spans.back();
        spans.pop_back();
        const Eigen::Vector3d &a = points[first], &b = points[last];
        double farthest = 0.0;
        size_t at = first;
        for (size_t i = first + 1; i < last; ++i) {
            if (const double d = (a + nearestOnSegment(a, b, points[i]) * (b - a) - points[i]).norm();
                d > farthest) {
                farthest = d;
                at = i;
            }
        }
        if (farthest > tolerance) {
            keep[at] = true;
            spans.push_back({first, at});
            spans.push_back({at, last});
        }
    }
    std::vector<Eigen::Vector3d> kept;
    for (size_t i = 0; i < points.size(); ++i)
        if (keep[i])
            kept.push_back(points[i]);
    return kept;
}

Polyline polylineOf(const RoadInput& road) {
    SP_CHECK(!road.name.empty(), InvalidArgument, "LaneGraph::build(): a road has no name");
    Polyline line;
    for (const Eigen::Vector3d& p : road.points) {
        SP_CHECK(p.allFinite(), InvalidArgument, "LaneGraph::build(): road '", road.name,
                 "' has a point that is not finite");
        if (line.points.empty() || (p - line.points.back()).norm() > 1e-9)
            line.points.push_back(p);
    }
    SP_CHECK(line.points.size() >= 2, InvalidArgument, "LaneGraph::build(): road '", road.name,
             "' needs at least two distinct points, got ", line.points.size());
    line.closed = line.points.size() >= 4 && (line.points.front() - line.points.back()).norm() < 1e-6;
    if (line.closed)
        line.points.back() = line.points.front();
    line.points = simplified(line.points, kSimplifyTolerance);
    line.s = arcLengths(line.points);
    return line;
}

// Where two segments cross in the XY plane: the parameter along the first, or none (parallel ones never do).
std::optional<double> crossing(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                               const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
    const Eigen::Vector2d r = (a1 - a0).head<2>(), q = (b1 - b0).head<2>(), w = (b0 - a0).head<2>();
    const double denominator = r.x() * q.y() - r.y() * q.x();
    if (std::abs(denominator) < 1e-12)
        return std::nullopt;
    const double t = (w.x() * q.y() - w.y() * q.x()) / denominator;
    const double u = (w.x() * r.y() - w.y() * r.x()) / denominator;
    if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0)
        return std::nullopt;
    return t;
}

uint64_t cellKey(int x, int y) {
    return (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
}

Eigen::Vector2i cellOf(const Eigen::Vector3d& p, double size) {
    return {int(std::floor(p.x() / size)), int(std::floor(p.y() / size))};
}

// Visits the cells that a segment's XY bounding box overlaps.
template <typename Visit>
void forEachCell(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double size, Visit&& visit) {
    const Eigen::Vector2i lo = cellOf(a.cwiseMin(b), size), hi = cellOf(a.cwiseMax(b), size);
    for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
            visit(x, y);
}

// Where a lane of a road piece starts or ends: a junction, a free road end, or the piece's own other end (a
// closed road with no junction).
struct Node {
    enum Kind { JunctionNode, FreeEnd, Loop } kind = FreeEnd;
    int index = -1; // the junction; for a free end, 2 * piece (its start) or 2 * piece + 1 (its end)
    bool operator<(const Node& o) const { return std::tie(kind, index) < std::tie(o.kind, o.index); }
};

struct Piece {
    int road = -1;
    double from = 0.0, to = 0.0; // arc lengths along the road (to > from; past the length on a closed road)
    Node start, end;
};

std::vector<Eigen::Vector3d> bezier(const Eigen::Vector3d& p0, const Eigen::Vector3d& t0,
                                    const Eigen::Vector3d& p1, const Eigen::Vector3d& t1, int segments) {
    const double handle = std::max((p1 - p0).norm() / 3.0, 0.5);
    const Eigen::Vector3d c0 = p0 + handle * t0, c1 = p1 - handle * t1;
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i <= segments; ++i) {
        const double t = double(i) / segments, u = 1.0 - t;
        points.push_back(u * u * u * p0 + 3.0 * u * u * t * c0 + 3.0 * u * t * t * c1 + t * t * t * p1);
    }
    return points;
}

void measure(Lane& lane) {
    lane.distances = arcLengths(lane.points);
}

struct Meetings {
    std::vector<Junction> junctions;
    std::vector<std::vector<std::pair<double, Node>>> cuts; // per road: (arc length, node)
};

// Where roads meet: each open road's ends, and where they touch another road, joined into places; a place on
// two or more roads is a junction, numbered in the order of its first mark; each road's cuts (arc length,
// node).
Meetings findMeetings(const std::vector<Polyline>& lines, double tolerance) {
    Meetings found;
    struct Mark {
        int road;
        double s;
        Eigen::Vector3d p;
    };
    std::vector<Mark> marks;
    for (int r = 0; r < int(lines.size()); ++r) {
        if (lines[r].closed)
            continue;
        for (const double end : {0.0, lines[r].length()}) {
            const Eigen::Vector3d p = lines[r].at(end);
            marks.push_back({r, end, p});
            for (int q = 0; q < int(lines.size()); ++q)
                if (q != r)
                    if (const auto [s, d] = lines[q].project(p); d <= tolerance)
                        marks.push_back({q, s, lines[q].at(s)});
        }
    }
    // Marks within twice the tolerance of each other are one place (joined through a grid of that size).
    std::vector<int> place(marks.size());
    std::iota(place.begin(), place.end(), 0);
    const auto find = [&](int i) {
        while (place[i] != i)
            i = place[i] = place[place[i]];
        return i;
    };
    const double joinDistance = 2.0 * tolerance;
    std::unordered_map<uint64_t, std::vector<int>> markCells;
    for (int i = 0; i < int(marks.size()); ++i) {
        const Eigen::Vector2i cell = cellOf(marks[i].p, joinDistance);
        for (int x = cell.x() - 1; x <= cell.x() + 1; ++x)
            for (int y = cell.y() - 1; y <= cell.y() + 1; ++y)
                if (const auto found = markCells.find(cellKey(x, y)); found != markCells.end())
                    for (const int j : found->second)
                        if ((marks[i].p - marks[j].p).norm() <= joinDistance)
                            place[find(i)] = find(j);
        markCells[cellKey(cell.x(), cell.y())].push_back(i);
    }

    // A place where two or more roads meet is a junction (numbered in the order of their first marks); a
    // place on one road only is that road's free end.
    std::map<int, std::vector<int>> marksOfPlace;
    for (int i = 0; i < int(marks.size()); ++i)
        marksOfPlace[find(i)].push_back(i);
    std::vector<std::vector<int>> placesInOrder;
    for (auto& [root, members] : marksOfPlace)
        placesInOrder.push_back(std::move(members));
    std::sort(placesInOrder.begin(), placesInOrder.end());
    found.cuts.resize(lines.size());
    for (const std::vector<int>& members : placesInOrder) {
        std::vector<int> roadsHere;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (const int j : members) {
            roadsHere.push_back(marks[j].road);
            sum += marks[j].p;
        }
        std::sort(roadsHere.begin(), roadsHere.end());
        roadsHere.erase(std::unique(roadsHere.begin(), roadsHere.end()), roadsHere.end());
        Node node;
        if (roadsHere.size() >= 2) {
            node = {Node::JunctionNode, int(found.junctions.size())};
            found.junctions.push_back({sum / double(members.size()), roadsHere});
        }
        for (const int j : members)
            found.cuts[marks[j].road].push_back({marks[j].s, node});
    }

    return found;
}

// Throws InvalidArgument naming both roads and the point where two roads cross away from any junction of
// them.
void checkCrossings(const std::vector<Polyline>& lines, const std::vector<RoadInput>& roads,
                    const std::vector<Junction>& junctions, double tolerance) {
    constexpr double kCell = 8.0;
    std::unordered_map<uint64_t, std::vector<std::array<int, 2>>> roadCells;
    for (int r = 0; r < int(lines.size()); ++r)
        for (int i = 1; i < int(lines[r].points.size()); ++i)
            forEachCell(lines[r].points[i - 1], lines[r].points[i], kCell, [&](int x, int y) {
                roadCells[cellKey(x, y)].push_back({r, i});
            });
    for (int r = 0; r < int(lines.size()); ++r)
        for (int i = 1; i < int(lines[r].points.size()); ++i) {
            const Eigen::Vector3d &a0 = lines[r].points[i - 1], &a1 = lines[r].points[i];
            forEachCell(a0, a1, kCell, [&](int x, int y) {
                for (const auto& [q, j] : roadCells[cellKey(x, y)]) {
                    if (q <= r)
                        continue;
                    const auto t = crossing(a0, a1, lines[q].points[j - 1], lines[q].points[j]);
                    if (!t)
                        continue;
                    const Eigen::Vector3d at = a0 + *t * (a1 - a0);
                    const bool atJunction =
                        std::any_of(junctions.begin(), junctions.end(), [&](const Junction& junction) {
                            return (junction.position - at).head<2>().norm() <= 3.0 * tolerance &&
                                   std::count(junction.roads.begin(), junction.roads.end(), r) &&
                                   std::count(junction.roads.begin(), junction.roads.end(), q);
                        });
                    SP_CHECK(atJunction, InvalidArgument, "LaneGraph::build(): road '", roads[r].name,
                             "' crosses road '", roads[q].name, "' at (", at.x(), ", ", at.y(), ", ", at.z(),
                             ") without a junction: end one of them there, or split it there into two roads");
                }
            });
        }
}

// Each road cut at its junctions into pieces (a cut within the tolerance of another is the same cut).
std::vector<Piece> cutIntoPieces(const std::vector<Polyline>& lines,
                                 std::vector<std::vector<std::pair<double, Node>>> cuts, double tolerance) {
    std::vector<Piece> pieces;
    for (int r = 0; r < int(lines.size()); ++r) {
        auto& list = cuts[r];
        std::stable_sort(list.begin(), list.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        std::vector<std::pair<double, Node>> merged;
        for (const auto& cut : list) {
            if (!merged.empty() && cut.first - merged.back().first <= 2.0 * tolerance) {
                if (cut.second.kind == Node::JunctionNode)
                    merged.back().second = cut.second;
                continue;
            }
            merged.push_back(cut);
        }
        const Polyline& line = lines[r];
        if (line.closed) {
            if (merged.empty()) {
                const int self = int(pieces.size());
                pieces.push_back({r, 0.0, line.length(), {Node::Loop, self}, {Node::Loop, self}});
                continue;
            }
            for (size_t k = 0; k < merged.size(); ++k) {
                const double to =
                    k + 1 < merged.size() ? merged[k + 1].first : merged[0].first + line.length();
                pieces.push_back(
                    {r, merged[k].first, to, merged[k].second, merged[(k + 1) % merged.size()].second});
            }
            continue;
        }
        // An open road: its ends are cuts too (free ends unless a junction took them).
        if (merged.empty() || merged.front().first > 2.0 * tolerance)
            merged.insert(merged.begin(), {0.0, Node{}});
        merged.front().first = 0.0;
        if (merged.back().first < line.length() - 2.0 * tolerance)
            merged.push_back({line.length(), Node{}});
        merged.back().first = line.length();
        for (size_t k = 0; k + 1 < merged.size(); ++k)
            pieces.push_back(
                {r, merged[k].first, merged[k + 1].first, merged[k].second, merged[k + 1].second});
    }
    for (int p = 0; p < int(pieces.size()); ++p) { // each free end its own node: 2p its start, 2p + 1 its end
        if (pieces[p].start.kind == Node::FreeEnd)
            pieces[p].start.index = 2 * p;
        if (pieces[p].end.kind == Node::FreeEnd)
            pieces[p].end.index = 2 * p + 1;
    }

    return pieces;
}

} // namespace

double RoadProfile::totalWidth() const {
    double total = 0.0;
    for (const LaneDesc& lane : lanes)
        total += lane.width;
    return total;
}

RoadProfile RoadProfile::twoWayStreet() {
    return {
        {{"Sidewalk", 2.0, true}, {"Driving", 3.5, true}, {"Driving", 3.5, false}, {"Sidewalk", 2.0, false}}};
}

int LaneGraph::tagIndex(const std::string& name) const {
    const auto found = std::find(tagNames_.begin(), tagNames_.end(), name);
    return found == tagNames_.end() ? -1 : int(found - tagNames_.begin());
}

LaneGraph LaneGraph::build(const std::vector<RoadInput>& roads, const RoadProfile& profile,
                           const BuildOptions& options) {
    SP_CHECK(!profile.lanes.empty(), InvalidArgument, "LaneGraph::build(): the road profile has no lanes");
    for (const LaneDesc& lane : profile.lanes) {
        SP_CHECK(std::isfinite(lane.width) && lane.width > 0.0, InvalidArgument,
                 "LaneGraph::build(): a lane's width must be > 0, got ", lane.width);
        SP_CHECK(!lane.tag.empty(), InvalidArgument, "LaneGraph::build(): a lane has no tag");
    }
    SP_CHECK(std::isfinite(options.junctionTolerance) && options.junctionTolerance > 0.0, InvalidArgument,
             "LaneGraph::build(): junctionTolerance must be > 0, got ", options.junctionTolerance);
    std::vector<Polyline> lines;
    for (const RoadInput& road : roads)
        lines.push_back(polylineOf(road));
    const double tolerance = options.junctionTolerance;

    Meetings meetings = findMeetings(lines, tolerance);
    checkCrossings(lines, roads, meetings.junctions, tolerance);
    const std::vector<Piece> pieces = cutIntoPieces(lines, std::move(meetings.cuts), tolerance);

    LaneGraph graph;
    graph.profile_ = profile;
    graph.junctions_ = std::move(meetings.junctions);

    // Tags in profile order.
    for (const LaneDesc& desc : profile.lanes)
        if (graph.tagIndex(desc.tag) < 0)
            graph.tagNames_.push_back(desc.tag);

    // Lanes along each piece, stopping short of junctions.
    const double total = profile.totalWidth();
    struct Ends {
        Node start, end;
        int piece;
    };
    std::vector<Ends> ends;
    for (int p = 0; p < int(pieces.size()); ++p) {
        const Piece& piece = pieces[p];
        const Polyline& line = lines[piece.road];
        const double length = piece.to - piece.from;
        const double trim = std::min(0.5 * total + options.cornerRadius, 0.4 * length);
        const double from = piece.from + (piece.start.kind == Node::JunctionNode ? trim : 0.0);
        const double to = piece.to - (piece.end.kind == Node::JunctionNode ? trim : 0.0);
        // The centre line's arc lengths: the ends and every vertex between them.
        std::vector<double> at{from};
        for (int lap = 0; lap < (line.closed ? 2 : 1); ++lap)
            for (const double s : line.s)
                if (s + lap * line.length() > from + 1e-9 && s + lap * line.length() < to - 1e-9)
                    at.push_back(s + lap * line.length());
        std::sort(at.begin() + 1, at.end());
        at.push_back(to);
        const int first = int(graph.lanes_.size());
        double rightEdge = -0.5 * total; // lanes from the right edge leftwards
        for (const LaneDesc& desc : profile.lanes) {
            const double offset = -(rightEdge + 0.5 * desc.width); // to the right of the centre line
            rightEdge += desc.width;
            Lane lane;
            lane.width = desc.width;
            lane.tag = graph.tagIndex(desc.tag);
            lane.road = piece.road;
            lane.piece = p;
            lane.slot = int(&desc - profile.lanes.data());
            for (const double s : at) {
                const Eigen::Vector3d right = line.direction(s).cross(Eigen::Vector3d::UnitZ());
                lane.points.push_back(line.at(s) + offset * right);
            }
            if (!desc.forward)
                std::reverse(lane.points.begin(), lane.points.end());
            measure(lane);
            graph.lanes_.push_back(std::move(lane));
            ends.push_back(desc.forward ? Ends{piece.start, piece.end, p} : Ends{piece.end, piece.start, p});
        }
        // Neighbours running the same way: a forward lane's right is the profile's previous lane, a backward
        // lane's right the next one.
        for (int k = 0; k < int(profile.lanes.size()); ++k) {
            const bool forward = profile.lanes[k].forward;
            Lane& lane = graph.lanes_[first + k];
            const int before = k - 1, after = k + 1;
            const auto same = [&](int j) {
                return j >= 0 && j < int(profile.lanes.size()) && profile.lanes[j].forward == forward;
            };
            if (same(before))
                (forward ? lane.right : lane.left) = first + before;
            if (same(after))
                (forward ? lane.left : lane.right) = first + after;
        }
    }

    // Links: through junctions and U-turns by connector lanes, round closed roads directly.
    const auto link = [&](int from, int to) {
        graph.lanes_[from].next.push_back(to);
        graph.lanes_[to].prev.push_back(from);
    };
    const auto connect = [&](int from, int to, int junction) {
        const Lane &a = graph.lanes_[from], &b = graph.lanes_[to];
        const Eigen::Vector3d p0 = a.points.back(), p1 = b.points.front();
        const Eigen::Vector3d t0 = (a.points.back() - a.points[a.points.size() - 2]).normalized();
        const Eigen::Vector3d t1 = (b.points[1] - b.points.front()).normalized();
        Lane connector;
        connector.width = a.width;
        connector.tag = a.tag;
        connector.junction = junction;
        connector.points = bezier(p0, t0, p1, t1, std::max(options.connectorSegments, 1));
        measure(connector);
        const int index = int(graph.lanes_.size());
        graph.lanes_.push_back(std::move(connector));
        link(from, index);
        link(index, to);
    };
    const int roadLanes = int(ends.size());
    std::map<Node, std::vector<int>> arriving, leaving;
    for (int l = 0; l < roadLanes; ++l) {
        arriving[ends[l].end].push_back(l);
        leaving[ends[l].start].push_back(l);
    }
    for (const auto& [node, into] : arriving)
        for (const int a : into)
            for (const int b : leaving[node]) {
                if (graph.lanes_[a].tag != graph.lanes_[b].tag)
                    continue;
                if (node.kind == Node::Loop) {
                    if (a == b)
                        link(a, a);
                } else if (node.kind == Node::FreeEnd) {
                    connect(a, b, -1); // a U-turn onto the same piece
                } else if (ends[a].piece != ends[b].piece) {
                    connect(a, b, node.index);
                }
            }
    graph.index();
    return graph;
}

void LaneGraph::index() {
    cells_.clear();
    minCell_ = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
    maxCell_ = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
    for (int l = 0; l < int(lanes_.size()); ++l)
        for (int i = 1; i < int(lanes_[l].points.size()); ++i)
            forEachCell(lanes_[l].points[i - 1], lanes_[l].points[i], cellSize_, [&](int x, int y) {
                cells_[cellKey(x, y)].push_back({l, i});
                minCell_ = minCell_.cwiseMin(Eigen::Vector2i(x, y));
                maxCell_ = maxCell_.cwiseMax(Eigen::Vector2i(x, y));
            });
}

LaneLocation LaneGraph::locationOnSegment(int lane, int segment, const Eigen::Vector3d& point) const {
    const Lane& l = lanes_[lane];
    const Eigen::Vector3d &a = l.points[segment - 1], &b = l.points[segment];
    const Eigen::Vector3d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = nearestOnSegment(a, b, point);
    LaneLocation location;
    location.lane = lane;
    location.distance = l.distances[segment - 1] + t * (l.distances[segment] - l.distances[segment - 1]);
    location.position = a + t * ab;
    location.direction = len2 > 0.0 ? Eigen::Vector3d(ab.normalized()) : Eigen::Vector3d::UnitX();
    return location;
}

LaneLocation LaneGraph::locationAt(int lane, double distance) const {
    SP_CHECK(lane >= 0 && lane < int(lanes_.size()), InvalidArgument, "LaneGraph::locationAt(): lane ", lane,
             " is not one of the ", lanes_.size(), " lanes");
    const Lane& l = lanes_[lane];
    distance = std::clamp(std::isfinite(distance) ? distance : 0.0, 0.0, l.length());
    const int segment = std::clamp(
        int(std::upper_bound(l.distances.begin(), l.distances.end(), distance) - l.distances.begin()), 1,
        int(l.points.size()) - 1);
    const double span = l.distances[segment] - l.distances[segment - 1];
    const double t = span > 0.0 ? (distance - l.distances[segment - 1]) / span : 0.0;
    LaneLocation location;
    location.lane = lane;
    location.distance = distance;
    location.position = l.points[segment - 1] + t * (l.points[segment] - l.points[segment - 1]);
    const Eigen::Vector3d d = l.points[segment] - l.points[segment - 1];
    location.direction = d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitX();
    return location;
}

LaneLocation LaneGraph::advanced(const LaneLocation& location, double advance) const {
    SP_CHECK(std::isfinite(advance), InvalidArgument, "LaneGraph::advanced(): the distance is ", advance);
    return locationAt(location.lane, location.distance + advance);
}

double LaneGraph::squaredDistanceToSegment(int lane, int segment, const Eigen::Vector3d& point) const {
    const Lane& l = lanes_[lane];
    const Eigen::Vector3d &a = l.points[segment - 1], &b = l.points[segment];
    return (a + nearestOnSegment(a, b, point) * (b - a) - point).squaredNorm();
}

bool LaneGraph::runsAlong(int lane, int segment, const Eigen::Vector3d* heading) const {
    if (!heading)
        return true;
    const Lane& l = lanes_[lane];
    return (l.points[segment] - l.points[segment - 1]).head<2>().dot(heading->head<2>()) > 0.0;
}

std::optional<LaneLocation> LaneGraph::nearestByScan(const Eigen::Vector3d& point, double maxDistance,
                                                     int tag, const Eigen::Vector3d* heading) const {
    // Squared distances: the nearest is chosen on them, and the location made once for it.
    double best = maxDistance * maxDistance;
    std::array<int, 2> bestId{-1, -1};
    for (int l = 0; l < int(lanes_.size()); ++l) {
        if (tag >= 0 && lanes_[l].tag != tag)
            continue;
        for (int i = 1; i < int(lanes_[l].points.size()); ++i)
            if (const double d2 = squaredDistanceToSegment(l, i, point);
                (d2 < best || (bestId[0] < 0 && d2 <= best)) && runsAlong(l, i, heading)) {
                best = d2;
                bestId = {l, i};
            }
    }
    if (bestId[0] < 0)
        return std::nullopt;
    return locationOnSegment(bestId[0], bestId[1], point);
}

std::optional<LaneLocation> LaneGraph::nearest(const Eigen::Vector3d& point, double maxDistance, int tag,
                                               const Eigen::Vector3d* heading) const {
    if (cells_.empty() || !point.allFinite() || std::isnan(maxDistance))
        return std::nullopt;
    double best = maxDistance * maxDistance;
    std::array<int, 2> bestId{-1, -1};
    const Eigen::Vector2i centre = cellOf(point, cellSize_);
    // How far the point is from its own cell's nearest side: a cell r rings out is at least that plus r - 1
    // cells away, so the search stops once that is farther than the best so far (or than maxDistance), or
    // once it is past the grid.
    const Eigen::Vector2d inCell = point.head<2>() - centre.cast<double>() * cellSize_;
    const double margin = std::min({inCell.x(), inCell.y(), cellSize_ - inCell.x(), cellSize_ - inCell.y()});
    const int reach =
        std::max((maxCell_ - centre).cwiseAbs().maxCoeff(), (minCell_ - centre).cwiseAbs().maxCoeff());
    for (int ring = 0; ring <= reach; ++ring) {
        if (ring >= 1) {
            const double gap = margin + (ring - 1) * cellSize_;
            if (gap * gap > best)
                break;
        }
        for (int x = centre.x() - ring; x <= centre.x() + ring; ++x) {
            // Inside the ring only its first and last rows: the rest was seen at smaller rings.
            const int step = x == centre.x() - ring || x == centre.x() + ring ? 1 : std::max(2 * ring, 1);
            for (int y = centre.y() - ring; y <= centre.y() + ring; y += step) {
                const auto cell = cells_.find(cellKey(x, y));
                if (cell == cells_.end())
                    continue;
                for (const auto& id : cell->second) {
                    if ((tag >= 0 && lanes_[id[0]].tag != tag) || !runsAlong(id[0], id[1], heading))
                        continue;
                    const double d2 = squaredDistanceToSegment(id[0], id[1], point);
                    // Ties go to the first lane and segment, as the scan has it.
                    if (d2 < best || (d2 == best && (bestId[0] < 0 || id < bestId))) {
                        best = d2;
                        bestId = id;
                    }
                }
            }
        }
    }
    if (bestId[0] < 0)
        return std::nullopt;
    return locationOnSegment(bestId[0], bestId[1], point);
}

} // namespace sp::zonegraph
