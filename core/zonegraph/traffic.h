#pragma once
// Traffic: drivers that take cars along a LaneGraph's lanes. Each frame a driver is told where its car is and
// how fast it goes (from the physics step just done) and answers with the car's inputs: throttle, steering
// and brake. It never moves the car itself, so cars drive as the vehicle physics lets them.
//
// - Route. A driver keeps the lanes ahead of it: the lane it is on, then the lanes it chose to take, far
// enough
//   to see a stopping distance ahead. At a lane's end it picks one of the lanes that lane leads into (of its
//   own tag), at random from its own seeded generator: a turn or straight on at a junction, the U-turn at a
//   free road end.
// - Steering: pure pursuit, toward the point of the route a speed-dependent distance ahead of the car.
// - Speed: the intelligent driver model (Treiber, Hennecke and Helbing 2000): free-road acceleration up to
// the
//   target speed, which curves ahead lower to what their bend allows, braking for the car ahead (a time gap
//   and a standstill gap) and for stop lines.
// - Junctions. Before entering a junction a driver claims the connector lane it will take; a claim is granted
//   when no other driver holds a connector that crosses or merges with it, else the driver stops at the
//   junction's edge until one is free. Claims are granted in driver order and released once the car has left
//   the connector.
//
// Pure logic: no engine objects. World coordinates, metres, seconds, Z up.

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/zonegraph/lane_graph.h"

namespace sp::zonegraph {

// How a driver drives.
struct DriverSettings {
    double targetSpeed = 10.0;        // m/s on a free, straight road
    double minGap = 3.0;              // metres bumper to bumper when stopped behind a car
    double timeGap = 1.2;             // seconds of headway kept behind a car at speed
    double acceleration = 2.0;        // m/s², the most it asks for
    double comfortDeceleration = 3.0; // m/s², what it plans to brake with
    double lateralAcceleration = 2.5; // m/s², what it allows in curves
    int tag = -1;                     // the lanes it drives (a tag index; -1: any)
    std::uint64_t seed = 1;           // its turn choices' generator
};

// A car as its driver sees it after a physics step.
struct CarState {
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); // the chassis' centre
    Eigen::Vector3d forward = Eigen::Vector3d::UnitX(); // unit, the car's X axis
    double speed = 0.0;                                 // along forward, m/s
    double length = 4.2;                                // bumper to bumper, metres
    double wheelbase = 2.6;                             // front to rear axle, metres
    double maxSteer = 0.61;                             // radians of front wheel angle at full steer input
    double maxAcceleration = 4.0;                       // m/s² at full throttle
    double maxDeceleration = 10.0;                      // m/s² at full brake
};

// A car's inputs: throttle in [0, 1], steer in [-1, 1] (positive left), brake in [0, 1].
struct DriveCommand {
    double throttle = 0.0;
    double steer = 0.0;
    double brake = 0.0;
};

// One driver and what it remembers between frames.
struct Driver {
    DriverSettings settings;
    // route[0]: the lane the car is on; then the lanes it chose to take next. Empty: off the lanes.
    std::vector<int> route;
    double distance = 0.0; // along route[0], metres
    double lateral = 0.0;  // the car's offset from route[0]'s centre line, left positive, metres
    double gapAhead = std::numeric_limits<double>::infinity(); // bumper to the car or stop line ahead
    bool waiting = false;     // stopping for a junction (crossing traffic in it, or no room past it)
    std::vector<int> claims;  // the connector lanes it holds
    int requested = -1;       // the connector it asks for (and may not have yet)
    int requestFrames = 0;    // for how many frames it has asked: the longest-asking is served first
    std::uint64_t random = 0; // the turn chooser's state (0: not seeded yet)
};

class Traffic {
  public:
    explicit Traffic(const LaneGraph& graph);

    const LaneGraph& graph() const { return *graph_; }
    // Whether connector lanes a and b cross or merge (one junction's, not from the same lane): cars may not
    // be on both at once.
    bool conflicts(int a, int b) const;

    // One frame for every driver: finds each car on its lanes, then decides its inputs (commands[i] for
    // drivers[i], cars[i]). A car more than a few metres off its lanes is found again on the nearest lane
    // that runs its way; one far from every lane of its tag gets only the brake. `others` are cars nobody
    // here drives (a player's, a parked one): drivers keep their distance from them too.
    void step(const std::vector<Driver*>& drivers, const std::vector<CarState>& cars,
              const std::vector<CarState>& others, std::vector<DriveCommand>& commands) const;

  private:
    struct Look;
    // The stages of a step: the car ahead of each driver; the junction claims asked for and granted; each
    // driver's inputs.
    // `cars` and `places` (lane, distance; lane -1 off the lanes) hold the drivers' cars, then the others.
    void findLeaders(const std::vector<Driver*>& drivers, const std::vector<CarState>& cars,
                     const std::vector<std::pair<int, double>>& places, std::vector<Look>& looks) const;
    void claimJunctions(const std::vector<Driver*>& drivers, const std::vector<CarState>& cars,
                        const std::vector<std::pair<int, double>>& places, std::vector<Look>& looks) const;
    DriveCommand drive(Driver& driver, const CarState& car, Look& look) const;
    // Places the driver on its route from its car's position, or on the nearest lane; false when there is
    // none.
    bool track(Driver& driver, const CarState& car) const;
    // Extends the route until it reaches `horizon` metres past the car (or a lane that leads nowhere).
    void extendRoute(Driver& driver, double horizon) const;
    // The point `ahead` metres along the route from the car's place on it.
    Eigen::Vector3d pointAhead(const Driver& driver, double ahead) const;
    // The speed the route's curves allow from here, braking comfortably for those ahead.
    double curveSpeed(const Driver& driver, double horizon) const;

    const LaneGraph* graph_;
    std::unordered_map<int, std::vector<int>> conflicts_; // connector -> the connectors it conflicts with
};

} // namespace sp::zonegraph
