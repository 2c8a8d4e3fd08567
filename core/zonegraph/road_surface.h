#pragma once
// The visible road: triangles over a lane graph's lanes and junctions, and its lane markings, for a renderer
// to draw. Each road lane is a strip of its width along its centre line; each junction's corners are the
// sidewalk connectors between neighbouring roads, and its road the patch from the driving lanes' ends to the
// corners' inner edges (sidewalks stand 5 mm above the road, as a curb); markings are strips 12 cm wide, a
// few centimetres above the surface, on the lines between a piece's lanes: dashed (3 m on, 6 m off) between
// driving lanes (a centre line where they run opposite ways), solid between a driving lane and any other. A
// lane tagged "Sidewalk" is sidewalk, any other is road. World coordinates; every normal is +Z. Pure logic.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/zonegraph/lane_graph.h"

namespace sp::zonegraph {

struct SurfaceMesh {
    std::vector<Eigen::Vector3f> positions;
    std::vector<uint32_t> indices; // triangles, counter-clockwise seen from above
    bool empty() const { return indices.empty(); }
};

struct RoadSurface {
    SurfaceMesh road, sidewalk, markings;
};

struct SurfaceOptions {
    double lift = 0.02;        // the surface above the lanes' centre lines (over a ground at their height)
    double markingLift = 0.03; // the markings above the lanes' centre lines
    double markingWidth = 0.12;
    double dash = 3.0, gap = 6.0;
};

RoadSurface buildRoadSurface(const LaneGraph& graph, const SurfaceOptions& options = {});

} // namespace sp::zonegraph
