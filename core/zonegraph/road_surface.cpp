#include "core/zonegraph/road_surface.h"

#include "core/zonegraph/polyline.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace sp::zonegraph {

namespace {

// The horizontal unit normal to the left of the polyline at each of its points (the mean of the segments'
// there).
std::vector<Eigen::Vector3d> leftNormals(const std::vector<Eigen::Vector3d>& points) {
    std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::UnitY());
    for (size_t i = 0; i < points.size(); ++i) {
        Eigen::Vector3d d = points[std::min(i + 1, points.size() - 1)] - points[i > 0 ? i - 1 : 0];
        d.z() = 0.0;
        if (d.norm() > 0.0)
            normals[i] = Eigen::Vector3d(-d.y(), d.x(), 0.0).normalized();
    }
    return normals;
}

// A strip of `width` along `points` (at least two), `lift` above them.
void addStrip(SurfaceMesh& mesh, const std::vector<Eigen::Vector3d>& points, double width, double lift) {
    if (points.size() < 2)
        return;
    const std::vector<Eigen::Vector3d> left = leftNormals(points);
    const uint32_t first = uint32_t(mesh.positions.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector3d p = points[i] + Eigen::Vector3d(0.0, 0.0, lift);
        mesh.positions.push_back((p - 0.5 * width * left[i]).cast<float>()); // right edge
        mesh.positions.push_back((p + 0.5 * width * left[i]).cast<float>()); // left edge
    }
    for (uint32_t i = 0; i + 1 < uint32_t(points.size()); ++i) {
        const uint32_t r0 = first + 2 * i, l0 = r0 + 1, r1 = r0 + 2, l1 = r0 + 3;
        mesh.indices.insert(mesh.indices.end(), {r0, r1, l1, r0, l1, l0});
    }
}

// The part of a polyline between arc lengths a and b.
std::vector<Eigen::Vector3d> between(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& s,
                                     double a, double b) {
    const auto at = [&](double d) { return pointAtArcLength(points, s, d); };
    std::vector<Eigen::Vector3d> part{at(a)};
    for (size_t i = 0; i < points.size(); ++i)
        if (s[i] > a && s[i] < b)
            part.push_back(points[i]);
    part.push_back(at(b));
    return part;
}

void addLine(SurfaceMesh& mesh, const std::vector<Eigen::Vector3d>& line, bool dashed,
             const SurfaceOptions& options) {
    if (!dashed) {
        addStrip(mesh, line, options.markingWidth, options.markingLift);
        return;
    }
    const std::vector<double> s = arcLengths(line);
    // Dashes centred on the line's length, so a piece's two ends look alike.
    const double period = options.dash + options.gap;
    const double start = std::fmod(std::fmod(0.5 * s.back() - 0.5 * options.dash, period) + period, period);
    for (double a = start - period; a < s.back(); a += period) {
        const double from = std::max(a, 0.0), to = std::min(a + options.dash, s.back());
        if (to - from > 0.1)
            addStrip(mesh, between(line, s, from, to), options.markingWidth, options.markingLift);
    }
}

// The bearing of p seen from a junction's centre, radians counter-clockwise from +X.
double bearingFrom(const Eigen::Vector3d& centre, const Eigen::Vector3d& p) {
    return std::atan2(p.y() - centre.y(), p.x() - centre.x());
}

// A junction's corner sidewalks: the sidewalk connectors between neighbouring roads, round the block
// between them. Around a junction a lane arriving on a road's right edge has the next road counter-clockwise
// on its right (the corner it walks round); a sidewalk connector to any other road crosses a road.
std::vector<int> cornerSidewalks(const LaneGraph& graph, const std::vector<int>& connectors,
                                 const Eigen::Vector3d& centre) {
    // Each piece's bearing from the centre, from its lanes' ends there.
    std::map<int, Eigen::Vector3d> ends;
    for (const int l : connectors) {
        const Lane& lane = graph.lanes()[size_t(l)];
        if (lane.prev.size() != 1 || lane.next.size() != 1)
            continue;
        const Lane &from = graph.lanes()[size_t(lane.prev[0])], &to = graph.lanes()[size_t(lane.next[0])];
        ends.emplace(from.piece, from.points.back());
        ends.emplace(to.piece, to.points.front());
    }
    std::vector<std::pair<double, int>> around;
    for (const auto& [piece, at] : ends)
        around.emplace_back(bearingFrom(centre, at), piece);
    std::sort(around.begin(), around.end());
    std::map<int, int> nextCounterClockwise;
    for (size_t i = 0; i < around.size(); ++i)
        nextCounterClockwise[around[i].second] = around[(i + 1) % around.size()].second;
    std::vector<int> corners;
    for (const int l : connectors) {
        const Lane& lane = graph.lanes()[size_t(l)];
        if (lane.prev.size() == 1 && lane.next.size() == 1 &&
            nextCounterClockwise[graph.lanes()[size_t(lane.prev[0])].piece] ==
                graph.lanes()[size_t(lane.next[0])].piece)
            corners.push_back(l);
    }
    return corners;
}

// Sidewalks stand this much above the road (where a corner's sidewalk meets the junction's patch, the one
// shows above the other rather than both flickering).
constexpr double kCurb = 0.005;

} // namespace

