// Mesh import through assimp: OBJ (+MTL), PLY and glTF files written by the test, and the errors.

#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>

#include "core/base/error.h"
#include "core/render/image_buffer.h"
#include "core/render/mesh_import.h"
#include "gl_fixture.h"

namespace sp::render {
namespace {

class MeshImportTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::path(SPEAR_RENDER_TEST_OUTPUT_DIR) / "import" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        std::filesystem::create_directories(dir_);
    }
    std::string write(const std::string& name, const std::string& text) {
        const std::filesystem::path path = dir_ / name;
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }
    std::filesystem::path dir_;
};

// Two quads with two materials: a red one at z = 0 and a metallic grey one at z = 1.
constexpr const char* kObj = R"(mtllib two.mtl
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
usemtl red
f 1 2 3 4
usemtl grey
f 5 6 7 8
)";
constexpr const char* kMtl = R"(newmtl red
Kd 0.8 0.1 0.1
Ns 100
newmtl grey
Kd 0.5 0.5 0.5
)";

TEST_F(MeshImportTest, ObjWithTwoMaterialsGivesTwoSubmeshes) {
    write("two.mtl", kMtl);
    ImportedMesh imported = importMesh(write("two.obj", kObj));
    ASSERT_EQ(imported.mesh.submeshCount(), 2u);
    ASSERT_EQ(imported.materials.size(), 2u);
    EXPECT_EQ(imported.mesh.indices.size(), 12u); // quads triangulated
    std::vector<std::string> names = {imported.materials[0].name, imported.materials[1].name};
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"grey", "red"}));
    for (const ImportedMaterial& material : imported.materials)
        if (material.name == "red") {
            EXPECT_NEAR(material.material.baseColor.x(), 0.8f, 1e-6f);
            EXPECT_NEAR(material.material.roughness, std::sqrt(2.0f / 102.0f), 1e-5f);
        }
}

TEST_F(MeshImportTest, PlyTriangle) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    ImportedMesh imported = importMesh(write("tri.ply", ply));
    EXPECT_EQ(imported.mesh.positions.size(), 3u);
    EXPECT_EQ(imported.mesh.submeshCount(), 1u);
    EXPECT_NEAR(std::abs(imported.mesh.normals[0].z()), 1.0f, 1e-5f);
}

TEST_F(MeshImportTest, GltfWithEmbeddedBufferAndPbrFactors) {
    // One triangle; buffer = 3 float3 positions + 3 uint16 indices (+2 bytes padding), base64-encoded.
    const std::string gltf = R"({
 "asset": {"version": "2.0"},
 "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0, "translation": [0, 0, 2]}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
 "materials": [{"name": "metal", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.1, 1], "metallicFactor": 1.0, "roughnessFactor": 0.25}}],
 "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
 "accessors": [
  {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})";
    ImportedMesh imported = importMesh(write("tri.gltf", gltf));
    ASSERT_EQ(imported.materials.size(), 1u);
    EXPECT_NEAR(imported.materials[0].material.metallic, 1.0f, 1e-6f);
    EXPECT_NEAR(imported.materials[0].material.roughness, 0.25f, 1e-6f);
    EXPECT_NEAR(imported.materials[0].material.baseColor.y(), 0.8f, 1e-6f);
    // glTF is Y-up, spear Z-up: (x, y, z) -> (x, -z, y). The triangle in glTF's z = 0 plane, moved 2 along
    // glTF's +z (forward) by its node, stands upright in spear's y = -2 plane, its glTF +y edge pointing up.
    for (const Eigen::Vector3f& p : imported.mesh.positions)
        EXPECT_NEAR(p.y(), -2.0f, 1e-6f) << p.transpose(); // the node translation is baked in
    float top = 0.0f;
    for (const Eigen::Vector3f& p : imported.mesh.positions)
        top = std::max(top, p.z());
    EXPECT_NEAR(top, 1.0f, 1e-6f);
    for (const Eigen::Vector3f& n : imported.mesh.normals) // glTF's +z face normal is spear's -y
        EXPECT_NEAR(std::abs(n.y()), 1.0f, 1e-5f);
}

