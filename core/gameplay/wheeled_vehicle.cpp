#include "core/gameplay/wheeled_vehicle.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/base/error.h"
#include "core/gameplay/controller.h"
#include "core/world/physics_hooks.h"
#include "core/world/physics_subsystem.h"
#include "core/world/world.h"

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;
constexpr double kWheelWidth = 0.25; // metres, of the wheel meshes

UStaticMeshComponent* makeVisual(AActor& owner, const char* name, const char* mesh) {
    auto* component = owner.CreateDefaultSubobject<UStaticMeshComponent>(name);
    component->StaticMesh = mesh;
    component->CollisionPrimitive = ECollisionPrimitive::NoCollision; // the vehicle's rays are its wheels
    return component;
}

FTransform transformOf(const Eigen::Isometry3d& pose, const Eigen::Vector3d& scale) {
    FTransform transform;
    transform.Translation = FVector::fromEigen(pose.translation());
    transform.Rotation = FQuat::fromEigen(Eigen::Quaterniond(pose.linear()));
    transform.Scale3D = FVector::fromEigen(scale);
    return transform;
}

} // namespace

AWheeledVehiclePawn::AWheeledVehiclePawn() : APawn(NoDefaultRoot{}) {
    // A car drives where its wheels take it: the controller's view does not turn it.
    bUseControllerRotationPitch = bUseControllerRotationYaw = bUseControllerRotationRoll = false;
    Mesh = CreateDefaultSubobject<UStaticMeshComponent>("Mesh");
    Mesh->StaticMesh = "/Engine/BasicShapes/Cube";
    Mesh->RelativeScale3D = {4.2, 1.8, 0.6};
    Mesh->MassInKg = 1500.0;
    Mesh->Friction = 0.6;
    Mesh->bSimulatePhysics = true;
    Cabin = makeVisual(*this, "Cabin", "/Engine/BasicShapes/Cube");
    Cabin->RelativeLocation = {-0.05, 0.0, 0.9}; // in the chassis' unit-cube frame (scaled by it)
    Cabin->RelativeScale3D = {0.5, 0.85, 0.9};
    WheelFrontLeft = makeVisual(*this, "WheelFrontLeft", "/Engine/BasicShapes/Cylinder");
    WheelFrontRight = makeVisual(*this, "WheelFrontRight", "/Engine/BasicShapes/Cylinder");
    WheelRearLeft = makeVisual(*this, "WheelRearLeft", "/Engine/BasicShapes/Cylinder");
    WheelRearRight = makeVisual(*this, "WheelRearRight", "/Engine/BasicShapes/Cylinder");
    Wheels = {WheelFrontLeft, WheelFrontRight, WheelRearLeft, WheelRearRight};
    InputComponent = CreateDefaultSubobject<UInputComponent>("InputComponent");
    placeWheelMeshes(nullptr); // at rest under the chassis
}

void AWheeledVehiclePawn::SetMaxEngineForce(double NewForce) {
    sp::checkSetting(std::isfinite(NewForce) && NewForce >= 0.0, "AWheeledVehiclePawn", "MaxEngineForce",
                     ">= 0", NewForce);
    MaxEngineForce = NewForce;
}
void AWheeledVehiclePawn::SetMaxBrakeForce(double NewForce) {
    sp::checkSetting(std::isfinite(NewForce) && NewForce >= 0.0, "AWheeledVehiclePawn", "MaxBrakeForce",
                     ">= 0", NewForce);
    MaxBrakeForce = NewForce;
}
void AWheeledVehiclePawn::SetMaxSteerAngle(double NewAngle) {
    sp::checkSetting(std::isfinite(NewAngle) && NewAngle >= 0.0 && NewAngle <= 80.0, "AWheeledVehiclePawn",
                     "MaxSteerAngle", "in [0, 80] degrees", NewAngle);
    MaxSteerAngle = NewAngle;
}
void AWheeledVehiclePawn::SetWheelRadius(double NewRadius) {
    sp::checkSetting(std::isfinite(NewRadius) && NewRadius > 0.0, "AWheeledVehiclePawn", "WheelRadius", "> 0",
                     NewRadius);
    WheelRadius = NewRadius;
}
void AWheeledVehiclePawn::SetSuspensionStiffness(double NewStiffness) {
    sp::checkSetting(std::isfinite(NewStiffness) && NewStiffness > 0.0, "AWheeledVehiclePawn",
                     "SuspensionStiffness", "> 0", NewStiffness);
    SuspensionStiffness = NewStiffness;
}
void AWheeledVehiclePawn::SetTireFriction(double NewFriction) {
    sp::checkSetting(std::isfinite(NewFriction) && NewFriction >= 0.0, "AWheeledVehiclePawn", "TireFriction",
                     ">= 0", NewFriction);
    TireFriction = NewFriction;
}

