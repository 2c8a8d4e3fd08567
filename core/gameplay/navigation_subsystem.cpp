#include "core/gameplay/navigation_subsystem.h"

#include "core/gameplay/navigation_system.h"
#include "core/gameplay/pawn.h"
#include "core/reflect/object_base.h"
#include "core/world/physics_subsystem.h"
#include "core/world/world.h"

namespace sp::gameplay {

namespace {

// Space left around geometry when the region comes from it rather than from bounds volumes.
constexpr double kRegionMargin = 0.1;

} // namespace

NavigationSubsystem::NavigationSubsystem(UWorld& world) : world_(world), system_(new UNavigationSystemV1()) {
    system_->InitObject("NavigationSystem", &world);
}

NavigationSubsystem::~NavigationSubsystem() {
    reflect::ObjectTable::rememberName(*system_);
}

const NavigationSubsystem::Snapshot& NavigationSubsystem::snapshot() {
    world::PhysicsSubsystem& physics = world_.GetSubsystem<world::PhysicsSubsystem>();
    physics.syncAll();
    const physics::PhysicsWorld& bodies = physics.GetPhysicsWorld();

    std::map<physics::BodyId, Cached> current;
    bool changed = false;
    for (const auto& [component, body] : physics.componentBodies()) {
        if (!body.isSet() || !component->bCanEverAffectNavigation || bodies.isOverlapOnly(body) ||
            bodies.isSimulatingPhysics(body) || dynamic_cast<const APawn*>(component->GetOwner()))
            continue;
        const Eigen::Isometry3d pose = bodies.getPose(body);
        if (auto it = cache_.find(body); it != cache_.end() && it->second.pose.isApprox(pose, 0.0)) {
            current.emplace(body, std::move(it->second));
            continue;
        }
        changed = true;
        Cached cached;
        cached.pose = pose;
        const physics::Shape& shape = bodies.getShape(body);
        cached.plane = shape.type() == physics::ShapeType::Plane;
        if (!cached.plane) {
            physics::appendTriangles(shape, pose, Eigen::AlignedBox3d(), cached.soup);
            cached.bounds = cached.soup.bounds();
        }
        current.emplace(body, std::move(cached));
    }
    changed = changed || current.size() != cache_.size();
    cache_ = std::move(current);

    // The region: the bounds volumes, else the finite geometry.
    Eigen::AlignedBox3d region;
    for (AActor* actor : world_.find_actors_by_class(&ANavMeshBoundsVolume::StaticClass()))
        region.extend(static_cast<ANavMeshBoundsVolume*>(actor)->worldBounds());
    if (region.isEmpty()) {
        for (const auto& [body, cached] : cache_)
            if (!cached.plane)
                region.extend(cached.bounds);
        if (!region.isEmpty()) {
            region.min().array() -= kRegionMargin;
            region.max().array() += kRegionMargin;
        }
    }
    if (taken_ && !changed && sameRegion(region, snapshot_.region))
        return snapshot_;
    taken_ = true;

    snapshot_ = Snapshot{};
    snapshot_.region = region;
    for (const auto& [body, cached] : cache_) {
        if (cached.plane) {
            physics::TriangleSoup square;
            physics::appendTriangles(bodies.getShape(body), cached.pose, region, square);
            snapshot_.soup.append(square);
            snapshot_.bodies.emplace(body, Placed{cached.pose, square.bounds()});
        } else {
            snapshot_.soup.append(cached.soup);
            snapshot_.bodies.emplace(body, Placed{cached.pose, cached.bounds});
        }
    }
    return snapshot_;
}

} // namespace sp::gameplay
