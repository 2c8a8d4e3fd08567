#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/render/primitives.h"
#include "core/render/scene.h"

namespace sp::render {
namespace {

TEST(SceneTest, RemovedHandlesAreStaleAndNamed) {
    Scene scene;
    MeshId mesh = scene.addMesh(primitives::box());
    scene.removeMesh(mesh);
    try {
        scene.mesh(mesh);
        FAIL();
    } catch (const StaleObject& e) {
        EXPECT_STREQ(e.what(), "Scene::mesh(): MeshId{0:1} was removed or never existed");
    }
    // The slot is reused with a new generation; the old handle stays stale.
    MeshId again = scene.addMesh(primitives::sphere());
    EXPECT_EQ(again.index, mesh.index);
    EXPECT_NE(again.generation, mesh.generation);
    EXPECT_THROW(scene.mesh(mesh), StaleObject);
    EXPECT_EQ(scene.mesh(again).name, "sphere");
}

TEST(SceneTest, InstancesNeedOneMaterialAndIdPerSlot) {
    Scene scene;
    MeshId mesh = scene.addMesh(primitives::box());
    MaterialId material = scene.addMaterial(Material{});
    Instance instance{mesh, {material}, {7}};
    InstanceId id = scene.addInstance(instance);
    EXPECT_EQ(scene.instance(id).objectIds[0], 7u);

    instance.objectIds = {0};
    try {
        scene.addInstance(instance);
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(),
                     "Scene::addInstance(): objectIds[0] is 0, which is reserved for the background");
    }
    instance.objectIds = {1, 2};
    EXPECT_THROW(scene.addInstance(instance), InvalidArgument);
    // Resources in use cannot be removed.
    EXPECT_THROW(scene.removeMesh(mesh), InvalidState);
    EXPECT_THROW(scene.removeMaterial(material), InvalidState);
    scene.removeInstance(id);
    EXPECT_THROW(scene.setTransform(id, Eigen::Affine3d::Identity()), StaleObject);
    scene.removeMaterial(material);
    scene.removeMesh(mesh);
}

TEST(SceneTest, MaterialIdDefaultsToIndexPlusOne) {
    Scene scene;
    MaterialId a = scene.addMaterial(Material{});
    Material custom;
    custom.id = 42;
    MaterialId b = scene.addMaterial(custom);
    EXPECT_EQ(scene.materialIdValue(a), a.index + 1);
    EXPECT_EQ(scene.materialIdValue(b), 42u);
    Material bad;
    bad.roughness = 2.0f;
    EXPECT_THROW(scene.addMaterial(bad), InvalidArgument);
}

TEST(SceneTest, LightLimitAndValidation) {
    Scene scene;
    for (std::size_t i = 0; i < Scene::kMaxLights; ++i)
        scene.addLight(Light{});
    EXPECT_THROW(scene.addLight(Light{}), InvalidState);
    Light spot;
    spot.type = LightType::Spot;
    spot.innerConeDeg = 50.0f;
    spot.outerConeDeg = 40.0f;
    Scene other;
    EXPECT_THROW(other.addLight(spot), InvalidArgument);
}

TEST(SceneTest, BoundsCoverTransformedInstances) {
    Scene scene;
    MeshId mesh = scene.addMesh(primitives::box({2, 2, 2}));
    MaterialId material = scene.addMaterial(Material{});
    Instance instance{mesh, {material}, {1}};
    instance.transform.translation() = Eigen::Vector3d(10, 0, 0);
    scene.addInstance(instance);
    Eigen::Vector3d centre;
    double radius;
    scene.bounds(centre, radius);
    EXPECT_TRUE(centre.isApprox(Eigen::Vector3d(10, 0, 0)));
    EXPECT_NEAR(radius, std::sqrt(3.0), 1e-9);
}

} // namespace
} // namespace sp::render
