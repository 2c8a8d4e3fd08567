// Mean wall time of PhysicsWorld::step(1/60 s) for boxes falling onto a plane, as a table. The ratio
// column compares against the real-time floor: a 1/60 s frame must step in under 16.7 ms.
//
// Usage: spear_physics_bench [frames]   (default 240 frames = 4 s simulated, falling, impact and settling)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/physics/physics_world.h"

namespace {

using sp::physics::BodyDesc;
using sp::physics::Mobility;
using sp::physics::PhysicsWorld;
using sp::physics::Shape;

constexpr double kFrame = 1.0 / 60.0;

struct Result {
    int bodies;
    double meanMs;
    double minMs;
    double maxMs;
    size_t awakeAtEnd;
};

// Boxes on a square grid 1.5 m apart, at staggered heights and tilts so that they tumble and collide
// with the floor at different times.
void addBoxes(PhysicsWorld& world, int count) {
    BodyDesc floor;
    floor.shape = Shape::plane();
    floor.mobility = Mobility::Static;
    world.addBody(floor);
    const int side = int(std::ceil(std::sqrt(double(count))));
    for (int i = 0; i < count; ++i) {
        BodyDesc box;
        box.shape = Shape::box({0.25, 0.25, 0.25});
        box.pose.translation() = Eigen::Vector3d(1.5 * (i % side), 1.5 * (i / side), 1.0 + 0.25 * (i % 5));
        box.pose.rotate(Eigen::AngleAxisd(0.2 * (i % 7), Eigen::Vector3d(1, 1, 0).normalized()));
        world.addBody(box);
    }
}

Result measure(int count, int frames) {
    PhysicsWorld world;
    addBoxes(world, count);
    std::vector<double> ms;
    ms.reserve(size_t(frames));
    for (int frame = 0; frame < frames; ++frame) {
        const auto start = std::chrono::steady_clock::now();
        world.step(kFrame);
        const auto stop = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
    }
    double sum = 0.0;
    for (double value : ms)
        sum += value;
    size_t awake = 0;
    for (sp::physics::BodyId id : world.bodies())
        awake += world.isAwake(id) ? 1 : 0;
    return {count, sum / double(frames), *std::min_element(ms.begin(), ms.end()),
            *std::max_element(ms.begin(), ms.end()), awake};
}

} // namespace

int main(int argc, char** argv) {
    const int frames = argc > 1 ? std::atoi(argv[1]) : 240;
    if (frames < 1) {
        std::fprintf(stderr, "spear_physics_bench: frames must be >= 1, got '%s'\n", argv[1]);
        return 2;
    }
    const PhysicsWorld::Settings settings;
    std::printf("PhysicsWorld::step(1/60 s), %d frames, %d substeps of %.5f s per frame\n", frames,
                int(std::lround(kFrame / settings.fixedTimeStep)), settings.fixedTimeStep);
    std::printf("%8s %12s %10s %10s %14s %14s %8s\n", "boxes", "mean ms", "min ms", "max ms", "us/box/frame",
                "x real time", "awake");
    for (int count : {4, 16, 64, 256}) {
        const Result r = measure(count, frames);
        std::printf("%8d %12.4f %10.4f %10.4f %14.3f %14.1f %8zu\n", r.bodies, r.meanMs, r.minMs, r.maxMs,
                    1000.0 * r.meanMs / r.bodies, 1000.0 * kFrame / r.meanMs, r.awakeAtEnd);
    }
    return 0;
}
