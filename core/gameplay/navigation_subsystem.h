#pragma once
// NavigationSubsystem: what the world's navigation data is built from. It owns the world's
// UNavigationSystemV1 and keeps the triangles of each navigation body: a colliding, unsimulated body (Static,
// or Movable and moved by code) that is not a sensor, whose component has bCanEverAffectNavigation and is
// not part of a pawn (pawns are navigation's agents, not its obstacles). Simulated bodies are left out: they
// would rebuild tiles every frame. A body is known by its id and pose; a body whose shape changes is rebuilt
// with a new id, so the two say exactly which geometry a mesh was built from.

#include <map>
#include <memory>

#include <Eigen/Geometry>

#include "core/physics/body_id.h"
#include "core/physics/triangles.h"
#include "core/world/world_subsystem.h"

class UNavigationSystemV1;
class UWorld;

namespace sp::gameplay {

class NavigationSubsystem : public world::WorldSubsystem {
  public:
    static constexpr int kTickOrder = world::tick_order::kPhysics + 50; // nothing to tick

    explicit NavigationSubsystem(UWorld& world);
    ~NavigationSubsystem() override;

    UNavigationSystemV1& navigationSystem() { return *system_; }

    struct Placed {
        Eigen::Isometry3d pose;
        Eigen::AlignedBox3d bounds;
    };
    struct Snapshot {
        physics::TriangleSoup soup;               // all of it, infinite planes cut to region
        std::map<physics::BodyId, Placed> bodies; // each body's pose and world box
        Eigen::AlignedBox3d region;               // empty: nothing to build over
    };
    // The navigation geometry as it is now (physics synced first).
    const Snapshot& snapshot();

    // Whether two regions are the same (two empty regions are: nothing to build over either way).
    static bool sameRegion(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
        return a.isEmpty() || b.isEmpty() ? a.isEmpty() == b.isEmpty() : a.isApprox(b);
    }

  private:
    struct Cached {
        physics::TriangleSoup soup; // empty for an infinite plane, cut to the region at each snapshot
        Eigen::Isometry3d pose;
        Eigen::AlignedBox3d bounds;
        bool plane = false;
    };

    UWorld& world_;
    std::unique_ptr<UNavigationSystemV1> system_;
    std::map<physics::BodyId, Cached> cache_;
    Snapshot snapshot_;
    bool taken_ = false;
};

} // namespace sp::gameplay
