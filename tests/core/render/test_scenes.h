#pragma once
// Small scenes shared by the golden, intrinsics and latency tests.

#include <utility>

#include "core/render/camera.h"
#include "core/render/primitives.h"
#include "core/render/scene.h"

namespace sp::render::test {

inline Camera cameraLookingAt(const Eigen::Vector3d& position, const Eigen::Vector3d& target, int width,
                              int height, double hfovDeg = 60.0) {
    Camera camera;
    const Eigen::Vector3d x = (target - position).normalized();
    const Eigen::Vector3d up = std::abs(x.z()) < 0.99 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d y = up.cross(x).normalized();
    camera.pose.linear() << x, y, x.cross(y);
    camera.pose.translation() = position;
    camera.params.width = width;
    camera.params.height = height;
    camera.params.hfovDeg = hfovDeg;
    camera.params.shadowResolution = 512;
    return camera;
}

inline Material makeMaterial(Eigen::Vector3f color, float roughness, float metallic) {
    Material m;
    m.baseColor << color, 1.0f;
    m.roughness = roughness;
    m.metallic = metallic;
    return m;
}

// The mesh with each triangle wound the other way, its normals unchanged.
inline MeshData rewound(MeshData mesh) {
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    return mesh;
}

// Ground, a box, a metallic sphere and a cylinder; a directional sun with shadows and a sky term.
inline void buildShapesScene(Scene& scene) {
    MeshId plane = scene.addMesh(primitives::plane(8, 8));
    MeshId box = scene.addMesh(primitives::box({0.8f, 0.8f, 0.8f}));
    MeshId sphere = scene.addMesh(primitives::sphere(0.45f, 32, 16));
    MeshId cylinder = scene.addMesh(primitives::cylinder(0.3f, 1.0f, 24));
    MaterialId ground = scene.addMaterial(makeMaterial({0.6f, 0.6f, 0.55f}, 0.9f, 0.0f));
    MaterialId red = scene.addMaterial(makeMaterial({0.7f, 0.12f, 0.1f}, 0.5f, 0.0f));
    MaterialId gold = scene.addMaterial(makeMaterial({1.0f, 0.78f, 0.34f}, 0.3f, 1.0f));
    MaterialId blue = scene.addMaterial(makeMaterial({0.1f, 0.25f, 0.7f}, 0.2f, 0.0f));
    scene.addInstance({plane, {ground}, {1}});
    Instance b{box, {red}, {2}};
    b.transform = Eigen::Translation3d(0.3, 0.8, 0.4) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
    scene.addInstance(b);
    Instance s{sphere, {gold}, {3}};
    s.transform.translation() = Eigen::Vector3d(-0.2, -0.5, 0.45);
    scene.addInstance(s);
    Instance c{cylinder, {blue}, {4}};
    c.transform.translation() = Eigen::Vector3d(1.2, -0.6, 0.5);
    scene.addInstance(c);
    Light sun;
    sun.direction = Eigen::Vector3d(-0.4, -0.5, -1.0);
    sun.intensity = 3.0f;
    scene.addLight(sun);
    Environment environment;
    environment.ambient = {0.12f, 0.14f, 0.18f};
    environment.background = {0.25f, 0.3f, 0.4f};
    scene.setEnvironment(environment);
}

// A warm shadowed spot light from above one corner and a bluish point light of finite range.
inline void addSpotAndPointLights(Scene& scene) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = Eigen::Vector3d(1.5, 1.2, 2.8);
    spot.direction = Eigen::Vector3d(-0.5, -0.4, -1.0);
    spot.intensity = 12.0f;
    spot.innerConeDeg = 20.0f;
    spot.outerConeDeg = 35.0f;
    spot.color = {1.0f, 0.9f, 0.75f};
    scene.addLight(spot);
    Light point;
    point.type = LightType::Point;
    point.position = Eigen::Vector3d(0.5, -1.5, 1.0);
    point.intensity = 1.5f;
    point.color = {0.5f, 0.6f, 1.0f};
    point.range = 5.0f;
    scene.addLight(point);
}

// A grey room corner lit by a spot light and a point light (no sun): tests local lights and falloff.
inline void buildSpotScene(Scene& scene) {
    MeshId plane = scene.addMesh(primitives::plane(6, 6));
    MeshId box = scene.addMesh(primitives::box({0.6f, 0.6f, 1.2f}));
    MaterialId white = scene.addMaterial(makeMaterial({0.8f, 0.8f, 0.8f}, 0.7f, 0.0f));
    MaterialId green = scene.addMaterial(makeMaterial({0.2f, 0.6f, 0.25f}, 0.4f, 0.0f));
    scene.addInstance({plane, {white}, {1}});
    Instance wall{plane, {white}, {2}};
    wall.transform =
        Eigen::Translation3d(-1.5, 0, 1.5) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY());
    scene.addInstance(wall);
    Instance b{box, {green}, {3}};
    b.transform.translation() = Eigen::Vector3d(0.2, 0.1, 0.6);
    scene.addInstance(b);
    addSpotAndPointLights(scene);
    Environment environment;
    environment.ambient = {0.02f, 0.02f, 0.02f};
    scene.setEnvironment(environment);
}

} // namespace sp::render::test