RoadSurface buildRoadSurface(const LaneGraph& graph, const SurfaceOptions& options) {
    RoadSurface surface;
    const int sidewalk = graph.tagIndex("Sidewalk");
    const RoadProfile& profile = graph.profile();
    // Road lanes, and each piece's lanes in profile order for the markings between them.
    std::map<int, std::vector<int>> pieces;
    std::map<int, std::vector<Eigen::Vector3d>> junctionCorners; // each junction's patch boundary
    std::map<int, std::vector<int>> sidewalkTurns;               // each junction's sidewalk connectors
    for (int l = 0; l < int(graph.lanes().size()); ++l) {
        const Lane& lane = graph.lanes()[l];
        if (lane.piece >= 0) {
            addStrip(lane.tag == sidewalk ? surface.sidewalk : surface.road, lane.points, lane.width,
                     options.lift + (lane.tag == sidewalk ? kCurb : 0.0));
            pieces[lane.piece].push_back(l);
        } else if (lane.junction >= 0 && lane.tag == sidewalk) {
            sidewalkTurns[lane.junction].push_back(l);
        } else if (lane.junction >= 0) {
            // A driving connector's ends, edge to edge across the road lanes it joins (their directions: the
            // connector's own sampled ends lean into its turn): the junction's patch holds them all.
            const auto edges = [&](const Eigen::Vector3d& at, const Lane& road, bool atEnd) {
                const size_t n = road.points.size();
                Eigen::Vector3d d = atEnd ? Eigen::Vector3d(road.points[n - 1] - road.points[n - 2])
                                          : Eigen::Vector3d(road.points[1] - road.points[0]);
                d.z() = 0.0;
                const Eigen::Vector3d side = d.norm() > 0.0 ? Eigen::Vector3d(-d.y(), d.x(), 0.0).normalized()
                                                            : Eigen::Vector3d::UnitY();
                junctionCorners[lane.junction].push_back(at + 0.5 * road.width * side);
                junctionCorners[lane.junction].push_back(at - 0.5 * road.width * side);
            };
            if (lane.prev.size() == 1 && lane.next.size() == 1) {
                edges(lane.points.front(), graph.lanes()[size_t(lane.prev[0])], true);
                edges(lane.points.back(), graph.lanes()[size_t(lane.next[0])], false);
            }
        }
    }
    // Each junction's patch: the road between the driving lanes' ends and the corner sidewalks' inner edges,
    // a fan round the junction's centre through them in order of bearing (a junction is star-shaped from its
    // centre: every road and corner faces it).
    for (auto& [junction, boundary] : junctionCorners) {
        const Eigen::Vector3d centre = graph.junctions()[size_t(junction)].position;
        for (const int l : cornerSidewalks(graph, sidewalkTurns[junction], centre)) {
            const Lane& turn = graph.lanes()[size_t(l)];
            addStrip(surface.sidewalk, turn.points, turn.width, options.lift + kCurb);
            // Its inner edge (on its left: the corner turns right round the block) bounds the road.
            const std::vector<Eigen::Vector3d> left = leftNormals(turn.points);
            for (size_t i = 0; i < turn.points.size(); ++i)
                boundary.push_back(turn.points[i] + 0.5 * turn.width * left[i]);
        }
        std::sort(boundary.begin(), boundary.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
            return bearingFrom(centre, a) < bearingFrom(centre, b);
        });
        if (boundary.size() < 3)
            continue;
        const double height = centre.z() + options.lift;
        const uint32_t first = uint32_t(surface.road.positions.size());
        surface.road.positions.emplace_back(float(centre.x()), float(centre.y()), float(height));
        for (const Eigen::Vector3d& p : boundary)
            surface.road.positions.emplace_back(float(p.x()), float(p.y()), float(height));
        const uint32_t count = uint32_t(boundary.size());
        for (uint32_t i = 0; i < count; ++i)
            surface.road.indices.insert(surface.road.indices.end(),
                                        {first, first + 1 + i, first + 1 + (i + 1) % count});
    }
    // Markings on the lines between neighbouring lanes of a piece, in the road's direction.
    for (const auto& [piece, lanes] : pieces) {
        for (size_t k = 0; k + 1 < lanes.size(); ++k) {
            const Lane &a = graph.lanes()[lanes[k]], &b = graph.lanes()[lanes[k + 1]];
            const bool aDriving = a.tag != sidewalk, bDriving = b.tag != sidewalk;
            if (!aDriving && !bDriving)
                continue;
            const bool aForward = profile.lanes[size_t(a.slot)].forward,
                       bForward = profile.lanes[size_t(b.slot)].forward;
            std::vector<Eigen::Vector3d> pa = a.points, pb = b.points;
            if (!aForward)
                std::reverse(pa.begin(), pa.end());
            if (!bForward)
                std::reverse(pb.begin(), pb.end());
            if (pa.size() != pb.size())
                continue;
            // The line between them: their edges meet half a width from each centre line.
            std::vector<Eigen::Vector3d> line(pa.size());
            for (size_t i = 0; i < pa.size(); ++i)
                line[i] = (b.width * pa[i] + a.width * pb[i]) / (a.width + b.width);
            addLine(surface.markings, line, aDriving && bDriving, options);
        }
    }
    return surface;
}

} // namespace sp::zonegraph
