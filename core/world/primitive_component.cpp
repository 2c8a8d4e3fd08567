#include "core/world/primitive_component.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/base/error.h"
#include "core/world/actor.h"
#include "core/world/physics_subsystem.h"
#include "core/world/world.h"

namespace {
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

bool isInPlay(const UPrimitiveComponent& component) {
    const AActor* owner = component.GetOwner();
    return owner && owner->HasBegunPlay() && component.GetWorld();
}
} // namespace

Eigen::AlignedBox3d UPrimitiveComponent::GetWorldBounds() const {
    const Eigen::AlignedBox3d local = GetLocalBounds();
    Eigen::AlignedBox3d world;
    if (local.isEmpty())
        return world;
    const FTransform transform = GetComponentTransform();
    const Eigen::Isometry3d pose = transform.toIsometry();
    const Eigen::Vector3d scale = transform.Scale3D.toEigen();
    for (int corner = 0; corner < 8; ++corner)
        world.extend(pose * local.corner(Eigen::AlignedBox3d::CornerType(corner)).cwiseProduct(scale));
    return world;
}

void UPrimitiveComponent::GetBounds(FVector& Origin, FVector& BoxExtent) const {
    const Eigen::AlignedBox3d bounds = GetWorldBounds();
    Origin = bounds.isEmpty() ? GetComponentLocation() : FVector::fromEigen(bounds.center());
    BoxExtent = bounds.isEmpty() ? FVector{} : FVector::fromEigen(bounds.sizes() / 2.0);
}

void UPrimitiveComponent::BeginPlay() {
    USceneComponent::BeginPlay();
    // The world's physics exists from the first primitive on; the world then registers this component with
    // it, as with every subsystem, once BeginPlay returns (and unregisters it before EndPlay).
    if (UWorld* world = GetWorld())
        world->GetSubsystem<sp::world::PhysicsSubsystem>();
}

void UPrimitiveComponent::SetSimulatePhysics(bool bSimulate) {
    if (bSimulate && isInPlay(*this)) {
        SP_CHECK(Mobility == EComponentMobility::Movable, sp::InvalidState,
                 "UPrimitiveComponent.SetSimulatePhysics(): ", GetDebugName(),
                 " is not Movable; set its Mobility to Movable first");
        SP_CHECK(MassInKg > 0.0, sp::InvalidState,
                 "UPrimitiveComponent.SetSimulatePhysics(): ", GetDebugName(), " has mass ", MassInKg,
                 " kg; set MassInKg > 0 first");
        const sp::physics::BodyId body = sp::world::PhysicsSubsystem::of(*this, "SetSimulatePhysics")
                                             .syncComponent(*this, "SetSimulatePhysics");
        SP_CHECK(body.isSet(), sp::InvalidState, "UPrimitiveComponent.SetSimulatePhysics(): ", GetDebugName(),
                 " has no collision (no mesh, or CollisionPrimitive is NoCollision)");
        const ECollisionPrimitive primitive = CollisionPrimitive == ECollisionPrimitive::FromMesh
                                                  ? GetMeshCollisionPrimitive()
                                                  : CollisionPrimitive;
        SP_CHECK(primitive != ECollisionPrimitive::Plane, sp::InvalidState,
                 "UPrimitiveComponent.SetSimulatePhysics(): ", GetDebugName(),
                 " collides as a plane, which cannot be simulated; set CollisionPrimitive to Box");
    }
    bSimulatePhysics = bSimulate;
}

bool UPrimitiveComponent::IsSimulatingPhysics() const {
    if (!isInPlay(*this))
        return false;
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "IsSimulatingPhysics");
    const sp::physics::BodyId body = physics.syncComponent(*this, "IsSimulatingPhysics");
    return body.isSet() && physics.GetPhysicsWorld().isSimulatingPhysics(body);
}

