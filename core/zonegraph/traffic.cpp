#include "core/zonegraph/traffic.h"

#include "core/zonegraph/polyline.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sp::zonegraph {
namespace {

constexpr double kLost = 6.0;       // metres off its lanes before a driver looks for the nearest lane again
constexpr int kMaxRouteLanes = 64;  // a route never holds more (short connectors in a tight grid)
constexpr double kStopMargin = 1.0; // metres between a front bumper and the junction it waits for
// Connector lanes whose centre lines come nearer than this conflict: two cars on them could touch (a car's
// width, and room for the body to swing out of the line in a turn).
constexpr double kClearance = 3.0;

Eigen::Vector2d flat(const Eigen::Vector3d& v) {
    return v.head<2>();
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

double pointToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a + nearestOnSegment(a, b, p) * (b - a) - p).norm();
}

// The distance between segments ab and cd on the ground: zero where they cross.
double segmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return 0.0;
    return std::min(
        {pointToSegment(a, c, d), pointToSegment(b, c, d), pointToSegment(c, a, b), pointToSegment(d, a, b)});
}

// Whether two cars on these centre lines could touch: they come within a car's width and a margin.
bool polylinesTouch(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& q) {
    for (size_t i = 1; i < p.size(); ++i)
        for (size_t j = 1; j < q.size(); ++j)
            if (segmentDistance(flat(p[i - 1]), flat(p[i]), flat(q[j - 1]), flat(q[j])) < kClearance)
                return true;
    return false;
}

// xorshift64*: small, fast and the same everywhere, so routes repeat run to run.
std::uint64_t nextRandom(std::uint64_t& state) {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return state * 0x2545F4914F6CDD1DULL;
}

// The point of the lane nearest `point` among its segments within [low, high] metres along it: a car is
// looked for near where it was, so a lane that bends back on itself (a U-turn) cannot capture it on its
// other leg.
LaneLocation projectNear(const LaneGraph& graph, int laneIndex, const Eigen::Vector3d& point, double low,
                         double high) {
    const Lane& lane = graph.lanes()[size_t(laneIndex)];
    double best = std::numeric_limits<double>::infinity(), bestDistance = 0.0;
    for (size_t i = 1; i < lane.points.size(); ++i) {
        if (lane.distances[i] < low || lane.distances[i - 1] > high)
            continue;
        const Eigen::Vector3d &a = lane.points[i - 1], &b = lane.points[i];
        const double t = nearestOnSegment(a, b, point);
        const double d2 = (a + t * (b - a) - point).squaredNorm();
        if (d2 < best) {
            best = d2;
            bestDistance = lane.distances[i - 1] + t * (lane.distances[i] - lane.distances[i - 1]);
        }
    }
    return graph.locationAt(laneIndex, bestDistance);
}

bool isJunctionConnector(const Lane& lane) {
    return lane.junction >= 0;
}

} // namespace

Traffic::Traffic(const LaneGraph& graph) : graph_(&graph) {
    // Connectors of one junction, of one tag, that start from different lanes and cross, pass close or end on
    // the same lane would put two cars in one place.
    std::unordered_map<int, std::vector<int>> byJunction;
    const auto& lanes = graph.lanes();
    for (int l = 0; l < int(lanes.size()); ++l)
        if (isJunctionConnector(lanes[size_t(l)]))
            byJunction[lanes[size_t(l)].junction].push_back(l);
    for (const auto& [junction, connectors] : byJunction)
        for (size_t i = 0; i < connectors.size(); ++i)
            for (size_t j = i + 1; j < connectors.size(); ++j) {
                const Lane &a = lanes[size_t(connectors[i])], &b = lanes[size_t(connectors[j])];
                if (a.tag != b.tag || a.prev == b.prev)
                    continue;
                if (a.next == b.next || polylinesTouch(a.points, b.points)) {
                    conflicts_[connectors[i]].push_back(connectors[j]);
                    conflicts_[connectors[j]].push_back(connectors[i]);
                }
            }
}

bool Traffic::conflicts(int a, int b) const {
    const auto it = conflicts_.find(a);
    return it != conflicts_.end() && std::find(it->second.begin(), it->second.end(), b) != it->second.end();
}