TEST_F(MeshImportTest, AGltfOcclusionMapIsPackedIntoTheMetallicRoughnessTexturesR) {
    // glTF keeps occlusion (R) and metallic-roughness (G, B) in two textures, often one image; the renderer's
    // material reads one texture with occlusion in R. A metallic-roughness map alone occludes nothing.
    const std::uint8_t rm[4 * 4] = {9, 64, 191, 255, 9, 64, 191, 255, 9, 64, 191, 255, 9, 64, 191, 255};
    const std::uint8_t ao[4 * 4] = {102, 0, 0, 255, 102, 0, 0, 255, 102, 0, 0, 255, 102, 0, 0, 255};
    writePng((dir_ / "rm.png").string(), 2, 2, 4, rm);
    writePng((dir_ / "ao.png").string(), 2, 2, 4, ao);
    auto gltf = [](const std::string& occlusion) {
        return R"({
 "asset": {"version": "2.0"},
 "scene": 0, "scenes": [{"nodes": [0]}],
 "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "material": 0}]}],
 "materials": [{"pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0}})" +
               occlusion + R"(}],
 "textures": [{"source": 0}, {"source": 1}],
 "images": [{"uri": "rm.png"}, {"uri": "ao.png"}],
 "buffers": [{"byteLength": 68, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8="}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6},
                 {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
 "accessors": [
  {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
  {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}]
})";
    };
    const ImportedMesh both = importMesh(write("both.gltf", gltf(R"(, "occlusionTexture": {"index": 1})")));
    const ImportedMesh alone = importMesh(write("alone.gltf", gltf("")));
    ASSERT_TRUE(both.materials.at(0).roughnessMetallicTexture.has_value());
    ASSERT_TRUE(alone.materials.at(0).roughnessMetallicTexture.has_value());
    const std::vector<std::uint8_t>& packed = both.materials[0].roughnessMetallicTexture->rgba;
    const std::vector<std::uint8_t>& plain = alone.materials[0].roughnessMetallicTexture->rgba;
    EXPECT_EQ((std::vector<int>{packed[0], packed[1], packed[2]}), (std::vector<int>{102, 64, 191}));
    EXPECT_EQ((std::vector<int>{plain[0], plain[1], plain[2]}), (std::vector<int>{255, 64, 191}));
}

TEST_F(MeshImportTest, AFileWithoutNormalsGetsHardEdgesAtItsCreases) {
    // A cube of eight shared corners and no normals: each face gets its own normal along an axis (corners
    // split at the 90-degree edges), not the smooth average that would shade the cube as a blob. (A finely
    // tessellated sphere stays smooth and shared: MeshLods.ImportedFineMeshesGetLevelsInTheScene.)
    const std::string obj =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n";
    const ImportedMesh imported = importMesh(write("cube.obj", obj));
    ASSERT_EQ(imported.mesh.indices.size(), 36u);
    for (const Eigen::Vector3f& n : imported.mesh.normals)
        EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0f, 1e-5f) << n.transpose(); // along an axis
    EXPECT_GE(imported.mesh.positions.size(), 24u);                         // four corners a face
}

TEST_F(MeshImportTest, MissingFileIsNotFoundNamingThePath) {
    const std::string path = (dir_ / "nope.obj").string();
    try {
        importMesh(path);
        FAIL();
    } catch (const NotFound& e) {
        EXPECT_EQ(std::string(e.what()), "importMesh(): no such file '" + path + "'");
    }
}

TEST_F(MeshImportTest, CorruptOrUnsupportedIsInvalidArgument) {
    EXPECT_THROW(importMesh(write("garbage.gltf", "{ this is not json")), InvalidArgument);
    EXPECT_THROW(importMesh(write("data.unknownext", "\x01\x02\x03 binary junk")), InvalidArgument);
    EXPECT_THROW(importMesh(write("empty.obj", "# nothing here\n")), InvalidArgument);
}

TEST_F(MeshImportTest, AFileReadBeforeComesFromTheCacheUntilAFileItReadChanges) {
    // The OBJ and its material library: read once; the same again while neither changes; read afresh when
    // the library changes (a new colour), when the OBJ is replaced by another file, and refused once gone.
    write("two.mtl", kMtl);
    const std::string obj = write("two.obj", kObj);
    const std::uint64_t before = meshFilesRead();
    const ImportedMesh first = importMesh(obj);
    const ImportedMesh again = importMesh(obj);
    EXPECT_EQ(meshFilesRead(), before + 1);
    EXPECT_EQ(again.mesh.indices, first.mesh.indices);
    ASSERT_EQ(again.materials.size(), first.materials.size());
    for (std::size_t m = 0; m < first.materials.size(); ++m)
        EXPECT_EQ(again.materials[m].material.baseColor, first.materials[m].material.baseColor);

    std::string mtl = kMtl;
    // (A longer file: two writes within one tick of the kernel's file clock could keep size and times.)
    mtl.replace(mtl.find("Kd 0.8 0.1 0.1"), 14, "Kd 0.1 0.8 0.1\n# recoloured");
    write("two.mtl", mtl);
    const ImportedMesh recoloured = importMesh(obj);
    EXPECT_EQ(meshFilesRead(), before + 2) << "the material library changed";
    bool green = false;
    for (const ImportedMaterial& material : recoloured.materials)
        green = green || (material.name == "red" && material.material.baseColor.y() > 0.7f);
    EXPECT_TRUE(green);

    const std::filesystem::path replacement = dir_ / "replacement.obj";
    std::ofstream(replacement) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::filesystem::rename(replacement, obj); // another file under the same name
    EXPECT_EQ(importMesh(obj).mesh.indices.size(), 3u);
    EXPECT_EQ(meshFilesRead(), before + 3);
    std::filesystem::remove(obj);
    EXPECT_THROW(importMesh(obj), NotFound);
}

class MeshImportGlTest : public test::GlTest {};

TEST_F(MeshImportGlTest, ImportedObjRendersWithPerSlotIds) {
    const std::filesystem::path dir = std::filesystem::path(SPEAR_RENDER_TEST_OUTPUT_DIR) / "import" / "gl";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "two.mtl") << kMtl;
    std::ofstream(dir / "two.obj") << kObj;
    ImportedMesh imported = importMesh((dir / "two.obj").string());
    Scene scene;
    ImportedMeshIds ids = addToScene(scene, imported);
    // Slot ids: 10 for the z = 0 quad's material group, 20 for the other.
    std::vector<std::uint32_t> slotIds;
    for (const Submesh& sub : imported.mesh.submeshes)
        slotIds.push_back(imported.mesh.positions[imported.mesh.indices[sub.firstIndex]].z() < 0.5f ? 10
                                                                                                    : 20);
    scene.addInstance({ids.mesh, ids.materials, slotIds});
    // Look from below: only the z = 0 quad is visible; from above only the z = 1 quad.
    RenderTarget target(renderer(), {Modality::ObjectIds}, 0);
    Frame frame;
    target.render(scene, lookingAlong({0.01, 0, -3}, {0, 0, 1}, 8, 8, 30.0), frame);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(4, 4), 10u);
    target.render(scene, lookingAlong({0.01, 0, 4}, {0, 0, -1}, 8, 8, 30.0), frame);
    EXPECT_EQ(frame.get(Modality::ObjectIds).uintAt(4, 4), 20u);
}

} // namespace
} // namespace sp::render