void UPrimitiveComponent::SetMassOverrideInKg(double NewMassInKg) {
    SP_CHECK(std::isfinite(NewMassInKg) && NewMassInKg > 0.0, sp::InvalidArgument,
             "UPrimitiveComponent.SetMassOverrideInKg(): MassInKg ", NewMassInKg, " must be > 0");
    MassInKg = NewMassInKg;
}

// Physics reads these values at every step; one out of range (NaN, a negative friction) would poison the
// simulation frames later, far from the call that set it: they are checked here, when set.
namespace {
bool unit(double value) {
    return value >= 0.0 && value <= 1.0; // false for NaN
}
} // namespace

void UPrimitiveComponent::SetFriction(double NewFriction) {
    sp::checkSetting(std::isfinite(NewFriction) && NewFriction >= 0.0, "UPrimitiveComponent", "Friction",
                     "finite and >= 0", NewFriction);
    Friction = NewFriction;
}
void UPrimitiveComponent::SetRestitution(double NewRestitution) {
    sp::checkSetting(unit(NewRestitution), "UPrimitiveComponent", "Restitution", "in [0, 1]", NewRestitution);
    Restitution = NewRestitution;
}
void UPrimitiveComponent::SetLinearDamping(double NewLinearDamping) {
    sp::checkSetting(unit(NewLinearDamping), "UPrimitiveComponent", "LinearDamping", "in [0, 1]",
                     NewLinearDamping);
    LinearDamping = NewLinearDamping;
}
void UPrimitiveComponent::SetAngularDamping(double NewAngularDamping) {
    sp::checkSetting(unit(NewAngularDamping), "UPrimitiveComponent", "AngularDamping", "in [0, 1]",
                     NewAngularDamping);
    AngularDamping = NewAngularDamping;
}

void UPrimitiveComponent::AddForce(const FVector& Force, bool bAccelChange) {
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "AddForce");
    const sp::physics::BodyId body = physics.requireSimulatedBody(*this, "AddForce");
    physics.GetPhysicsWorld().applyForce(body, Force.toEigen() * (bAccelChange ? MassInKg : 1.0));
}

void UPrimitiveComponent::AddTorqueInRadians(const FVector& Torque) {
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "AddTorqueInRadians");
    physics.GetPhysicsWorld().applyTorque(physics.requireSimulatedBody(*this, "AddTorqueInRadians"),
                                          Torque.toEigen());
}

void UPrimitiveComponent::AddImpulse(const FVector& Impulse, bool bVelChange) {
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "AddImpulse");
    const sp::physics::BodyId body = physics.requireSimulatedBody(*this, "AddImpulse");
    physics.GetPhysicsWorld().applyImpulse(body, Impulse.toEigen() * (bVelChange ? MassInKg : 1.0));
}

void UPrimitiveComponent::SetPhysicsLinearVelocity(const FVector& NewVel, bool bAddToCurrent) {
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "SetPhysicsLinearVelocity");
    const sp::physics::BodyId body = physics.requireSimulatedBody(*this, "SetPhysicsLinearVelocity");
    auto& world = physics.GetPhysicsWorld();
    world.setLinearVelocity(
        body, NewVel.toEigen() + (bAddToCurrent ? world.getLinearVelocity(body) : Eigen::Vector3d::Zero()));
}

FVector UPrimitiveComponent::GetPhysicsLinearVelocity() const {
    if (!isInPlay(*this))
        return {};
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "GetPhysicsLinearVelocity");
    const sp::physics::BodyId body = physics.syncComponent(*this, "GetPhysicsLinearVelocity");
    return body.isSet() ? FVector::fromEigen(physics.GetPhysicsWorld().getLinearVelocity(body)) : FVector{};
}

void UPrimitiveComponent::SetPhysicsAngularVelocityInDegrees(const FVector& NewAngVel, bool bAddToCurrent) {
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "SetPhysicsAngularVelocityInDegrees");
    const sp::physics::BodyId body =
        physics.requireSimulatedBody(*this, "SetPhysicsAngularVelocityInDegrees");
    auto& world = physics.GetPhysicsWorld();
    world.setAngularVelocity(body,
                             NewAngVel.toEigen() / kDegreesPerRadian +
                                 (bAddToCurrent ? world.getAngularVelocity(body) : Eigen::Vector3d::Zero()));
}

