#include "core/zonegraph/traffic.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/core/zonegraph/test_roads.h"

namespace sp::zonegraph {
namespace {

// A car as a kinematic bicycle: what the drivers' commands do to it, without a physics engine (its rear
// axle, half a wheelbase behind its centre, moves the way the car faces; the front wheels turn it). The tests
// in tests/python/test_lanes.py drive Bullet's vehicles.
struct Bicycle {
    CarState state;
    double yaw = 0.0;

    void apply(const DriveCommand& command, double dt) {
        const double accel = command.throttle * state.maxAcceleration - command.brake * state.maxDeceleration;
        state.speed = std::max(state.speed + accel * dt, 0.0);
        Eigen::Vector3d rear = state.position - state.forward * state.wheelbase / 2.0;
        rear += state.forward * state.speed * dt;
        yaw += state.speed / state.wheelbase * std::tan(command.steer * state.maxSteer) * dt;
        state.forward = Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0);
        state.position = rear + state.forward * state.wheelbase / 2.0;
    }
};

Bicycle carAt(const LaneGraph& graph, int lane, double distance) {
    const LaneLocation at = graph.locationAt(lane, distance);
    Bicycle car;
    car.state.position = at.position;
    car.yaw = std::atan2(at.direction.y(), at.direction.x());
    car.state.forward = at.direction;
    return car;
}

using test::circle;
using test::fourWay;
using test::straight;

// Steps every car's driver and car together for `seconds` at 60 Hz; `watch` sees the cars after each step.
template <typename Watch>
void drive(const Traffic& traffic, std::vector<Driver>& drivers, std::vector<Bicycle>& cars, double seconds,
           Watch&& watch) {
    std::vector<Driver*> pointers;
    for (Driver& driver : drivers)
        pointers.push_back(&driver);
    std::vector<DriveCommand> commands;
    for (int frame = 0; frame < int(seconds * 60.0); ++frame) {
        std::vector<CarState> states;
        for (const Bicycle& car : cars)
            states.push_back(car.state);
        traffic.step(pointers, states, {}, commands);
        for (size_t i = 0; i < cars.size(); ++i)
            cars[i].apply(commands[i], 1.0 / 60.0);
        watch();
    }
}

int drivingLaneAt(const LaneGraph& graph, const Eigen::Vector3d& point, const Eigen::Vector3d& heading) {
    const auto found = graph.nearest(point, 5.0, graph.tagIndex("Driving"), &heading);
    return found ? found->lane : -1;
}

TEST(Traffic, ADriverKeepsToItsLaneRoundALoopAtItsSpeed) {
    const LaneGraph graph = LaneGraph::build({circle("Ring", 40.0, 96)}, RoadProfile::twoWayStreet());
    const int lane = drivingLaneAt(graph, {40.0, -1.0, 0.0}, {0.0, 1.0, 0.0});
    ASSERT_GE(lane, 0);
    const Traffic traffic(graph);
    std::vector<Driver> drivers(1);
    drivers[0].settings.tag = graph.tagIndex("Driving");
    drivers[0].settings.targetSpeed = 8.0;
    std::vector<Bicycle> cars{carAt(graph, lane, 0.0)};
    double worst = 0.0, travelled = 0.0, topSpeed = 0.0;
    Eigen::Vector3d last = cars[0].state.position;
    drive(traffic, drivers, cars, 60.0, [&] {
        worst = std::max(worst, std::abs(drivers[0].lateral));
        travelled += (cars[0].state.position - last).norm();
        last = cars[0].state.position;
        topSpeed = std::max(topSpeed, cars[0].state.speed);
    });
    // Half a lane width is the test the issue sets; a kinematic car does far better.
    EXPECT_LT(worst, 0.5);
    // A minute at its speed, less the 4 s it takes to get there at 2 m/s².
    EXPECT_GT(travelled, 0.95 * (60.0 * 8.0 - 16.0));
    EXPECT_NEAR(topSpeed, 8.0, 0.3);
    // It stays on its own lane (a closed road's lane leads into itself).
    EXPECT_EQ(drivers[0].route[0], lane);
}

TEST(Traffic, ADriverStopsBehindAStandingCarAndKeepsItsGap) {
    const LaneGraph graph =
        LaneGraph::build({straight("Main", {0, 0, 0}, {300, 0, 0})}, RoadProfile::twoWayStreet());
    const int lane = drivingLaneAt(graph, {10.0, -1.75, 0.0}, {1.0, 0.0, 0.0});
    const Traffic traffic(graph);
    std::vector<Driver> drivers(1);
    drivers[0].settings.targetSpeed = 12.0;
    drivers[0].settings.tag = graph.tagIndex("Driving");
    std::vector<Bicycle> cars{carAt(graph, lane, 5.0)};
    std::vector<CarState> parked{carAt(graph, lane, 120.0).state};
    std::vector<Driver*> pointers{&drivers[0]};
    std::vector<DriveCommand> commands;
    double closest = 1e9;
    for (int frame = 0; frame < 60 * 40; ++frame) {
        traffic.step(pointers, {cars[0].state}, parked, commands);
        cars[0].apply(commands[0], 1.0 / 60.0);
        closest = std::min(closest, (parked[0].position - cars[0].state.position).norm() - 4.2);
    }
    // Stopped, bumper to bumper at its standstill gap (3 m), never nearer than half of it.
    EXPECT_LT(cars[0].state.speed, 0.05);
    EXPECT_NEAR(drivers[0].gapAhead, 3.0, 0.5);
    EXPECT_GT(closest, 1.5);
}

TEST(Traffic, CarsFromFourSidesTakeTurnsThroughAJunctionWithoutTouching) {
    // Four roads meeting at the origin; a car 30 m out on each, all driving in at once.
    const LaneGraph graph = LaneGraph::build(fourWay(80.0), RoadProfile::twoWayStreet());
    ASSERT_EQ(graph.junctions().size(), 1u);
    const Traffic traffic(graph);
    // Opposite straight movements pass side by side; crossing ones conflict.
    std::vector<Driver> drivers(4);
    std::vector<Bicycle> cars;
    const Eigen::Vector3d starts[4] = {{30, 1.75, 0}, {-1.75, 30, 0}, {-30, -1.75, 0}, {1.75, -30, 0}};
    for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d heading = -starts[i].normalized();
        const int lane = drivingLaneAt(graph, starts[i], heading);
        ASSERT_GE(lane, 0) << i;
        cars.push_back(carAt(graph, lane, graph.nearest(starts[i], 1.0, -1, &heading)->distance));
        drivers[size_t(i)].settings.tag = graph.tagIndex("Driving");
        drivers[size_t(i)].settings.seed = uint64_t(i) + 1;
    }
    double closest = 1e9;
    bool someoneWaited = false;
    std::vector<bool> through(4, false);
    drive(traffic, drivers, cars, 30.0, [&] {
        for (size_t a = 0; a < 4; ++a) {
            someoneWaited = someoneWaited || drivers[a].waiting;
            through[a] = through[a] || cars[a].state.position.norm() > 40.0;
            for (size_t b = a + 1; b < 4; ++b)
                closest = std::min(closest, (cars[a].state.position - cars[b].state.position).norm());
        }
    });
    // Two cars' centres nearer than a car's width and a margin would be touching or as good as.
    EXPECT_GT(closest, 2.5);
    EXPECT_TRUE(someoneWaited);
    for (int i = 0; i < 4; ++i)
        EXPECT_TRUE(through[size_t(i)]) << "car " << i << " never got through";
}