bool Traffic::track(Driver& driver, const CarState& car) const {
    const LaneGraph& graph = *graph_;
    if (!driver.route.empty() && (driver.route[0] < 0 || driver.route[0] >= int(graph.lanes().size())))
        driver.route.clear(); // a route from another graph
    LaneLocation at;
    if (!driver.route.empty()) {
        double low = driver.distance - 5.0, high = driver.distance + 25.0;
        for (;;) {
            at = projectNear(graph, driver.route[0], car.position, low, high);
            const double length = graph.lanes()[size_t(driver.route[0])].length();
            if (at.distance < length - 1e-6 || driver.route.size() < 2)
                break;
            driver.route.erase(driver.route.begin()); // past this lane's end: on the next one
            low = 0.0;
            high = 25.0;
        }
        if ((car.position - at.position).norm() > kLost)
            driver.route.clear();
    }
    if (driver.route.empty()) {
        const Eigen::Vector3d heading(car.forward.x(), car.forward.y(), 0.0);
        const auto found = graph.nearest(car.position, kLost, driver.settings.tag, &heading);
        if (!found)
            return false;
        at = *found;
        driver.route = {at.lane};
    }
    driver.distance = at.distance;
    const Eigen::Vector2d left = Eigen::Vector2d(-at.direction.y(), at.direction.x()).normalized();
    driver.lateral = flat(car.position - at.position).dot(left);
    return true;
}

void Traffic::extendRoute(Driver& driver, double horizon) const {
    const auto& lanes = graph_->lanes();
    if (driver.random == 0)
        driver.random = driver.settings.seed * 0x9E3779B97F4A7C15ULL | 1ULL;
    double reach = lanes[size_t(driver.route[0])].length() - driver.distance;
    for (size_t k = 1; k < driver.route.size(); ++k)
        reach += lanes[size_t(driver.route[k])].length();
    while (reach < horizon && int(driver.route.size()) < kMaxRouteLanes) {
        std::vector<int> choices;
        for (int next : lanes[size_t(driver.route.back())].next)
            if (driver.settings.tag < 0 || lanes[size_t(next)].tag == driver.settings.tag)
                choices.push_back(next);
        if (choices.empty())
            return; // a dead end: the route stops there
        const int chosen = choices[size_t(nextRandom(driver.random) % choices.size())];
        driver.route.push_back(chosen);
        reach += lanes[size_t(chosen)].length();
    }
}

Eigen::Vector3d Traffic::pointAhead(const Driver& driver, double ahead) const {
    double d = driver.distance + ahead;
    for (size_t k = 0; k < driver.route.size(); ++k) {
        const double length = graph_->lanes()[size_t(driver.route[k])].length();
        if (d <= length || k + 1 == driver.route.size())
            return graph_->locationAt(driver.route[k], std::min(d, length)).position;
        d -= length;
    }
    return Eigen::Vector3d::Zero(); // unreachable: a tracked driver has a route
}

double Traffic::curveSpeed(const Driver& driver, double horizon) const {
    // The bend at each sample is the turn between two 3 m chords; the speed allowed there is the one whose
    // lateral acceleration in it is the driver's limit, and from here the driver may be going as fast as
    // braking comfortably still reaches that.
    constexpr double kChord = 3.0, kStep = 2.0;
    const DriverSettings& s = driver.settings;
    double allowed = std::numeric_limits<double>::infinity();
    Eigen::Vector3d p0 = pointAhead(driver, 0.0), p1 = pointAhead(driver, kChord);
    for (double ahead = 0.0; ahead <= horizon; ahead += kStep) {
        const Eigen::Vector3d p2 = pointAhead(driver, ahead + 2.0 * kChord);
        const Eigen::Vector2d a = flat(p1 - p0), b = flat(p2 - p1);
        if (a.norm() > 1e-3 && b.norm() > 1e-3) {
            const double turn = std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
            const double curvature = turn / kChord;
            if (curvature > 1e-4) {
                const double bend = std::sqrt(s.lateralAcceleration / curvature);
                allowed = std::min(allowed, std::sqrt(bend * bend + 2.0 * s.comfortDeceleration * ahead));
            }
        }
        p0 = pointAhead(driver, ahead + kStep);
        p1 = pointAhead(driver, ahead + kStep + kChord);
    }
    return allowed;
}

