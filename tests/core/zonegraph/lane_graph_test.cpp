#include "core/zonegraph/lane_graph.h"

#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/base/error.h"
#include "tests/core/zonegraph/test_roads.h"

namespace sp::zonegraph {
namespace {

using test::circle;
using test::grid;
using test::straight;

const RoadProfile kStreet = RoadProfile::twoWayStreet();

TEST(LaneGraph, AStraightRoadHasItsProfilesLanesSideBySide) {
    const LaneGraph graph = LaneGraph::build({straight("Main", {0, 0, 0}, {100, 0, 0})}, kStreet);
    ASSERT_EQ(graph.tagNames(), (std::vector<std::string>{"Sidewalk", "Driving"}));
    // Four road lanes, from the right edge (-Y, looking along +X) to the left; then the U-turns at both ends.
    ASSERT_EQ(graph.lanes().size(), 8u);
    const double y[] = {-4.5, -1.75, 1.75, 4.5};
    for (int k = 0; k < 4; ++k) {
        const Lane& lane = graph.lanes()[k];
        EXPECT_EQ(lane.road, 0);
        EXPECT_NEAR(lane.length(), 100.0, 1e-9);
        EXPECT_NEAR(lane.points.front().y(), y[k], 1e-9);
        EXPECT_NEAR(lane.points.back().y(), y[k], 1e-9);
        EXPECT_EQ(lane.points.front().x(), k < 2 ? 0.0 : 100.0) << "backward lanes run against the road";
    }
    EXPECT_DOUBLE_EQ(graph.lanes()[1].width, 3.5);
    EXPECT_EQ(graph.lanes()[1].tag, graph.tagIndex("Driving"));
    EXPECT_EQ(graph.tagIndex("Cycling"), -1);
    // At the far end the forward driving lane turns back onto the backward one, through a connector.
    ASSERT_EQ(graph.lanes()[1].next.size(), 1u);
    const Lane& turn = graph.lanes()[graph.lanes()[1].next[0]];
    EXPECT_EQ(turn.road, -1);
    EXPECT_EQ(turn.junction, -1);
    EXPECT_EQ(turn.next, (std::vector<int>{2}));
    EXPECT_TRUE(turn.points.front().isApprox(graph.lanes()[1].points.back()));
    EXPECT_TRUE(turn.points.back().isApprox(graph.lanes()[2].points.front()));
    // Lanes running the same way are neighbours; the driving lanes each way have none.
    EXPECT_EQ(graph.lanes()[1].right, 0);
    EXPECT_EQ(graph.lanes()[1].left, -1);
    EXPECT_EQ(graph.lanes()[2].right, 3);
    EXPECT_EQ(graph.lanes()[3].left, 2);
}

TEST(LaneGraph, FourRoadsEndingTogetherMakeAFourWayJunction) {
    const LaneGraph graph = LaneGraph::build(
        {straight("West", {-50, 0, 0}, {0, 0, 0}), straight("East", {0, 0, 0}, {50, 0, 0}),
         straight("South", {0, -50, 0}, {0, 0, 0}), straight("North", {0, 0, 0}, {0, 50, 0})},
        kStreet);
    ASSERT_EQ(graph.junctions().size(), 1u);
    EXPECT_EQ(graph.junctions()[0].roads, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_TRUE(graph.junctions()[0].position.isZero(1e-9));
    // West's forward driving lane arrives at the junction, stopping half the road's width and the corner
    // radius short of it, and leads into one connector to each other road's leaving driving lane.
    const Lane& arriving = graph.lanes()[1];
    EXPECT_NEAR(arriving.points.back().x(), -(5.5 + BuildOptions().cornerRadius), 1e-9);
    ASSERT_EQ(arriving.next.size(), 3u);
    std::set<int> roads;
    for (const int c : arriving.next) {
        const Lane& connector = graph.lanes()[c];
        EXPECT_EQ(connector.junction, 0);
        EXPECT_EQ(connector.tag, graph.tagIndex("Driving"));
        ASSERT_EQ(connector.next.size(), 1u);
        const Lane& leaving = graph.lanes()[connector.next[0]];
        EXPECT_EQ(leaving.tag, graph.tagIndex("Driving"));
        EXPECT_TRUE(connector.points.back().isApprox(leaving.points.front()));
        EXPECT_NEAR((leaving.points.front() - graph.junctions()[0].position).head<2>().norm(),
                    std::hypot(5.5 + BuildOptions().cornerRadius, 1.75), 1e-9);
        roads.insert(leaving.road);
    }
    EXPECT_EQ(roads, (std::set<int>{1, 2, 3}));
    // 4 arriving lanes of each tag, each into the 3 other roads: 24 connectors; free ends make 4 U-turns
    // each.
    int connectors = 0, turns = 0;
    for (const Lane& lane : graph.lanes()) {
        connectors += lane.junction == 0;
        turns += lane.road == -1 && lane.junction == -1;
    }
    EXPECT_EQ(connectors, 24);
    EXPECT_EQ(turns, 8);
}

TEST(LaneGraph, ARoadEndingOnAnotherSplitsItIntoATJunction) {
    const LaneGraph graph = LaneGraph::build(
        {straight("Main", {-50, 0, 0}, {50, 0, 0}, 11), straight("Side", {0, 0.3, 0}, {0, 40, 0})}, kStreet);
    ASSERT_EQ(graph.junctions().size(), 1u);
    EXPECT_EQ(graph.junctions()[0].roads, (std::vector<int>{0, 1}));
    int mainLanes = 0;
    for (const Lane& lane : graph.lanes())
        mainLanes += lane.road == 0;
    EXPECT_EQ(mainLanes, 8) << "Main is two pieces, either side of the junction";
    // Driving straight on along Main goes through the junction.
    const Lane& west = graph.lanes()[1];
    ASSERT_EQ(west.road, 0);
    std::set<int> reached;
    for (const int c : west.next)
        reached.insert(graph.lanes()[graph.lanes()[c].next[0]].road);
    EXPECT_EQ(reached, (std::set<int>{0, 1}));
}

TEST(LaneGraph, RoadsThatCrossWithoutAJunctionAreRefused) {
    try {
        LaneGraph::build({straight("H", {-50, 0, 0}, {50, 0, 0}), straight("V", {0, -50, 0}, {0, 50, 0})},
                         kStreet);
        FAIL() << "expected InvalidArgument";
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(),
                     "LaneGraph::build(): road 'H' crosses road 'V' at (0, 0, 0) without a junction: end "
                     "one of them there, or split it there into two roads");
    }
}

TEST(LaneGraph, BadInputIsRefusedNamingIt) {
    const auto message = [](const std::vector<RoadInput>& roads, const RoadProfile& profile) -> std::string {
        try {
            LaneGraph::build(roads, profile);
        } catch (const InvalidArgument& e) {
            return e.what();
        }
        return "(built)";
    };
    const RoadInput road = straight("Main", {0, 0, 0}, {10, 0, 0});
    EXPECT_EQ(message({RoadInput{"Dot", {{1, 2, 3}, {1, 2, 3}}}}, kStreet),
              "LaneGraph::build(): road 'Dot' needs at least two distinct points, got 1");
    EXPECT_EQ(message({RoadInput{"Nan", {{0, 0, 0}, {NAN, 0, 0}}}}, kStreet),
              "LaneGraph::build(): road 'Nan' has a point that is not finite");
    EXPECT_EQ(message({road}, RoadProfile{}), "LaneGraph::build(): the road profile has no lanes");
    EXPECT_EQ(message({road}, RoadProfile{{{"Driving", 0.0, true}}}),
              "LaneGraph::build(): a lane's width must be > 0, got 0");
    EXPECT_EQ(message({road}, RoadProfile{{{"", 3.0, true}}}), "LaneGraph::build(): a lane has no tag");
}

TEST(LaneGraph, AClosedRoadsLanesLoopAndAdvanceAlongTheirOwnArc) {
    const LaneGraph graph = LaneGraph::build({circle("Ring", 20.0, 720)}, kStreet);
    EXPECT_TRUE(graph.junctions().empty());
    ASSERT_EQ(graph.lanes().size(), 4u) << "no connectors: each lane leads into itself";
    const Lane& driving = graph.lanes()[1];
    EXPECT_EQ(driving.next, (std::vector<int>{1}));
    // Counter-clockwise, the right of the road is outside: the forward driving lane is a circle of 21.75 m.
    const double radius = 21.75;
    EXPECT_NEAR(driving.length(), 2.0 * M_PI * radius, 1e-3);
    const LaneLocation start = graph.locationAt(1, 0.0);
    EXPECT_TRUE(start.position.isApprox(Eigen::Vector3d(radius, 0, 0), 1e-9));
    for (const double d : {5.0, 20.0, 60.0, 100.0}) {
        const LaneLocation moved = graph.advanced(start, d);
        const double angle = d / radius;
        EXPECT_NEAR(moved.distance, d, 1e-9);
        EXPECT_NEAR(
            (moved.position - Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), 0)).norm(),
            0.0, 2e-3)
            << d;
        EXPECT_NEAR(moved.direction.dot(Eigen::Vector3d(-std::sin(angle), std::cos(angle), 0)), 1.0, 1e-4);
    }
    // Advancing stops at the lane's ends.
    EXPECT_DOUBLE_EQ(graph.advanced(start, 1e6).distance, driving.length());
    EXPECT_DOUBLE_EQ(graph.advanced(start, -3.0).distance, 0.0);
}

