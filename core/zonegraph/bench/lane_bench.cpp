// Lane benchmark: nearest-lane queries per second on a street grid through LaneGraph::nearest (a grid of the
// lanes' segments) against LaneGraph::nearestByScan (every segment of every lane: the brute-force floor), on
// the same random points, and the graph's build time. bench/bench_lanes.py runs it for the scan's rate and
// compares the engine's calls with it. Never run by the tests.
//
//     build/core/zonegraph/spear_zonegraph_bench [--blocks N] [--queries Q]     (defaults: 20, 200000)
//
// A grid of N x N blocks 60 m square is 2N(N + 1) road pieces of the default two-way street (four lanes) and
// the connectors through its junctions: 12,952 lanes at N = 20.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/zonegraph/lane_graph.h"

namespace {

using sp::zonegraph::LaneGraph;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv) {
    int blocks = 20, queries = 200'000;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--blocks"))
            blocks = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--queries"))
            queries = std::atoi(argv[i + 1]);
    }
    if (blocks < 1 || queries < 1) {
        std::fprintf(stderr, "usage: spear_zonegraph_bench [--blocks N >= 1] [--queries Q >= 1]\n");
        return 2;
    }
    constexpr double kBlock = 60.0;
    std::vector<sp::zonegraph::RoadInput> roads;
    for (int i = 0; i <= blocks; ++i)
        for (int j = 0; j < blocks; ++j) {
            roads.push_back({"x" + std::to_string(i) + "_" + std::to_string(j),
                             {{j * kBlock, i * kBlock, 0.0}, {(j + 1) * kBlock, i * kBlock, 0.0}}});
            roads.push_back({"y" + std::to_string(i) + "_" + std::to_string(j),
                             {{i * kBlock, j * kBlock, 0.0}, {i * kBlock, (j + 1) * kBlock, 0.0}}});
        }
    const Clock::time_point built = Clock::now();
    const LaneGraph graph = LaneGraph::build(roads, sp::zonegraph::RoadProfile::twoWayStreet());
    std::printf("grid of %d x %d blocks: %zu roads, %zu lanes, %zu junctions, built in %.3f s\n", blocks,
                blocks, roads.size(), graph.lanes().size(), graph.junctions().size(), secondsSince(built));

    // Points anywhere over the city and a little beyond, at street level, each looking 50 m around it.
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> coordinate(-20.0, blocks * kBlock + 20.0);
    std::vector<Eigen::Vector3d> points(static_cast<size_t>(queries));
    for (Eigen::Vector3d& p : points)
        p = {coordinate(random), coordinate(random), 0.5};
    constexpr double kReach = 50.0;

    Clock::time_point start = Clock::now();
    size_t found = 0;
    for (const Eigen::Vector3d& p : points)
        found += graph.nearest(p, kReach).has_value();
    const double gridRate = queries / secondsSince(start);
    // The scan is slow: it answers a tenth of the points (at least 100).
    const int scanned = std::max(100, queries / 10);
    start = Clock::now();
    size_t agreed = 0;
    for (int i = 0; i < scanned; ++i) {
        const auto byScan = graph.nearestByScan(points[size_t(i)], kReach);
        const auto byGrid = graph.nearest(points[size_t(i)], kReach);
        agreed += byScan.has_value() == byGrid.has_value() && (!byScan || byScan->lane == byGrid->lane);
    }
    // The scan's own time: the grid's share of that loop taken out.
    const double scanRate = scanned / (secondsSince(start) - scanned / gridRate);
    std::printf(
        "nearest lane: grid %.0f queries/s, scan %.0f queries/s (%.0fx); %zu of %d found; the two agree "
        "on %zu of %d\n",
        gridRate, scanRate, gridRate / scanRate, found, queries, agreed, scanned);
    std::printf("scan_queries_per_second=%.1f\n", scanRate);
    return agreed == size_t(scanned) ? 0 : 1;
}