// What one driver found this frame, between the stages of Traffic::step.
struct Traffic::Look {
    bool onLanes = false;
    double horizon = 0.0;                                 // metres of route it looks along
    double gap = std::numeric_limits<double>::infinity(); // to the car ahead
    double leaderSpeed = 0.0;
    size_t leaderAt = 0;    // the route index of the lane that car is on (route.size(): none)
    int request = -1;       // the connector it asks to claim now
    double requestAt = 0.0; // metres from the car's place on its route to that connector's start
    double stopLine = std::numeric_limits<double>::infinity(); // metres along the route to stop before
};

void Traffic::step(const std::vector<Driver*>& drivers, const std::vector<CarState>& cars,
                   const std::vector<CarState>& others, std::vector<DriveCommand>& commands) const {
    const size_t n = drivers.size();
    commands.assign(n, DriveCommand{});
    std::vector<Look> looks(n);
    for (size_t i = 0; i < n; ++i) {
        Driver& driver = *drivers[i];
        driver.waiting = false;
        driver.gapAhead = std::numeric_limits<double>::infinity();
        looks[i].onLanes = track(driver, cars[i]);
        if (!looks[i].onLanes) {
            driver.claims.clear();
            driver.requestFrames = 0;
            continue;
        }
        const double v = std::max(cars[i].speed, 0.0);
        looks[i].horizon = std::max(40.0, v * v / (2.0 * driver.settings.comfortDeceleration) + 30.0);
        extendRoute(driver, looks[i].horizon);
    }
    // The cars without drivers, where they are: on the nearest lane that runs their way. Drivers keep clear
    // of them as of each other.
    std::vector<CarState> everyone = cars;
    std::vector<std::pair<int, double>> places(n);
    for (size_t i = 0; i < n; ++i)
        if (looks[i].onLanes)
            places[i] = {drivers[i]->route[0], drivers[i]->distance};
        else
            places[i] = {-1, 0.0};
    for (const CarState& other : others) {
        const Eigen::Vector3d heading(other.forward.x(), other.forward.y(), 0.0);
        const auto at = graph_->nearest(other.position, kLost, -1, &heading);
        everyone.push_back(other);
        places.emplace_back(at ? at->lane : -1, at ? at->distance : 0.0);
    }
    findLeaders(drivers, everyone, places, looks);
    claimJunctions(drivers, cars, places, looks);
    for (size_t i = 0; i < n; ++i)
        if (looks[i].onLanes)
            commands[i] = drive(*drivers[i], cars[i], looks[i]);
        else
            commands[i].brake = 1.0; // off the lanes: stop
}

void Traffic::findLeaders(const std::vector<Driver*>& drivers, const std::vector<CarState>& cars,
                          const std::vector<std::pair<int, double>>& places, std::vector<Look>& looks) const {
    const auto& lanes = graph_->lanes();
    // Who is on which lane, by distance along it.
    std::unordered_map<int, std::vector<std::pair<double, size_t>>> occupants;
    for (size_t i = 0; i < places.size(); ++i)
        if (places[i].first >= 0)
            occupants[places[i].first].emplace_back(places[i].second, i);
    for (auto& [lane, list] : occupants)
        std::sort(list.begin(), list.end());
    // The nearest car on `lane` past `after` metres (a car turning off onto a sibling lane counts while its
    // rear may still be at the lanes' common start: within its length of it).
    const auto nearestOn = [&](int lane, double after, bool sibling,
                               size_t self) -> const std::pair<double, size_t>* {
        const auto it = occupants.find(lane);
        if (it == occupants.end())
            return nullptr;
        for (const auto& occupant : it->second)
            if (occupant.second != self && occupant.first > after)
                return sibling && occupant.first > cars[occupant.second].length ? nullptr : &occupant;
        return nullptr;
    };
    for (size_t i = 0; i < drivers.size(); ++i) {
        Look& look = looks[i];
        if (!look.onLanes)
            continue;
        const Driver& driver = *drivers[i];
        look.leaderAt = driver.route.size();
        double offset = -driver.distance;
        for (size_t k = 0; k < driver.route.size() && offset <= look.horizon; ++k) {
            const int lane = driver.route[k];
            const auto consider = [&](const std::pair<double, size_t>* found) {
                if (!found)
                    return;
                const double g = offset + found->first - (cars[i].length + cars[found->second].length) / 2.0;
                if (g < look.gap) {
                    look.gap = g;
                    look.leaderSpeed = cars[found->second].speed;
                }
            };
            consider(nearestOn(lane, k == 0 ? driver.distance : -1.0, false, i));
            if (k > 0)
                for (int sibling : lanes[size_t(driver.route[k - 1])].next)
                    if (sibling != lane)
                        consider(nearestOn(sibling, -1.0, true, i));
            if (look.gap < std::numeric_limits<double>::infinity()) {
                look.leaderAt = k;
                break;
            }
            offset += lanes[size_t(lane)].length();
        }
    }
}

