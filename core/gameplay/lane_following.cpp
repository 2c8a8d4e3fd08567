#include "core/gameplay/lane_following.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <unordered_set>
#include <utility>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/gameplay/wheeled_vehicle.h"
#include "core/world/physics_subsystem.h"
#include "core/world/world.h"
#include "core/world/world_subsystem.h"

namespace {

namespace zonegraph = sp::zonegraph;

// The world's lane-following controllers, stepped together once their actors ticked and before physics.
class LaneTrafficSubsystem : public sp::world::WorldSubsystem {
  public:
    static constexpr int kTickOrder = sp::world::tick_order::kPhysics - 10;

    explicit LaneTrafficSubsystem(UWorld& world) : world_(world) {}

    void OnActorBeginPlay(AActor& actor) override {
        if (dynamic_cast<ALaneFollowingController*>(&actor))
            controllers_.push_back(actor.GetHandle());
        else if (dynamic_cast<AWheeledVehiclePawn*>(&actor))
            vehicles_.push_back(actor.GetHandle());
    }
    void OnActorEndPlay(AActor& actor) override {
        std::erase(controllers_, actor.GetHandle());
        std::erase(vehicles_, actor.GetHandle());
    }

    void Tick(double /*deltaSeconds*/) override {
        drivers_.clear();
        cars_.clear();
        driven_.clear();
        std::vector<std::pair<ALaneFollowingController*, AWheeledVehiclePawn*>> driving;
        for (const sp::reflect::ObjectHandle& handle : controllers_) {
            auto* controller =
                dynamic_cast<ALaneFollowingController*>(sp::reflect::ObjectTable::find(handle));
            auto* vehicle =
                controller ? dynamic_cast<AWheeledVehiclePawn*>(controller->K2_GetPawn()) : nullptr;
            if (!vehicle)
                continue;
            if (controller->bDriving) {
                driving.emplace_back(controller, vehicle);
            } else {
                controller->resetDriver(); // it says nothing about lanes while it only holds the brake
                vehicle->ApplyControls(0.0, 0.0, 1.0, 0.0);
            }
        }
        if (driving.empty())
            return;
        const zonegraph::Traffic* traffic = currentTraffic();
        for (auto [controller, vehicle] : driving) {
            const int tag = traffic ? traffic->graph().tagIndex(controller->LaneTag) : -1;
            if (!traffic || (tag < 0 && !controller->LaneTag.empty())) {
                if (traffic)
                    warnOnce("ALaneFollowingController: " + controller->GetName() +
                             " waits: no lane is tagged '" + controller->LaneTag + "'");
                controller->resetDriver();
                vehicle->ApplyControls(0.0, 0.0, 1.0, 0.0); // no lanes to follow: stop
                continue;
            }
            zonegraph::Driver& driver = controller->driver();
            if (driver.settings.tag != tag) { // other lanes: a route on the old ones means nothing
                controller->resetDriver();
                driver.settings.tag = tag;
            }
            drivers_.push_back(&driver);
            cars_.push_back(carState(*vehicle));
            driven_.push_back(vehicle);
        }
        if (drivers_.empty())
            return;
        // Every other car (a player's, a parked one, one whose driver waits) is in the drivers' way.
        others_.clear();
        const std::unordered_set<const AWheeledVehiclePawn*> driven(driven_.begin(), driven_.end());
        for (const sp::reflect::ObjectHandle& handle : vehicles_)
            if (auto* vehicle = dynamic_cast<AWheeledVehiclePawn*>(sp::reflect::ObjectTable::find(handle));
                vehicle && !driven.contains(vehicle))
                others_.push_back(carState(*vehicle));
        traffic->step(drivers_, cars_, others_, commands_);
        for (size_t i = 0; i < driven_.size(); ++i)
            driven_[i]->ApplyControls(commands_[i].throttle, commands_[i].steer, commands_[i].brake, 0.0);
    }

  private:
    // The car as its driver sees it: where and how fast, its size and what its engine and brakes can do.
    static zonegraph::CarState carState(AWheeledVehiclePawn& vehicle) {
        zonegraph::CarState car;
        car.position = vehicle.Mesh->GetComponentLocation().toEigen();
        car.forward = vehicle.Mesh->GetForwardVector().toEigen();
        car.speed = vehicle.GetForwardSpeed();
        const Eigen::Vector3d size = vehicle.Mesh->GetComponentScale().toEigen();
        car.length = size.x();
        car.wheelbase = 0.62 * size.x(); // the wheels sit at 62 % of the half length (AWheeledVehiclePawn)
        car.maxSteer = vehicle.MaxSteerAngle * std::numbers::pi / 180.0;
        const double mass = std::max(vehicle.Mesh->GetMass(), 1e-3);
        car.maxAcceleration = std::max(vehicle.MaxEngineForce / mass, 1e-3);
        car.maxDeceleration = std::max(4.0 * vehicle.MaxBrakeForce / mass, 1e-3);
        return car;
    }

    // Logs a problem once, not every frame.
    void warnOnce(const std::string& message) {
        if (warned_.insert(message).second)
            SP_LOG(message);
    }