TEST(Traffic, ConnectorsThatCrossConflictAndOppositeStraightsDoNot) {
    const LaneGraph graph = LaneGraph::build(fourWay(80.0), RoadProfile::twoWayStreet());
    const Traffic traffic(graph);
    const int driving = graph.tagIndex("Driving");
    // The connector from the lane arriving along `from` that leaves along `to`.
    const auto connector = [&](Eigen::Vector3d from, Eigen::Vector3d to) {
        const Eigen::Vector3d arriving = from * 20.0 + Eigen::Vector3d(-from.y(), from.x(), 0.0) * 1.75;
        const Eigen::Vector3d inward = -from;
        const int lane = graph.nearest(arriving, 1.0, driving, &inward)->lane;
        for (int c : graph.lanes()[size_t(lane)].next) {
            const Eigen::Vector3d end = graph.lanes()[size_t(c)].points.back();
            if (end.normalized().dot(to) > 0.7)
                return c;
        }
        return -1;
    };
    const Eigen::Vector3d east(1, 0, 0), north(0, 1, 0), west(-1, 0, 0), south(0, -1, 0);
    const int eastToWest = connector(east, west), westToEast = connector(west, east);
    const int northToSouth = connector(north, south), southToNorth = connector(south, north);
    ASSERT_GE(eastToWest, 0);
    ASSERT_GE(northToSouth, 0);
    EXPECT_FALSE(traffic.conflicts(eastToWest, westToEast));
    EXPECT_TRUE(traffic.conflicts(eastToWest, northToSouth));
    EXPECT_TRUE(traffic.conflicts(southToNorth, westToEast));
    // Merging onto one lane conflicts: from the east and from the south, both leaving west.
    EXPECT_TRUE(traffic.conflicts(eastToWest, connector(south, west)));
}