void Traffic::claimJunctions(const std::vector<Driver*>& drivers, const std::vector<CarState>& cars,
                             const std::vector<std::pair<int, double>>& places,
                             std::vector<Look>& looks) const {
    const auto& lanes = graph_->lanes();
    // A connector stays claimed while it is on the route, and until the car's rear has left it.
    std::vector<std::pair<int, size_t>> held; // (connector, driver)
    for (size_t i = 0; i < drivers.size(); ++i) {
        Driver& driver = *drivers[i];
        std::erase_if(driver.claims, [&](int c) {
            if (std::find(driver.route.begin(), driver.route.end(), c) != driver.route.end())
                return false;
            const auto& next = lanes[size_t(c)].next;
            return driver.route.empty() ||
                   std::find(next.begin(), next.end(), driver.route[0]) == next.end() ||
                   driver.distance >= cars[i].length;
        });
        for (int c : driver.claims)
            held.emplace_back(c, i);
    }
    // A car nobody here drives holds the junction connector it is on: drivers wait for it as for each other.
    for (size_t j = drivers.size(); j < places.size(); ++j)
        if (places[j].first >= 0 && isJunctionConnector(lanes[size_t(places[j].first)]))
            held.emplace_back(places[j].first, j);

    // Requests: each driver's first unclaimed connector within a stopping distance. The connector a car is on
    // is claimed whatever else holds one (it is there). A car asks only with nothing ahead of it short of the
    // connector and room for it past the connector's end: one that claimed and then waited (behind a car, or
    // for a full exit lane) would hold up the crossing traffic, which may be what it waits for.
    std::vector<size_t> asking;
    for (size_t i = 0; i < drivers.size(); ++i) {
        Driver& driver = *drivers[i];
        Look& look = looks[i];
        if (!look.onLanes)
            continue;
        const DriverSettings& s = driver.settings;
        const double v = std::max(cars[i].speed, 0.0);
        const double approach = v * v / (2.0 * s.comfortDeceleration) + s.minGap + 8.0;
        double offset = -driver.distance;
        int asked = -1;
        for (size_t k = 0; k < driver.route.size() && k <= look.leaderAt && offset <= approach; ++k) {
            const int lane = driver.route[k];
            const double length = lanes[size_t(lane)].length();
            if (isJunctionConnector(lanes[size_t(lane)]) &&
                std::find(driver.claims.begin(), driver.claims.end(), lane) == driver.claims.end()) {
                if (k == 0) {
                    driver.claims.push_back(lane);
                    held.emplace_back(lane, i);
                } else {
                    asked = lane;
                    look.requestAt = offset;
                    look.stopLine = offset - kStopMargin; // until the claim is granted
                    const double pastEnd = offset + length - cars[i].length / 2.0 + cars[i].length + s.minGap;
                    if (look.gap >= pastEnd)
                        look.request = lane;
                    break;
                }
            }
            offset += length;
        }
        // How long it has asked for this connector: the longest-waiting car goes first.
        driver.requestFrames = asked >= 0 && asked == driver.requested ? driver.requestFrames + 1 : 0;
        driver.requested = asked;
        if (look.request >= 0)
            asking.push_back(i);
    }

    // Granted first come, first served: a request waits while a conflicting connector is held, or while an
    // earlier request that conflicts with it still waits (else a stream of arrivals could starve it).
    std::stable_sort(asking.begin(), asking.end(), [&](size_t a, size_t b) {
        return drivers[a]->requestFrames > drivers[b]->requestFrames;
    });
    std::vector<std::pair<int, size_t>> denied;
    for (size_t i : asking) {
        const int c = looks[i].request;
        const auto blocks = [&](const std::pair<int, size_t>& other) {
            return other.second != i && conflicts(other.first, c);
        };
        if (std::any_of(held.begin(), held.end(), blocks) ||
            std::any_of(denied.begin(), denied.end(), blocks)) {
            denied.emplace_back(c, i);
            drivers[i]->waiting = true;
            continue;
        }
        drivers[i]->claims.push_back(c);
        held.emplace_back(c, i);
        looks[i].stopLine = std::numeric_limits<double>::infinity();
    }
    for (size_t i = 0; i < drivers.size(); ++i)
        if (looks[i].onLanes && looks[i].stopLine < std::numeric_limits<double>::infinity())
            drivers[i]->waiting = true;
}