sp::physics::VehicleDesc AWheeledVehiclePawn::describe() const {
    // Wheels sit under the chassis' corners; their connection points are just inside its bottom face, so
    // a wheel's ray never hits its own chassis.
    const Eigen::Vector3d half = Mesh->GetComponentScale().toEigen() / 2.0;
    sp::physics::VehicleDesc desc;
    for (int i = 0; i < 4; ++i) {
        const bool front = i < 2, left = i % 2 == 0;
        desc.wheels.push_back(
            {Eigen::Vector3d((front ? 0.62 : -0.62) * half.x(),
                             (left ? 1.0 : -1.0) * std::max(half.y() - kWheelWidth / 2, 0.0),
                             -half.z() + 0.05),
             WheelRadius, front});
    }
    desc.suspensionRestLength = 0.3;
    desc.suspensionStiffness = SuspensionStiffness;
    // Damping a little below critical (which is 2 sqrt(4 k) / 4 per kilogram and wheel for four wheels).
    desc.suspensionCompressionDamping = 0.8 * std::sqrt(SuspensionStiffness);
    desc.suspensionRelaxationDamping = 1.2 * std::sqrt(SuspensionStiffness);
    desc.maxSuspensionTravel = 0.25;
    desc.frictionSlip = TireFriction;
    return desc;
}

sp::physics::BodyId AWheeledVehiclePawn::vehicleBody(const char* function) {
    auto& physics = GetWorld()->GetSubsystem<sp::world::PhysicsSubsystem>();
    const sp::physics::BodyId body = physics.syncComponent(*Mesh, function);
    sp::physics::PhysicsWorld& world = physics.GetPhysicsWorld();
    if (!body.isSet() || !world.isSimulatingPhysics(body))
        return body_ = {};
    const sp::physics::VehicleDesc desc = describe();
    // The body is new when the chassis was rebuilt (its size changed), and then has no vehicle yet.
    if (!(body == body_) || !world.hasVehicle(body) || !(desc == desc_)) {
        world.setVehicle(body, desc);
        body_ = body;
        desc_ = desc;
    }
    return body_;
}

void AWheeledVehiclePawn::BeginPlay() {
    APawn::BeginPlay();
    // The wheel meshes keep what construction or a scene file gave them until the first step (a scene
    // loads and saves unchanged).
    GetWorld()->GetSubsystem<sp::world::PhysicsHooks>().add(*this);
}

void AWheeledVehiclePawn::EndPlay() {
    if (auto* subsystem = GetWorld()->FindSubsystem<sp::world::PhysicsHooks>())
        subsystem->remove(*this);
    body_ = {};
    APawn::EndPlay();
}

void AWheeledVehiclePawn::Tick(double deltaSeconds) {
    APawn::Tick(deltaSeconds);
    if (const AController* controller = GetController(); controller && controller->DrivesPawnDirectly())
        return; // its controller sets the controls once every actor has ticked
    const auto axis = [this](const char* action) { return InputComponent->GetActionValue(action).X; };
    ApplyControls(axis("Throttle"), axis("Steer"), axis("Brake"), axis("Handbrake"));
}

