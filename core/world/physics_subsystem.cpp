#include "core/world/physics_subsystem.h"

#include <algorithm>

#include "core/base/error.h"
#include "core/reflect/object_base.h"
#include "core/world/actor.h"
#include "core/world/mesh_geometry.h"
#include "core/world/physics_hooks.h"
#include "core/world/static_mesh_component.h"
#include "core/world/world.h"

namespace sp::world {

namespace {

// Bodies carry their component's object handle as their tag, so a raycast hit maps back to the
// component through the generation-checked object table (never a raw pointer).
uint64_t tagOf(const UPrimitiveComponent& component) {
    const reflect::ObjectHandle handle = component.GetHandle();
    return (uint64_t(handle.index) << 32) | handle.generation;
}

UPrimitiveComponent* componentOfTag(uint64_t tag) {
    const reflect::ObjectHandle handle{uint32_t(tag >> 32), uint32_t(tag & 0xffffffffu)};
    return dynamic_cast<UPrimitiveComponent*>(reflect::ObjectTable::find(handle));
}

// Thin shapes (a flat cylinder, a flat mesh's bounds as a box) get this half thickness instead of zero.
constexpr double kMinHalfExtent = 1e-3;
// A Plane collides as a slab this thick under its face, in metres whatever the scale: box-box and
// sphere-box contacts are exact and several times cheaper than a triangle's, and a slab is harder to tunnel
// through. Its back face stands this far behind the plane.
constexpr double kPlaneSlabThickness = 0.01;

physics::Shape makeShape(ECollisionPrimitive primitive, const Eigen::Vector3d& halfExtents,
                         const Eigen::Vector3d& scale, const std::string& mesh) {
    const Eigen::Vector3d he = halfExtents.cwiseMax(kMinHalfExtent);
    switch (primitive) {
    case ECollisionPrimitive::ConvexHull:
        return physics::Shape::convexHull(loadMeshGeometry(mesh, "physics")->vertices).scaled(scale);
    case ECollisionPrimitive::TriangleMesh: {
        const auto geometry = loadMeshGeometry(mesh, "physics");
        return physics::Shape::triangleMesh(geometry->vertices, geometry->indices).scaled(scale);
    }
    case ECollisionPrimitive::Sphere:
        return physics::Shape::sphere(he.maxCoeff()).scaled(scale);
    case ECollisionPrimitive::Capsule: {
        const double radius = std::max(he.x(), he.y());
        return physics::Shape::capsule(radius, std::max(he.z() - radius, 0.0)).scaled(scale);
    }
    case ECollisionPrimitive::Cylinder:
        return physics::Shape::cylinder(std::max(he.x(), he.y()), he.z()).scaled(scale);
    case ECollisionPrimitive::Plane: {
        const double half = 0.5 * kPlaneSlabThickness / scale.z(); // before the scale, which is applied after
        return physics::Shape::box({he.x(), he.y(), half}, {0.0, 0.0, -half}).scaled(scale);
    }
    default:
        return physics::Shape::box(he).scaled(scale);
    }
}

bool isMovable(const UPrimitiveComponent& component) {
    return component.Mobility == EComponentMobility::Movable;
}

// Whether the body should be dynamic. Settings that cannot be simulated (a static component, a plane,
// no mass) leave the body kinematic here; SetSimulatePhysics() reports them as errors instead.
bool wantsSimulation(const UPrimitiveComponent& component, ECollisionPrimitive primitive) {
    return component.bSimulatePhysics && isMovable(component) && primitive != ECollisionPrimitive::Plane &&
           primitive != ECollisionPrimitive::TriangleMesh && primitive != ECollisionPrimitive::NoCollision &&
           component.MassInKg > 0.0;
}

} // namespace

PhysicsSubsystem::PhysicsSubsystem(UWorld& world) : world_(world) {}

PhysicsSubsystem::~PhysicsSubsystem() = default;

void PhysicsSubsystem::OnComponentBeginPlay(UActorComponent& played) {
    auto* primitive = dynamic_cast<UPrimitiveComponent*>(&played);
    if (primitive)
        registerComponent(*primitive);
}

void PhysicsSubsystem::OnComponentEndPlay(UActorComponent& played) {
    auto* primitive = dynamic_cast<UPrimitiveComponent*>(&played);
    if (primitive)
        unregisterComponent(*primitive);
}

void PhysicsSubsystem::registerComponent(UPrimitiveComponent& component) {
    if (index_.contains(&component))
        return;
    index_.emplace(&component, entries_.size());
    Entry entry;
    entry.component = &component;
    entries_.push_back(std::move(entry));
    syncEntry(entries_.back());
}

void PhysicsSubsystem::unregisterComponent(UPrimitiveComponent& component) {
    auto it = index_.find(&component);
    if (it == index_.end())
        return;
    const size_t position = it->second;
    if (entries_[position].body.isSet())
        physicsWorld_.removeBody(entries_[position].body);
    entries_.erase(entries_.begin() + std::ptrdiff_t(position));
    index_.erase(it);
    for (auto& [key, value] : index_)
        if (value > position)
            --value;
}

bool PhysicsSubsystem::isRegistered(const UPrimitiveComponent& component) const {
    return index_.contains(&component);
}

PhysicsSubsystem& PhysicsSubsystem::of(const UPrimitiveComponent& component, const char* function) {
    UWorld* world = component.GetWorld();
    PhysicsSubsystem* physics = world ? world->FindSubsystem<PhysicsSubsystem>() : nullptr;
    SP_CHECK(physics && physics->isRegistered(component), InvalidState, "UPrimitiveComponent.", function,
             "(): ", component.GetDebugName(),
             " is not in play (its actor has not begun play or has ended it)");
    return *physics;
}

PhysicsSubsystem::Entry& PhysicsSubsystem::entryFor(const UPrimitiveComponent& component,
                                                    const char* function) {
    auto it = index_.find(&component);
    SP_CHECK(it != index_.end(), InvalidState, "UPrimitiveComponent.", function,
             "(): ", component.GetDebugName(),
             " is not in play (its actor has not begun play or has ended it)");
    return entries_[it->second];
}

physics::BodyId PhysicsSubsystem::syncComponent(const UPrimitiveComponent& component, const char* function) {
    Entry& entry = entryFor(component, function);
    syncEntry(entry);
    return entry.body;
}

physics::BodyId PhysicsSubsystem::requireSimulatedBody(const UPrimitiveComponent& component,
                                                       const char* function) {
    const physics::BodyId body = syncComponent(component, function);
    SP_CHECK(body.isSet() && physicsWorld_.isSimulatingPhysics(body), InvalidState, "UPrimitiveComponent.",
             function, "(): ", component.GetDebugName(),
             " is not simulating physics; call SetSimulatePhysics(bSimulate=True) first");
    return body;
}

std::vector<std::pair<UPrimitiveComponent*, physics::BodyId>> PhysicsSubsystem::componentBodies() const {
    std::vector<std::pair<UPrimitiveComponent*, physics::BodyId>> bodies;
    bodies.reserve(entries_.size());
    for (const Entry& entry : entries_)
        bodies.emplace_back(entry.component, entry.body);
    return bodies;
}

void PhysicsSubsystem::syncAll() {
    for (Entry& entry : entries_)
        syncEntry(entry);
}

void PhysicsSubsystem::syncEntry(Entry& entry) {
    const UPrimitiveComponent& component = *entry.component;
    ShapeKey key;
    const Eigen::AlignedBox3d bounds = component.GetLocalBounds();
    key.primitive = component.CollisionPrimitive == ECollisionPrimitive::FromMesh
                        ? component.GetMeshCollisionPrimitive()
                        : component.CollisionPrimitive;
    if (bounds.isEmpty())
        key.primitive = ECollisionPrimitive::NoCollision;
    if (key.primitive != ECollisionPrimitive::NoCollision) {
        key.halfExtents = bounds.sizes() / 2.0;
        key.scale = component.GetComponentScale().toEigen();
        key.isStatic = !isMovable(component);
        if (key.primitive == ECollisionPrimitive::ConvexHull ||
            key.primitive == ECollisionPrimitive::TriangleMesh)
            if (const auto* mesh = dynamic_cast<const UStaticMeshComponent*>(&component))
                key.mesh = mesh->GetMeshAsset();
    }
    const FTransform transform = component.GetComponentTransform();
    // A static body is rebuilt rather than moved: only an attach parent moving can move it in play.
    if (!(key == entry.shape) || (key.isStatic && !(transform == entry.syncedTransform))) {
        rebuildBody(entry, key);
        return;
    }
    if (!entry.body.isSet())
        return;
    syncProperties(entry);
    if (!(transform == entry.syncedTransform)) {
        physicsWorld_.setPose(entry.body, transform.toIsometry());
        entry.syncedTransform = transform;
    }
}

void PhysicsSubsystem::rebuildBody(Entry& entry, const ShapeKey& key) {
    const UPrimitiveComponent& component = *entry.component;
    if (entry.body.isSet())
        physicsWorld_.removeBody(entry.body);
    entry.body = {};
    entry.shape = key;
    entry.syncedTransform = component.GetComponentTransform();
    if (key.primitive == ECollisionPrimitive::NoCollision)
        return;
    try {
        physics::BodyDesc desc;
        desc.shape = makeShape(key.primitive, key.halfExtents, key.scale, key.mesh);
        desc.pose = entry.syncedTransform.toIsometry();
        desc.mobility = key.isStatic ? physics::Mobility::Static : physics::Mobility::Movable;
        desc.simulatePhysics = wantsSimulation(component, key.primitive);
        desc.mass = std::max(component.MassInKg, 0.0);
        desc.friction = component.Friction;
        desc.restitution = component.Restitution;
        desc.linearDamping = component.LinearDamping;
        desc.angularDamping = component.AngularDamping;
        desc.tag = tagOf(component);
        desc.overlapOnly = component.IsOverlapOnly();
        entry.body = physicsWorld_.addBody(desc);
    } catch (const NotFound& error) { // a mesh file that is not there: retried and reported each sync
        entry.shape = ShapeKey{};
        entry.shape.primitive = ECollisionPrimitive::FromMesh;
        SP_THROW(NotFound, "physics of ", component.GetDebugName(), ": ", error.what());
    } catch (const InvalidArgument& error) {
        // Forget the shape so that the next sync retries (and reports) once the settings are fixed.
        entry.shape = ShapeKey{};
        entry.shape.primitive = ECollisionPrimitive::FromMesh;
        SP_THROW(InvalidArgument, "physics of ", component.GetDebugName(), ": ", error.what());
    }
}

void PhysicsSubsystem::syncProperties(Entry& entry) {
    const UPrimitiveComponent& component = *entry.component;
    const physics::BodyId id = entry.body;
    try {
        if (!entry.shape.isStatic) {
            const bool simulate = wantsSimulation(component, entry.shape.primitive);
            const bool simulating = physicsWorld_.isSimulatingPhysics(id);
            if (simulating && !simulate)
                physicsWorld_.setSimulatePhysics(id, false);
            if (component.MassInKg != physicsWorld_.getMass(id) && component.MassInKg >= 0.0 &&
                (component.MassInKg > 0.0 || !simulate))
                physicsWorld_.setMass(id, component.MassInKg);
            if (simulate && !simulating)
                physicsWorld_.setSimulatePhysics(id, true);
            if (component.LinearDamping != physicsWorld_.getLinearDamping(id))
                physicsWorld_.setLinearDamping(id, component.LinearDamping);
            if (component.AngularDamping != physicsWorld_.getAngularDamping(id))
                physicsWorld_.setAngularDamping(id, component.AngularDamping);
        }
        if (component.Friction != physicsWorld_.getFriction(id))
            physicsWorld_.setFriction(id, component.Friction);
        if (component.Restitution != physicsWorld_.getRestitution(id))
            physicsWorld_.setRestitution(id, component.Restitution);
    } catch (const InvalidArgument& error) {
        SP_THROW(InvalidArgument, "physics of ", component.GetDebugName(), ": ", error.what());
    }
}

void PhysicsSubsystem::writeBack() {
    for (Entry& entry : entries_) {
        if (!entry.body.isSet() || !physicsWorld_.isSimulatingPhysics(entry.body))
            continue;
        const Eigen::Isometry3d pose = physicsWorld_.getPose(entry.body);
        FTransform transform = entry.component->GetComponentTransform();
        transform.Translation = FVector::fromEigen(pose.translation());
        transform.Rotation = FQuat::fromEigen(Eigen::Quaterniond(pose.linear()));
        entry.component->SetWorldTransform(transform);
        // What the component now reports (the rotation went through FRotator), so that the next sync
        // sees no change and leaves the body alone.
        entry.syncedTransform = entry.component->GetComponentTransform();
    }
}

void PhysicsSubsystem::Tick(double /*deltaSeconds*/) {
    if (PhysicsHooks* hooks = world_.FindSubsystem<PhysicsHooks>())
        hooks->beforeStep();
    syncAll();
}

void PhysicsSubsystem::StepConcurrently(double deltaSeconds) {
    physicsWorld_.step(deltaSeconds);
}

void PhysicsSubsystem::FinishTick(double /*deltaSeconds*/) {
    writeBack();
    PhysicsHooks* hooks = world_.FindSubsystem<PhysicsHooks>();
    if (hooks && hooks->afterStep())
        syncAll(); // a character's capsule moved: its sensor body follows before overlaps are found
    updateOverlapEvents();
}

std::vector<UPrimitiveComponent*> PhysicsSubsystem::currentOverlaps(const Entry& entry) {
    std::vector<UPrimitiveComponent*> found;
    if (!entry.component->bGenerateOverlapEvents || !entry.body.isSet())
        return found;
    for (const physics::BodyId other : physicsWorld_.overlaps(entry.body)) {
        UPrimitiveComponent* component = componentOfTag(physicsWorld_.getTag(other));
        if (component && component->bGenerateOverlapEvents &&
            component->GetOwner() != entry.component->GetOwner())
            found.push_back(component);
    }
    // In the order the components entered play, as the rest of the subsystem keeps them.
    std::sort(found.begin(), found.end(), [&](const UPrimitiveComponent* a, const UPrimitiveComponent* b) {
        return index_.at(a) < index_.at(b);
    });
    return found;
}

void PhysicsSubsystem::updateOverlapEvents() {
    for (Entry& entry : entries_) {
        std::vector<reflect::ObjectHandle> now;
        for (const UPrimitiveComponent* component : currentOverlaps(entry))
            now.push_back(component->GetHandle());
        const auto missingFrom = [](const std::vector<reflect::ObjectHandle>& from,
                                    const std::vector<reflect::ObjectHandle>& handles) {
            std::vector<reflect::ObjectHandle> missing;
            for (const reflect::ObjectHandle& handle : handles)
                if (std::find(from.begin(), from.end(), handle) == from.end())
                    missing.push_back(handle);
            return missing;
        };
        entry.began = missingFrom(entry.overlapping, now);
        entry.ended = missingFrom(now, entry.overlapping);
        entry.overlapping = std::move(now);
    }
}

std::vector<UPrimitiveComponent*>
PhysicsSubsystem::overlappingComponents(const UPrimitiveComponent& component, const char* function) {
    Entry& entry = entryFor(component, function);
    syncAll();
    return currentOverlaps(entry);
}

namespace {

std::vector<UPrimitiveComponent*> liveComponents(const std::vector<reflect::ObjectHandle>& handles) {
    std::vector<UPrimitiveComponent*> components;
    for (const reflect::ObjectHandle& handle : handles)
        if (auto* component = dynamic_cast<UPrimitiveComponent*>(reflect::ObjectTable::find(handle)))
            components.push_back(component);
    return components;
}

} // namespace

std::vector<UPrimitiveComponent*> PhysicsSubsystem::beganOverlaps(const UPrimitiveComponent& component,
                                                                  const char* function) {
    return liveComponents(entryFor(component, function).began);
}

std::vector<UPrimitiveComponent*> PhysicsSubsystem::endedOverlaps(const UPrimitiveComponent& component,
                                                                  const char* function) {
    return liveComponents(entryFor(component, function).ended);
}

UPrimitiveComponent* PhysicsSubsystem::lineTrace(const FVector& start, const FVector& end, FHitResult& hit) {
    syncAll();
    hit = FHitResult{};
    hit.TraceStart = start;
    hit.TraceEnd = end;
    hit.Location = hit.ImpactPoint = end;
    hit.Distance = (end.toEigen() - start.toEigen()).norm();
    const std::optional<physics::RayHit> ray = physicsWorld_.raycast(start.toEigen(), end.toEigen());
    if (!ray)
        return nullptr;
    hit.bBlockingHit = true;
    hit.Location = hit.ImpactPoint = FVector::fromEigen(ray->point);
    hit.ImpactNormal = hit.Normal = FVector::fromEigen(ray->normal);
    hit.Time = ray->fraction;
    hit.Distance = ray->fraction * (end.toEigen() - start.toEigen()).norm();
    return componentOfTag(ray->tag);
}

} // namespace sp::world
