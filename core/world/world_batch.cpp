// UWorld's batched services: many actors in one call, positions and forces as numpy arrays, for
// co-simulation and learning loops that move or push dozens of objects every frame.

#include <string>
#include <utility>
#include <vector>

#include "core/base/error.h"
#include "core/world/physics_subsystem.h"
#include "core/world/world.h"

sp::reflect::SpArray<double> UWorld::get_actor_locations(const std::vector<AActor*>& actors) const {
    sp::reflect::SpArray<double> locations("locations");
    locations.resize({int64_t(actors.size()), 3});
    double* out = locations.data();
    for (size_t i = 0; i < actors.size(); ++i) {
        SP_CHECK(actors[i], sp::InvalidArgument, "UWorld.get_actor_locations(): actors[", i, "] is None");
        const FVector location = actors[i]->GetActorLocation();
        out[3 * i + 0] = location.X;
        out[3 * i + 1] = location.Y;
        out[3 * i + 2] = location.Z;
    }
    return locations;
}

namespace {
// Checks that `rows` is (count, 3): one row per object.
void checkRows(const char* function, const char* name, const sp::reflect::SpArray<double>& rows,
               size_t count) {
    const auto& shape = rows.getShape();
    const bool matches = shape.size() == 2 && shape[0] == int64_t(count) && shape[1] == 3;
    if (!matches) {
        std::string got = "(";
        for (size_t i = 0; i < shape.size(); ++i)
            got += (i ? ", " : "") + std::to_string(shape[i]);
        got += shape.size() == 1 ? ",)" : ")";
        SP_THROW(sp::InvalidArgument, "UWorld.", function, "(): ", name, " must have shape (", count,
                 ", 3), got ", got);
    }
}
} // namespace

void UWorld::set_actor_locations(const std::vector<AActor*>& actors,
                                 const sp::reflect::SpArray<double>& locations) {
    checkRows("set_actor_locations", "locations", locations, actors.size());
    const double* rows = locations.data();
    for (size_t i = 0; i < actors.size(); ++i) {
        SP_CHECK(actors[i], sp::InvalidArgument, "UWorld.set_actor_locations(): actors[", i, "] is None");
        actors[i]->SetActorLocation({rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]});
    }
}

void UWorld::add_forces(const std::vector<UPrimitiveComponent*>& components,
                        const sp::reflect::SpArray<double>& forces, bool bAccelChange) {
    checkRows("add_forces", "forces", forces, components.size());
    // Every component's body first, then the forces: a component that cannot take one fails the call before
    // any other was pushed.
    std::vector<std::pair<sp::physics::PhysicsWorld*, sp::physics::BodyId>> bodies;
    bodies.reserve(components.size());
    for (size_t i = 0; i < components.size(); ++i) {
        SP_CHECK(components[i], sp::InvalidArgument, "UWorld.add_forces(): components[", i, "] is None");
        try {
            auto& physics = sp::world::PhysicsSubsystem::of(*components[i], "AddForce");
            bodies.emplace_back(&physics.GetPhysicsWorld(),
                                physics.requireSimulatedBody(*components[i], "AddForce"));
        } catch (const std::exception&) {
            sp::rethrowWithPrefix("UWorld.add_forces(): components[" + std::to_string(i) + "]: ");
        }
    }
    const double* rows = forces.data();
    for (size_t i = 0; i < components.size(); ++i) {
        const Eigen::Vector3d force(rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]);
        bodies[i].first->applyForce(bodies[i].second, force * (bAccelChange ? components[i]->MassInKg : 1.0));
    }
}
