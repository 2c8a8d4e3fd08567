// Levels of detail of finely tessellated meshes (mesh_lods.h): how many, how coarse, how far their surfaces
// moved, and what they keep (submeshes, borders between them, attributes); and that imports get them.

#include "core/render/mesh_lods.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/render/mesh_import.h"
#include "core/render/primitives.h"
#include "core/render/scene.h"

namespace sp::render {
namespace {

MeshData validated(MeshData mesh) {
    mesh.validate("test");
    return mesh;
}

// The largest distance from the sphere of `radius` about the origin of a point on a level's triangles
// (their corners and centroids).
double largestDeviation(const MeshData& mesh, double radius) {
    double largest = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Eigen::Vector3d a = mesh.positions[mesh.indices[t]].cast<double>();
        const Eigen::Vector3d b = mesh.positions[mesh.indices[t + 1]].cast<double>();
        const Eigen::Vector3d c = mesh.positions[mesh.indices[t + 2]].cast<double>();
        for (const Eigen::Vector3d& p : {a, b, c, Eigen::Vector3d((a + b + c) / 3.0)})
            largest = std::max(largest, std::abs(p.norm() - radius));
    }
    return largest;
}

TEST(MeshLods, AFineSphereHalvesItsTrianglesPerLevelWithinItsErrorBounds) {
    const MeshData sphere = validated(primitives::sphere(0.5f, 96, 48)); // 9,216 triangles
    const auto lods = simplifiedLods(sphere);
    ASSERT_GE(lods.size(), 3u);
    std::size_t previous = sphere.indices.size();
    float previousError = 0.0f;
    const double radius = 0.5 * std::sqrt(3.0); // half the bounding box's diagonal: MeshLod's unit
    for (std::size_t i = 0; i < lods.size(); ++i) {
        const auto& [level, error] = lods[i];
        SCOPED_TRACE("level " + std::to_string(i));
        EXPECT_LE(level.indices.size() * 5, previous * 4) << "at least a fifth fewer triangles";
        EXPECT_GE(level.indices.size() * 3, previous) << "about half, not a collapse";
        EXPECT_GE(error, previousError) << "errors never decrease";
        EXPECT_LE(error, kMostLodError);
        // The vertices kept are the sphere's own; the level's triangles sag inside it by about its error,
        // which is measured at the sphere's vertices (here also at the level's centroids).
        EXPECT_LE(largestDeviation(level, 0.5), 1.5 * double(error) * radius + 1e-6);
        // Only the vertices it uses, each with its normal and uv.
        ASSERT_EQ(level.normals.size(), level.positions.size());
        ASSERT_EQ(level.uvs.size(), level.positions.size());
        std::vector<bool> used(level.positions.size(), false);
        for (std::uint32_t index : level.indices) {
            ASSERT_LT(index, level.positions.size());
            used[index] = true;
        }
        EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
        for (std::size_t v = 0; v < level.positions.size(); ++v)
            EXPECT_GT(level.normals[v].dot(level.positions[v].normalized()), 0.99f) << "vertex " << v;
        ASSERT_EQ(level.submeshes.size(), 1u);
        EXPECT_EQ(level.submeshes[0].indexCount, level.indices.size());
        previous = level.indices.size();
        previousError = error;
    }
    EXPECT_LT(lods.back().first.indices.size() * 8, sphere.indices.size()) << "the coarsest is far coarser";
}

TEST(MeshLods, SmallMeshesGetNone) {
    EXPECT_TRUE(simplifiedLods(validated(primitives::box({1, 1, 1}))).empty());
    EXPECT_TRUE(simplifiedLods(validated(primitives::sphere(0.5f, 32, 16))).empty()); // 1,024 triangles
}

TEST(MeshLods, SubmeshesKeepTheirBorderAndStayNonEmpty) {
    // A finely divided square in two materials, left and right halves: each level keeps both submeshes and
    // every vertex on the line between them (x = 0), so the two halves still meet without a crack.
    constexpr int kDivisions = 64;
    MeshData square;
    for (int y = 0; y <= kDivisions; ++y)
        for (int x = 0; x <= kDivisions; ++x)
            square.positions.emplace_back(float(x) / kDivisions - 0.5f, float(y) / kDivisions - 0.5f,
                                          0.02f * std::sin(float(x + y)));
    std::vector<std::uint32_t> halves[2];
    for (int y = 0; y < kDivisions; ++y)
        for (int x = 0; x < kDivisions; ++x) {
            const std::uint32_t a = std::uint32_t(y * (kDivisions + 1) + x), b = a + 1,
                                c = a + kDivisions + 1, d = c + 1;
            std::vector<std::uint32_t>& half = halves[x < kDivisions / 2 ? 0 : 1];
            half.insert(half.end(), {a, b, d, a, d, c});
        }
    square.indices = halves[0];
    square.indices.insert(square.indices.end(), halves[1].begin(), halves[1].end());
    square.submeshes = {{0, std::uint32_t(halves[0].size())},
                        {std::uint32_t(halves[0].size()), std::uint32_t(halves[1].size())}};
    square = validated(square);
    const auto lods = simplifiedLods(square);
    ASSERT_FALSE(lods.empty());
    for (const auto& [level, error] : lods) {
        ASSERT_EQ(level.submeshes.size(), 2u);
        EXPECT_GT(level.submeshes[0].indexCount, 0u);
        EXPECT_GT(level.submeshes[1].indexCount, 0u);
        int onBorder = 0;
        for (const Eigen::Vector3f& p : level.positions)
            onBorder += std::abs(p.x()) < 1e-6f ? 1 : 0;
        EXPECT_EQ(onBorder, kDivisions + 1) << "the seam's vertices, all kept";
    }
}

TEST(MeshLods, SharedLevelsAreMadeOncePerProcess) {
    // The second ask for a key gets the levels the first made, without simplifying again; another key
    // (another content) its own.
    const MeshData sphere = validated(primitives::sphere(0.5f, 96, 48));
    const MeshData other = validated(primitives::sphere(0.5f, 80, 40));
    int made = 0;
    const auto first = sharedLods("test:sphere96", sphere, [&] { ++made; });
    const int madeFirst = made;
    const auto again = sharedLods("test:sphere96", sphere, [&] { ++made; });
    EXPECT_GT(madeFirst, 0);
    EXPECT_EQ(made, madeFirst) << "not made again";
    EXPECT_EQ(first.get(), again.get());
    const auto another = sharedLods("test:sphere80", other);
    EXPECT_NE(another.get(), first.get());
    EXPECT_NE(another->front().first.indices.size(), first->front().first.indices.size());
}

TEST(MeshLods, ImportedFineMeshesGetLevelsInTheScene) {
    // An OBJ sphere of 9,216 triangles added to a scene comes with its levels; a box does not.
    const std::filesystem::path dir = std::filesystem::path(SPEAR_RENDER_TEST_OUTPUT_DIR) / "import" / "lods";
    std::filesystem::create_directories(dir);
    const MeshData sphere = validated(primitives::sphere(0.5f, 96, 48));
    {
        std::ofstream obj(dir / "sphere.obj");
        for (const Eigen::Vector3f& p : sphere.positions)
            obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
        for (std::size_t t = 0; t < sphere.indices.size(); t += 3)
            obj << "f " << sphere.indices[t] + 1 << " " << sphere.indices[t + 1] + 1 << " "
                << sphere.indices[t + 2] + 1 << "\n";
    }
    Scene scene, second;
    const ImportedMesh imported = importMesh((dir / "sphere.obj").string());
    const ImportedMeshIds ids = addToScene(scene, imported, true);
    const std::vector<MeshLod>& lods = scene.meshLods(ids.mesh);
    ASSERT_GE(lods.size(), 3u);
    EXPECT_LT(scene.mesh(lods.back().mesh).indices.size() * 8, scene.mesh(ids.mesh).indices.size());
    // Drawn 20 pixels wide, the sphere takes a coarser level; 2,000 wide, itself.
    const double radiusInPixels = 20.0 / 2.0 * std::sqrt(3.0);
    EXPECT_NE(scene.lodFor(ids.mesh, radiusInPixels), ids.mesh);
    EXPECT_EQ(scene.lodFor(ids.mesh, 100.0 * radiusInPixels), ids.mesh);
    // A second scene importing it (another world) gets the same levels, made once (sharedLods()).
    const ImportedMeshIds again = addToScene(second, imported, true);
    ASSERT_EQ(second.meshLods(again.mesh).size(), lods.size());
    for (std::size_t i = 0; i < lods.size(); ++i) {
        EXPECT_EQ(second.meshLods(again.mesh)[i].relativeError, lods[i].relativeError);
        EXPECT_EQ(second.mesh(second.meshLods(again.mesh)[i].mesh).indices, scene.mesh(lods[i].mesh).indices);
    }
}

} // namespace
} // namespace sp::render