DriveCommand Traffic::drive(Driver& driver, const CarState& car, Look& look) const {
    const auto& lanes = graph_->lanes();
    const DriverSettings& s = driver.settings;
    const double v = std::max(car.speed, 0.0);

    // The end of a route that leads nowhere is a stop line too.
    if (lanes[size_t(driver.route.back())].next.empty()) {
        double end = -driver.distance;
        for (int lane : driver.route)
            end += lanes[size_t(lane)].length();
        look.stopLine = std::min(look.stopLine, end - kStopMargin);
    }
    double gap = look.gap, leaderSpeed = look.leaderSpeed;
    if (const double toStop = look.stopLine - car.length / 2.0; toStop < gap) {
        gap = toStop;
        leaderSpeed = 0.0;
    }
    driver.gapAhead = gap;

    // Speed: the intelligent driver model toward the target speed the curves ahead allow.
    DriveCommand command;
    const double desired = std::max(std::min(s.targetSpeed, curveSpeed(driver, look.horizon)), 0.1);
    double accel = s.acceleration * (1.0 - std::pow(v / desired, 4.0));
    if (gap < std::numeric_limits<double>::infinity()) {
        const double closing =
            v * (v - leaderSpeed) / (2.0 * std::sqrt(s.acceleration * s.comfortDeceleration));
        const double wanted = s.minGap + std::max(0.0, v * s.timeGap + closing);
        accel -= s.acceleration * std::pow(wanted / std::max(gap, 0.1), 2.0);
    }
    accel = std::clamp(accel, -car.maxDeceleration, s.acceleration);
    if (accel >= 0.0)
        command.throttle = std::min(accel / car.maxAcceleration, 1.0);
    else // stopped and told to slow: hold still
        command.brake = v < 0.3 ? 1.0 : std::min(-accel / car.maxDeceleration, 1.0);
    if (car.speed < -0.3) // rolled back: brake rather than drive on in reverse
        command.brake = 1.0;

    // Steering: pure pursuit from the rear axle toward a point ahead on the route.
    const double lookahead = std::clamp(4.0 + 0.5 * v, 5.0, 15.0);
    const Eigen::Vector2d forward = flat(car.forward).normalized();
    const Eigen::Vector2d left(-forward.y(), forward.x());
    const Eigen::Vector2d toTarget =
        flat(pointAhead(driver, lookahead)) - (flat(car.position) - forward * car.wheelbase / 2.0);
    if (const double reach = toTarget.norm(); reach > 1e-3) {
        const double alpha = std::atan2(toTarget.dot(left), toTarget.dot(forward));
        const double wheelAngle = std::atan(2.0 * car.wheelbase * std::sin(alpha) / reach);
        command.steer = std::clamp(wheelAngle / std::max(car.maxSteer, 1e-3), -1.0, 1.0);
    }
    return command;
}

} // namespace sp::zonegraph