TEST(LaneGraph, NearestLaneIsTheScansAnswer) {
    const LaneGraph graph = LaneGraph::build(grid(6, 60.0), kStreet);
    ASSERT_EQ(graph.junctions().size(), 49u);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> coordinate(-30.0, 390.0), height(-2.0, 2.0);
    int found = 0;
    for (int i = 0; i < 3000; ++i) {
        const Eigen::Vector3d point(coordinate(random), coordinate(random), height(random));
        const double reach = i % 3 == 0 ? 4.0 : (i % 3 == 1 ? 30.0 : 1e9);
        const int tag =
            i % 4 == 0 ? graph.tagIndex("Sidewalk") : (i % 4 == 1 ? graph.tagIndex("Driving") : -1);
        // Every fifth query wants a lane running its way (a car finding its side of the road).
        const Eigen::Vector3d heading(std::cos(i * 0.7), std::sin(i * 0.7), 0.0);
        const Eigen::Vector3d* way = i % 5 == 0 ? &heading : nullptr;
        const auto byGrid = graph.nearest(point, reach, tag, way);
        const auto byScan = graph.nearestByScan(point, reach, tag, way);
        ASSERT_EQ(byGrid.has_value(), byScan.has_value()) << i;
        if (!byGrid)
            continue;
        ++found;
        EXPECT_EQ(byGrid->lane, byScan->lane) << i;
        EXPECT_DOUBLE_EQ(byGrid->distance, byScan->distance) << i;
        EXPECT_TRUE(byGrid->position.isApprox(byScan->position)) << i;
        if (tag >= 0) {
            EXPECT_EQ(graph.lanes()[byGrid->lane].tag, tag);
        }
        EXPECT_LE((byGrid->position - point).norm(), reach);
        if (way) {
            EXPECT_GT(byGrid->direction.dot(heading), 0.0) << i;
        }
    }
    EXPECT_GT(found, 2000);
    // Far from every lane: none, not an error.
    EXPECT_FALSE(graph.nearest({5000, 5000, 0}, 10.0).has_value());
}

TEST(LaneGraph, TheSameRoadsBuildTheSameLanes) {
    const LaneGraph a = LaneGraph::build(grid(3, 40.0), kStreet),
                    b = LaneGraph::build(grid(3, 40.0), kStreet);
    ASSERT_EQ(a.lanes().size(), b.lanes().size());
    for (size_t l = 0; l < a.lanes().size(); ++l) {
        EXPECT_EQ(a.lanes()[l].points, b.lanes()[l].points);
        EXPECT_EQ(a.lanes()[l].next, b.lanes()[l].next);
    }
}

} // namespace
} // namespace sp::zonegraph
