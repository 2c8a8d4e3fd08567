// Overlap queries and sensors: overlaps() agrees with the analytic answer for boxes and spheres of any
// mobility; a sensor neither stops bodies nor rays.
#include <vector>

#include <gtest/gtest.h>

#include "core/physics/physics_world.h"
#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::addFloor;
using test::at;
using test::dynamicBody;
using test::run;

BodyId addSensor(PhysicsWorld& world, const Shape& shape, const Eigen::Isometry3d& pose, Mobility mobility) {
    BodyDesc desc;
    desc.shape = shape;
    desc.pose = pose;
    desc.mobility = mobility;
    desc.simulatePhysics = false;
    desc.overlapOnly = true;
    return world.addBody(desc);
}

BodyId addSphere(PhysicsWorld& world, double x, double y, double z, Mobility mobility) {
    BodyDesc desc;
    desc.shape = Shape::sphere(0.5);
    desc.pose = at(x, y, z);
    desc.mobility = mobility;
    desc.simulatePhysics = false;
    return world.addBody(desc);
}

TEST(OverlapsTest, BoxAndSphereOverlapsMatchTheGeometry) {
    PhysicsWorld world;
    // A 2 m cube sensor at the origin, turned 30 degrees about Z, and spheres of radius 0.5 around it.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const BodyId sensor = addSensor(world, Shape::box({1, 1, 1}), pose, Mobility::Static);
    const auto inBoxFrame = [&](double x, double y) { return pose * Eigen::Vector3d(x, y, 0); };
    struct Case {
        double x, y; // sphere centre in the box's frame
        bool overlaps;
    };
    // Face: 1 + 0.5 reaches; corner: the nearest point (1, 1) is sqrt(2) * d away.
    const std::vector<Case> cases{{1.4, 0.0, true}, {1.6, 0.0, false}, {0.0, -1.45, true},
                                  {1.3, 1.3, true}, {1.4, 1.4, false}, {0.0, 0.0, true}};
    for (const Case& c : cases) {
        const Eigen::Vector3d centre = inBoxFrame(c.x, c.y);
        // Static and kinematic spheres alike (a simulation step never tests such pairs).
        for (Mobility mobility : {Mobility::Static, Mobility::Movable}) {
            const BodyId sphere = addSphere(world, centre.x(), centre.y(), centre.z(), mobility);
            EXPECT_EQ(world.overlaps(sphere),
                      c.overlaps ? std::vector<BodyId>{sensor} : std::vector<BodyId>{})
                << "sphere at (" << c.x << ", " << c.y << ")";
            EXPECT_EQ(world.overlaps(sensor),
                      c.overlaps ? std::vector<BodyId>{sphere} : std::vector<BodyId>{})
                << "sphere at (" << c.x << ", " << c.y << ")";
            world.removeBody(sphere);
        }
    }
}

TEST(OverlapsTest, SphereAgainstSphereAtTheSumOfTheRadii) {
    PhysicsWorld world;
    const BodyId a = addSensor(world, Shape::sphere(1.0), at(0, 0, 0), Mobility::Movable);
    const BodyId near = addSphere(world, 1.45, 0, 0, Mobility::Movable);
    const BodyId far = addSphere(world, 0, 1.55, 0, Mobility::Movable);
    EXPECT_EQ(world.overlaps(a), std::vector<BodyId>{near});
    world.setPose(far, at(0, 1.45, 0)); // seen at once, without a step
    EXPECT_EQ(world.overlaps(a), (std::vector<BodyId>{near, far}));
}

TEST(OverlapsTest, BodiesAndRaysPassThroughASensor) {
    PhysicsWorld world;
    const BodyId floor = addFloor(world);
    const BodyId sensor = addSensor(world, Shape::box({2, 2, 0.5}), at(0, 0, 1.0), Mobility::Static);
    const BodyId box = world.addBody(dynamicBody(Shape::box({0.2, 0.2, 0.2}), 0, 0, 3.0));
    const std::optional<RayHit> hit = world.raycast({0.5, 0.5, 5.0}, {0.5, 0.5, -1.0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, floor); // through the sensor (the box is not on the ray's line)
    for (const RayHit& h : world.raycastAll({0.5, 0.5, 5.0}, {0.5, 0.5, -1.0}))
        EXPECT_NE(h.body, sensor);
    run(world, 0.55); // falling 2 m takes 0.64 s: the box is inside the sensor now
    EXPECT_EQ(world.overlaps(sensor), std::vector<BodyId>{box});
    run(world, 2.0);
    EXPECT_NEAR(world.getPose(box).translation().z(), 0.2, 1e-3); // it fell through onto the floor
    EXPECT_TRUE(world.overlaps(sensor).empty());                  // the box rests below it, on the floor
}

} // namespace
} // namespace sp::physics
