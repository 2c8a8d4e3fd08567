// UWorld's batched services: many actors in one call, positions as numpy arrays, for co-simulation and
// learning loops that move dozens of objects every frame.

#include "core/base/error.h"
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

void UWorld::set_actor_locations(const std::vector<AActor*>& actors,
                                 const sp::reflect::SpArray<double>& locations) {
    const auto& shape = locations.getShape();
    const bool matches = shape.size() == 2 && shape[0] == int64_t(actors.size()) && shape[1] == 3;
    if (!matches) {
        std::string got = "(";
        for (size_t i = 0; i < shape.size(); ++i)
            got += (i ? ", " : "") + std::to_string(shape[i]);
        got += shape.size() == 1 ? ",)" : ")";
        SP_THROW(sp::InvalidArgument, "UWorld.set_actor_locations(): locations must have shape (",
                 actors.size(), ", 3), got ", got);
    }
    const double* rows = locations.data();
    for (size_t i = 0; i < actors.size(); ++i) {
        SP_CHECK(actors[i], sp::InvalidArgument, "UWorld.set_actor_locations(): actors[", i, "] is None");
        actors[i]->SetActorLocation({rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]});
    }
}