    // The traffic on the lanes as they are now, remade when the lane graph was rebuilt (the drivers' routes
    // then name lanes of the old graph, so they start again from the nearest lane). Null, with the error
    // logged once, while the roads cannot make lanes.
    const zonegraph::Traffic* currentTraffic() {
        AZoneGraphData* data = UZoneGraphSubsystem::of(world_).GetZoneGraphData();
        const zonegraph::LaneGraph* graph = nullptr;
        try {
            graph = &data->graph("ALaneFollowingController");
        } catch (const sp::InvalidArgument& error) {
            warnOnce(std::string("ALaneFollowingController: the cars stop, the roads make no lanes: ") +
                     error.what());
            return nullptr;
        }
        // The traffic refers to the graph: made again for another AZoneGraphData or another build of it.
        if (!traffic_ || !(data_ == data->GetHandle()) || revision_ != data->graphRevision()) {
            traffic_.emplace(*graph);
            data_ = data->GetHandle();
            revision_ = data->graphRevision();
            for (const sp::reflect::ObjectHandle& handle : controllers_)
                if (auto* c = dynamic_cast<ALaneFollowingController*>(sp::reflect::ObjectTable::find(handle)))
                    c->resetDriver();
        }
        return &*traffic_;
    }

    UWorld& world_;
    std::vector<sp::reflect::ObjectHandle> controllers_; // in the order they began play
    std::vector<sp::reflect::ObjectHandle> vehicles_;    // every car of the world
    std::optional<zonegraph::Traffic> traffic_;
    sp::reflect::ObjectHandle data_; // the AZoneGraphData whose graph traffic_ drives on
    std::uint64_t revision_ = 0;
    std::set<std::string> warned_;
    // Per frame, kept to reuse their memory.
    std::vector<zonegraph::Driver*> drivers_;
    std::vector<zonegraph::CarState> cars_;
    std::vector<AWheeledVehiclePawn*> driven_;
    std::vector<zonegraph::CarState> others_;
    std::vector<zonegraph::DriveCommand> commands_;
};

// FNV-1a: a seed from the controller's name that is the same on every machine.
std::uint64_t seedOf(const std::string& name) {
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    for (unsigned char c : name)
        hash = (hash ^ c) * 0x100000001b3ULL;
    return hash;
}

} // namespace

void ALaneFollowingController::SetTargetSpeed(double NewSpeed) {
    sp::checkSetting(std::isfinite(NewSpeed) && NewSpeed > 0.0, "ALaneFollowingController", "TargetSpeed",
                     "> 0 m/s", NewSpeed);
    TargetSpeed = NewSpeed;
}

void ALaneFollowingController::SetMinGap(double NewGap) {
    sp::checkSetting(std::isfinite(NewGap) && NewGap >= 0.0, "ALaneFollowingController", "MinGap", ">= 0 m",
                     NewGap);
    MinGap = NewGap;
}

void ALaneFollowingController::SetTimeGap(double NewGap) {
    sp::checkSetting(std::isfinite(NewGap) && NewGap >= 0.0, "ALaneFollowingController", "TimeGap", ">= 0 s",
                     NewGap);
    TimeGap = NewGap;
}

void ALaneFollowingController::BeginPlay() {
    AController::BeginPlay();
    GetWorld()->GetSubsystem<LaneTrafficSubsystem>(); // made now, it hears of this controller beginning play
}

sp::zonegraph::Driver& ALaneFollowingController::driver() {
    driver_.settings.targetSpeed = TargetSpeed;
    driver_.settings.minGap = MinGap;
    driver_.settings.timeGap = TimeGap;
    const std::uint64_t seed = RandomSeed != 0 ? std::uint64_t(RandomSeed) : seedOf(GetName());
    if (seed != driver_.settings.seed) {
        driver_.settings.seed = seed;
        driver_.random = 0; // the chooser starts again from the new seed
    }
    return driver_;
}

void ALaneFollowingController::OnPossess(APawn* /*pawn*/) {
    resetDriver();
}

void ALaneFollowingController::resetDriver() {
    driver_.route.clear();
    driver_.claims.clear();
    driver_.distance = driver_.lateral = 0.0;
    driver_.waiting = false;
    driver_.gapAhead = std::numeric_limits<double>::infinity();
    driver_.requested = -1;
    driver_.requestFrames = 0;
}

FZoneGraphLaneLocation ALaneFollowingController::GetLaneLocation() const {
    FZoneGraphLaneLocation location;
    if (driver_.route.empty() || !K2_GetPawn())
        return location;
    // The lane as the traffic last saw it (the graph may have been rebuilt since: then none).
    AZoneGraphData* data = UZoneGraphSubsystem::of(*GetWorld()).GetZoneGraphData();
    const sp::zonegraph::LaneGraph& graph = data->graph("ALaneFollowingController.GetLaneLocation()");
    if (driver_.route[0] >= int(graph.lanes().size()))
        return location;
    return sp::gameplay::toLaneLocation(graph.locationAt(driver_.route[0], driver_.distance));
}

double ALaneFollowingController::GetGapAhead() const {
    return std::isfinite(driver_.gapAhead) ? driver_.gapAhead : -1.0;
}