void AWheeledVehiclePawn::ApplyControls(double throttle, double steer, double brake, double handbrake) {
    const sp::physics::BodyId body = vehicleBody("AWheeledVehiclePawn.Tick");
    if (!body.isSet())
        return; // a chassis that does not simulate does not drive
    const auto clamped = [](double value, double low) {
        return std::isfinite(value) ? std::clamp(value, low, 1.0) : 0.0;
    };
    throttle = clamped(throttle, -1.0);
    steer = clamped(steer, -1.0);
    brake = clamped(brake, 0.0);
    handbrake = clamped(handbrake, 0.0);
    sp::physics::PhysicsWorld& world =
        GetWorld()->GetSubsystem<sp::world::PhysicsSubsystem>().GetPhysicsWorld();
    for (int i = 0; i < 4; ++i) {
        const bool rear = i >= 2;
        sp::physics::WheelControls controls;
        controls.engineForce = rear ? throttle * MaxEngineForce / 2.0 : 0.0;
        controls.brakeForce = std::max(brake, rear ? handbrake : 0.0) * MaxBrakeForce;
        controls.steering = steer * MaxSteerAngle / kDegrees;
        world.setWheelControls(body, i, controls);
    }
}

double AWheeledVehiclePawn::GetForwardSpeed() const {
    auto* self = const_cast<AWheeledVehiclePawn*>(this); // syncing the body does not change the car
    auto& physics = self->GetWorld()->GetSubsystem<sp::world::PhysicsSubsystem>();
    const sp::physics::BodyId body = physics.syncComponent(*Mesh, "GetForwardSpeed");
    if (!body.isSet())
        return 0.0;
    return physics.GetPhysicsWorld().getLinearVelocity(body).dot(Mesh->GetForwardVector().toEigen());
}

FWheelState AWheeledVehiclePawn::GetWheelState(int WheelIndex) const {
    SP_CHECK(WheelIndex >= 0 && WheelIndex < GetNumWheels(), sp::InvalidArgument,
             "AWheeledVehiclePawn.GetWheelState(): WheelIndex ", WheelIndex, " is out of range [0, ",
             GetNumWheels(), ")");
    FWheelState state;
    const sp::physics::BodyId body = const_cast<AWheeledVehiclePawn*>(this)->vehicleBody("GetWheelState");
    if (!body.isSet()) { // not simulated: the wheels hang at rest under the chassis
        state.Location = Wheels[std::size_t(WheelIndex)]->GetComponentLocation();
        state.SuspensionLength = describe().suspensionRestLength;
        return state;
    }
    const sp::physics::WheelState wheel =
        GetWorld()->GetSubsystem<sp::world::PhysicsSubsystem>().GetPhysicsWorld().getWheelState(body,
                                                                                                WheelIndex);
    state.bInContact = wheel.inContact;
    state.Location = FVector::fromEigen(wheel.pose.translation());
    state.ContactPoint = FVector::fromEigen(wheel.contactPoint);
    state.SuspensionLength = wheel.suspensionLength;
    state.RotationInDegrees = wheel.rotation * kDegrees;
    state.SteerAngleInDegrees = wheel.steering * kDegrees;
    return state;
}

void AWheeledVehiclePawn::PostPhysicsTick() {
    // The wheel meshes follow the simulated wheels.
    auto* physics = GetWorld()->FindSubsystem<sp::world::PhysicsSubsystem>();
    placeWheelMeshes(physics && body_.isSet() && physics->GetPhysicsWorld().isValid(body_) &&
                             physics->GetPhysicsWorld().hasVehicle(body_)
                         ? &physics->GetPhysicsWorld()
                         : nullptr);
}

void AWheeledVehiclePawn::placeWheelMeshes(const sp::physics::PhysicsWorld* physics) {
    const FTransform chassis = Mesh->GetComponentTransform();
    // The cylinder mesh's axis is its Z: turned onto the wheel's axle (Y).
    const Eigen::Isometry3d toAxle(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
    const Eigen::Vector3d scale(2.0 * WheelRadius, 2.0 * WheelRadius, kWheelWidth);
    const sp::physics::VehicleDesc rest = describe();
    for (std::size_t i = 0; i < Wheels.size(); ++i) {
        Eigen::Isometry3d pose;
        if (physics) {
            pose = physics->getWheelState(body_, int(i)).pose;
        } else { // at rest under the chassis
            Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
            local.translation() =
                rest.wheels[i].connectionPoint - Eigen::Vector3d::UnitZ() * rest.suspensionRestLength;
            pose = chassis.toIsometry() * local;
        }
        const FTransform world = transformOf(pose * toAxle, scale);
        Wheels[i]->SetRelativeTransform(world.relativeTo(chassis));
    }
}
