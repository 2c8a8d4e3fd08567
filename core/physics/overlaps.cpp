// PhysicsWorld::overlaps (declared in physics_world.h): bounding boxes computed now give the candidates
// (the broadphase's are refreshed only at the start of a substep, so they trail a moving body), and
// Bullet's pair test of the two shapes decides.

#include "core/physics/detail/world_impl.h"

namespace sp::physics {

namespace {

// Whether a pair test found a point where the shapes touch or penetrate (Bullet also reports points a
// little apart, within its contact threshold).
struct Touching : btCollisionWorld::ContactResultCallback {
    bool touching = false;
    btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
        touching = touching || point.getDistance() <= 0.0;
        return 0;
    }
};

void boundsOf(const btCollisionObject& object, btVector3& low, btVector3& high) {
    object.getCollisionShape()->getAabb(object.getWorldTransform(), low, high);
}

} // namespace

std::vector<BodyId> PhysicsWorld::overlaps(BodyId id) const {
    Impl& w = *impl_;
    btCollisionObject* object = w.bodies.get(id, "PhysicsWorld::overlaps()").body.get();
    btVector3 low, high;
    boundsOf(*object, low, high);
    std::vector<BodyId> found; // slot order, so in id order
    w.bodies.forEach([&](BodyId other, detail::BodyRecord& record) {
        btVector3 otherLow, otherHigh;
        boundsOf(*record.body, otherLow, otherHigh);
        if (record.body.get() == object || !TestAabbAgainstAabb2(low, high, otherLow, otherHigh))
            return;
        Touching touching;
        w.world->contactPairTest(object, record.body.get(), touching);
        if (touching.touching)
            found.push_back(other);
    });
    return found;
}

} // namespace sp::physics
