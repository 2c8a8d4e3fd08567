#pragma once
// What a navigation mesh is built for: the agent it serves and the resolution it is built at. Metres and
// degrees, Z up.

#include <string_view>

namespace sp::navigation {

struct NavMeshSettings {
    double agentRadius = 0.35;     // clearance kept from walls and edges
    double agentHeight = 1.8;      // headroom needed under ceilings
    double maxSlopeDegrees = 45.0; // steepest walkable ground
    double maxStepHeight = 0.35;   // highest ledge walked up or down
    double cellSize = 0.1;         // horizontal resolution of the voxelisation
    double cellHeight = 0.05;      // vertical resolution
    double tileSize = 12.8;        // side of a tile (rebuilt as a unit when geometry changes)
    double minRegionArea = 0.5;    // islands smaller than this (square metres) are dropped

    bool operator==(const NavMeshSettings&) const = default;
};

// Throws sp::InvalidArgument naming `function`, the field and its value when a setting is out of range
// (sizes > 0 and finite, slope in (0, 90), radius and step >= 0, a tile at least 8 cells wide).
void validate(const NavMeshSettings& settings, std::string_view function);

} // namespace sp::navigation
