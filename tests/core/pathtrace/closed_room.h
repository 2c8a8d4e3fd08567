#pragma once
// A closed white room (inside 4 x 3 x 2.5 m, walls 0.2 m thick, diffuse 0.8) lit by a lamp inside, where most
// of the light is indirect; optionally a strong sun outside, which must not reach in. Shared by the probe and
// denoiser tests.

#include "core/render/primitives.h"
#include "core/render/scene.h"
#include "test_scenes.h"

namespace sp::pathtrace::test {

// Builds the room into `scene` and returns the lamp's id.
inline render::LightId buildClosedRoom(render::Scene& scene, bool sun) {
    const render::MaterialId white =
        scene.addMaterial(render::test::makeMaterial({0.8f, 0.8f, 0.8f}, 1.0f, 0.0f));
    const auto slab = [&](Eigen::Vector3f size, Eigen::Vector3d centre) {
        render::Instance instance{scene.addMesh(render::primitives::box(size)), {white}, {1}};
        instance.transform = Eigen::Translation3d(centre);
        scene.addInstance(instance);
    };
    const float t = 0.2f;
    slab({4.0f + 2 * t, 3.0f + 2 * t, t}, {0.0, 0.0, -t / 2});      // floor
    slab({4.0f + 2 * t, 3.0f + 2 * t, t}, {0.0, 0.0, 2.5 + t / 2}); // ceiling
    slab({t, 3.0f, 2.5f}, {2.0 + t / 2, 0.0, 1.25});                // walls
    slab({t, 3.0f, 2.5f}, {-2.0 - t / 2, 0.0, 1.25});
    slab({4.0f + 2 * t, t, 2.5f}, {0.0, 1.5 + t / 2, 1.25});
    slab({4.0f + 2 * t, t, 2.5f}, {0.0, -1.5 - t / 2, 1.25});
    render::Light lamp;
    lamp.type = render::LightType::Point;
    lamp.position = {0.5, 0.3, 2.2};
    lamp.intensity = 10.0f;
    const render::LightId id = scene.addLight(lamp);
    if (sun) {
        render::Light light;
        light.direction = Eigen::Vector3d(0.4, 0.3, -1.0).normalized();
        light.intensity = 100.0f;
        scene.addLight(light);
    }
    scene.setEnvironment({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}});
    return id;
}

// The view of the room the tests take: from a corner, towards the opposite one.
inline render::Camera closedRoomCamera() {
    return render::test::cameraLookingAt({-1.8, -1.3, 1.8}, {1.0, 0.8, 0.6}, 48, 32, 90.0);
}

} // namespace sp::pathtrace::test
