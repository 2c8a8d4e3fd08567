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

TEST(SceneTest, AMeshsShapeFiguresFollowItsDeformation) {
    // A flat plane, wound as its normals face: no lean; then deformed, its figures are the new shape's (found
    // when asked, after each deformation), read before and after the change.
    Scene scene;
    const MeshData plane = primitives::plane(4, 4);
    const MeshId mesh = scene.addMesh(plane);
    EXPECT_LT(scene.meshWindingSpread(mesh), 1e-5f);
    const float edge = scene.meshLongestEdge(mesh);
    EXPECT_NEAR(edge, plane.longestEdge(), 1e-6f);
    std::vector<Eigen::Vector3f> positions = plane.positions, normals = plane.normals;
    for (Eigen::Vector3f& p : positions)
        p *= 3.0f; // stretched
    for (Eigen::Vector3f& n : normals)
        n = (n + Eigen::Vector3f(0.5f, 0.0f, 0.0f)).normalized(); // leaning by atan(0.5) from the plane's own
    scene.deformMesh(mesh, positions, normals);
    EXPECT_NEAR(scene.meshLongestEdge(mesh), 3.0f * edge, 1e-5f);
    EXPECT_NEAR(scene.meshWindingSpread(mesh), 0.5f, 1e-4f);
    scene.deformMesh(mesh, plane.positions, plane.normals); // and back
    EXPECT_NEAR(scene.meshLongestEdge(mesh), edge, 1e-6f);
    EXPECT_LT(scene.meshWindingSpread(mesh), 1e-5f);
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

TEST(SceneTest, RectLightsNeedASizeAndAFrameAcrossTheirDirection) {
    Scene scene;
    Light rect;
    rect.type = LightType::Rect;
    rect.direction = Eigen::Vector3d(1.0, 0.0, 0.0);
    scene.addLight(rect); // the default frame: right +Y, up +Z
    Light flat = rect;
    flat.height = 0.0f;
    EXPECT_THROW(scene.addLight(flat), InvalidArgument);
    Light skew = rect;
    skew.right = Eigen::Vector3d(1.0, 0.0, 0.0); // along the direction: no rectangle across it
    EXPECT_THROW(scene.addLight(skew), InvalidArgument);
    EXPECT_FLOAT_EQ(rect.rectRadiance(), rect.intensity / (rect.width * rect.height));
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

TEST(SceneTest, LevelsOfDetailAreChosenByHalfAPixelOfError) {
    Scene scene;
    const MeshId fine = scene.addMesh(primitives::sphere(0.5f, 48, 24));
    const MeshId medium = scene.addMesh(primitives::sphere(0.5f, 24, 12));
    const MeshId coarse = scene.addMesh(primitives::sphere(0.5f, 12, 6));
    scene.setMeshLods(fine, {{medium, 0.01f}, {coarse, 0.04f}});
    EXPECT_EQ(scene.lodFor(fine, 1000.0), fine);  // 10 px of error at medium: too coarse
    EXPECT_EQ(scene.lodFor(fine, 50.0), medium);  // 0.5 px at medium, 2 px at coarse
    EXPECT_EQ(scene.lodFor(fine, 12.5), coarse);  // 0.5 px at coarse
    EXPECT_EQ(scene.lodFor(medium, 1.0), medium); // a level has no levels of its own

    EXPECT_THROW(scene.setMeshLods(fine, {{coarse, 0.04f}, {medium, 0.01f}}),
                 InvalidArgument); // must increase
    EXPECT_THROW(scene.setMeshLods(fine, {{fine, 0.01f}}), InvalidArgument);
    EXPECT_THROW(scene.setMeshLods(medium, {{fine, 0.01f}}), InvalidArgument); // fine has levels
    const MeshId twoSlots = scene.addMesh(primitives::box());
    MeshData split = primitives::box();
    split.submeshes = {{0, 18}, {18, 18}};
    EXPECT_THROW(scene.setMeshLods(twoSlots, {{scene.addMesh(split), 0.1f}}), InvalidArgument);
    try {
        scene.removeMesh(coarse);
        FAIL() << "a level in use was removed";
    } catch (const InvalidState& error) {
        EXPECT_NE(std::string(error.what()).find("is a level of detail of"), std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace sp::render