FVector UPrimitiveComponent::GetPhysicsAngularVelocityInDegrees() const {
    if (!isInPlay(*this))
        return {};
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "GetPhysicsAngularVelocityInDegrees");
    const sp::physics::BodyId body = physics.syncComponent(*this, "GetPhysicsAngularVelocityInDegrees");
    return body.isSet()
               ? FVector::fromEigen(physics.GetPhysicsWorld().getAngularVelocity(body) * kDegreesPerRadian)
               : FVector{};
}

bool UPrimitiveComponent::IsAnyRigidBodyAwake() const {
    if (!isInPlay(*this))
        return false;
    auto& physics = sp::world::PhysicsSubsystem::of(*this, "IsAnyRigidBodyAwake");
    const sp::physics::BodyId body = physics.syncComponent(*this, "IsAnyRigidBodyAwake");
    return body.isSet() && physics.GetPhysicsWorld().isAwake(body);
}

std::vector<UPrimitiveComponent*> UPrimitiveComponent::GetOverlappingComponents() const {
    constexpr const char* kFunction = "GetOverlappingComponents";
    return sp::world::PhysicsSubsystem::of(*this, kFunction).overlappingComponents(*this, kFunction);
}

std::vector<AActor*> UPrimitiveComponent::GetOverlappingActors(TSubclassOf<AActor> ClassFilter) const {
    SP_CHECK(ClassFilter, sp::InvalidArgument,
             "UPrimitiveComponent.GetOverlappingActors(): ClassFilter is None (pass AActor for every actor)");
    std::vector<AActor*> actors;
    for (const UPrimitiveComponent* component : GetOverlappingComponents()) {
        AActor* owner = component->GetOwner();
        if (owner && owner->IsA(*ClassFilter.Get()) &&
            std::find(actors.begin(), actors.end(), owner) == actors.end())
            actors.push_back(owner);
    }
    return actors;
}

bool UPrimitiveComponent::IsOverlappingComponent(const UPrimitiveComponent* OtherComp) const {
    SP_CHECK(OtherComp, sp::InvalidArgument,
             "UPrimitiveComponent.IsOverlappingComponent(): OtherComp is None");
    const std::vector<UPrimitiveComponent*> overlapping = GetOverlappingComponents();
    return std::find(overlapping.begin(), overlapping.end(), OtherComp) != overlapping.end();
}

bool UPrimitiveComponent::IsOverlappingActor(const AActor* Other) const {
    SP_CHECK(Other, sp::InvalidArgument, "UPrimitiveComponent.IsOverlappingActor(): Other is None");
    const std::vector<UPrimitiveComponent*> overlapping = GetOverlappingComponents();
    return std::any_of(overlapping.begin(), overlapping.end(),
                       [&](const UPrimitiveComponent* component) { return component->GetOwner() == Other; });
}

std::vector<UPrimitiveComponent*> UPrimitiveComponent::GetBeginOverlaps() const {
    return sp::world::PhysicsSubsystem::of(*this, "GetBeginOverlaps")
        .beganOverlaps(*this, "GetBeginOverlaps");
}

std::vector<UPrimitiveComponent*> UPrimitiveComponent::GetEndOverlaps() const {
    return sp::world::PhysicsSubsystem::of(*this, "GetEndOverlaps").endedOverlaps(*this, "GetEndOverlaps");
}

void sp::world::setMaterialSlot(std::vector<std::string>& materials, int index, const std::string& material,
                                const char* function) {
    SP_CHECK(index >= 0 && index < 256, sp::InvalidArgument, function, ": ElementIndex ", index,
             " is out of range [0, 256)");
    if (materials.size() <= size_t(index))
        materials.resize(size_t(index) + 1);
    materials[size_t(index)] = material;
}