TEST(Traffic, ACarNobodyDrivesHoldsTheJunctionItIsIn) {
    const LaneGraph graph = LaneGraph::build(fourWay(80.0), RoadProfile::twoWayStreet());
    const Traffic traffic(graph);
    const int driving = graph.tagIndex("Driving");
    const Eigen::Vector3d west(-1, 0, 0), south(0, -1, 0);
    // The driver comes from the east and goes straight on, west; a car stands in the junction on its way
    // south.
    const int arriving = graph.nearest({30, 1.75, 0}, 1.0, driving, &west)->lane;
    int across = -1;
    for (int c : graph.lanes()[size_t(arriving)].next)
        if (graph.lanes()[size_t(c)].points.back().x() < -5.0)
            across = c;
    ASSERT_GE(across, 0);
    const int southbound = graph.nearest({-1.75, 30, 0}, 1.0, driving, &south)->lane;
    int blocking = -1;
    for (int c : graph.lanes()[size_t(southbound)].next)
        if (traffic.conflicts(across, c))
            blocking = c; // one of the southbound car's ways through that crosses or meets it
    ASSERT_GE(blocking, 0);
    const LaneLocation standing = graph.locationAt(blocking, graph.lanes()[size_t(blocking)].length() / 2.0);
    CarState parked;
    parked.position = standing.position;
    parked.forward = standing.direction;

    Driver driver;
    driver.settings.tag = driving;
    driver.route = {arriving, across};
    Bicycle car = carAt(graph, arriving, graph.lanes()[size_t(arriving)].length() - 30.0);
    std::vector<Driver*> drivers{&driver};
    std::vector<DriveCommand> commands;
    for (int frame = 0; frame < 60 * 15; ++frame) {
        traffic.step(drivers, {car.state}, {parked}, commands);
        car.apply(commands[0], 1.0 / 60.0);
    }
    // It waits at the junction's edge (8.5 m out, and its stop margin) while the car stands there...
    EXPECT_TRUE(driver.waiting);
    EXPECT_LT(car.state.speed, 0.05);
    EXPECT_GT(car.state.position.x(), 8.5 + 1.0 + 2.1 - 0.1);
    // ... and drives through once it has gone.
    for (int frame = 0; frame < 60 * 10; ++frame) {
        traffic.step(drivers, {car.state}, {}, commands);
        car.apply(commands[0], 1.0 / 60.0);
    }
    EXPECT_LT(car.state.position.x(), -10.0);
}

TEST(Traffic, ACarFarFromEveryLaneBrakes) {
    const LaneGraph graph =
        LaneGraph::build({straight("Main", {0, 0, 0}, {100, 0, 0})}, RoadProfile::twoWayStreet());
    const Traffic traffic(graph);
    Driver driver;
    std::vector<Driver*> drivers{&driver};
    CarState car;
    car.position = {50.0, 40.0, 0.0};
    car.speed = 5.0;
    std::vector<DriveCommand> commands;
    traffic.step(drivers, {car}, {}, commands);
    EXPECT_TRUE(driver.route.empty());
    EXPECT_EQ(commands[0].brake, 1.0);
    EXPECT_EQ(commands[0].throttle, 0.0);
}

} // namespace
} // namespace sp::zonegraph
