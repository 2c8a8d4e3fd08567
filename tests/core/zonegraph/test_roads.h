#pragma once
// Roads the zonegraph tests build lanes on: straight ones, a circle, four roads meeting at the origin, and a
// city's street grid.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/zonegraph/lane_graph.h"

namespace sp::zonegraph::test {

// A straight road from a to b, sampled at `points` points.
inline RoadInput straight(const std::string& name, Eigen::Vector3d a, Eigen::Vector3d b, int points = 2) {
    RoadInput road{name, {}};
    for (int i = 0; i < points; ++i)
        road.points.push_back(a + (b - a) * (double(i) / (points - 1)));
    return road;
}

// A closed road round the origin, counter-clockwise from +X.
inline RoadInput circle(const std::string& name, double radius, int points) {
    RoadInput road{name, {}};
    for (int i = 0; i <= points; ++i) {
        const double a = 2.0 * std::numbers::pi * (i % points) / points;
        road.points.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
    }
    return road;
}

// Four roads `length` metres long leaving the origin east, north, west and south: a four-way junction.
inline std::vector<RoadInput> fourWay(double length) {
    return {straight("East", {0, 0, 0}, {length, 0, 0}), straight("North", {0, 0, 0}, {0, length, 0}),
            straight("West", {0, 0, 0}, {-length, 0, 0}), straight("South", {0, 0, 0}, {0, -length, 0})};
}

// The street grid of a city: every street between two neighbouring intersections is its own road.
inline std::vector<RoadInput> grid(int blocks, double block) {
    std::vector<RoadInput> roads;
    for (int i = 0; i <= blocks; ++i)
        for (int j = 0; j < blocks; ++j) {
            roads.push_back(straight("x" + std::to_string(i) + "_" + std::to_string(j),
                                     {j * block, i * block, 0.0}, {(j + 1) * block, i * block, 0.0}, 5));
            roads.push_back(straight("y" + std::to_string(i) + "_" + std::to_string(j),
                                     {i * block, j * block, 0.0}, {i * block, (j + 1) * block, 0.0}, 5));
        }
    return roads;
}

} // namespace sp::zonegraph::test
