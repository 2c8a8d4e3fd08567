#pragma once
// Where procedural generation puts things: pure placement rules, deterministic for a random generator's
// state, with no engine objects (UPCGComponent in core/procedural/pcg_component.h spawns the actors). Metres,
// Z up; areas are horizontal rectangles.

#include <random>
#include <vector>

#include <Eigen/Geometry>

namespace sp::procedural::pcg {

// One thing to place: where its base sits, which way it faces, its size, and which of the caller's
// variants (materials) it takes.
struct Placement {
    Eigen::Vector3d location;
    double yawDegrees = 0.0;
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    int variant = 0;
};

using Polyline = std::vector<Eigen::Vector3d>;

struct ScatterRules {
    double spacing = 2.0;  // no two placements closer than this (horizontally)
    int maxCount = 100;    // at most this many
    double minScale = 1.0; // uniform scale drawn from [minScale, maxScale]
    double maxScale = 1.0;
    bool randomYaw = true;
    int variants = 1; // variant drawn uniformly from [0, variants)
};

// Up to maxCount points in `area` at least `spacing` apart, outside every exclusion rectangle (dart
// throwing: candidates uniform over the area, kept when they fit; it stops after maxCount kept or 30 misses
// per point asked for). z = 0.
std::vector<Placement> scatter(const Eigen::AlignedBox2d& area, const ScatterRules& rules,
                               const std::vector<Eigen::AlignedBox2d>& exclusions, std::mt19937_64& rng);

struct SplineRules {
    double spacing = 2.0;   // between placements, measured along the curve
    double offset = 0.0;    // sideways from the curve (positive: to its left)
    bool bothSides = false; // mirror each placement to the other side
    bool align = true;      // face along the curve (else the yaw is drawn when randomYaw)
    bool randomYaw = false;
    double minScale = 1.0, maxScale = 1.0;
    int variants = 1;
};

// Placements every `spacing` metres along the polyline (a finely sampled curve), starting at its start.
std::vector<Placement> alongPolyline(const Polyline& curve, const SplineRules& rules, std::mt19937_64& rng);

struct CityRules {
    double blockSize = 24.0;  // side of a square block of lots
    double streetWidth = 8.0; // between blocks
    int lotsPerSide = 2;      // a block holds lotsPerSide^2 buildings
    double minHeight = 6.0, maxHeight = 30.0;
    double roadWidth = 8.0; // buildings keep half of it from every road
    int variants = 1;
};

// A grid of blocks filling `area` (from its minimum corner), each lot a building: its footprint 80 % of
// the lot, its height drawn from [minHeight, maxHeight]; lots within roadWidth / 2 of a road are left
// empty. scale = (footprint x, footprint y, height), location = the footprint's centre at z = 0.
std::vector<Placement> cityBlocks(const Eigen::AlignedBox2d& area, const CityRules& rules,
                                  const std::vector<Polyline>& roads, std::mt19937_64& rng);

// The horizontal distance from a rectangle to a polyline (0 when they touch).
double distanceToPolyline(const Eigen::AlignedBox2d& rect, const Polyline& line);

} // namespace sp::procedural::pcg
