#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "core/base/error.h"
#include "core/render/mesh_data.h"
#include "core/render/primitives.h"
#include "test_scenes.h"

namespace sp::render {
namespace {

TEST(MeshDataTest, FromArraysFillsDefaults) {
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const std::uint32_t indices[] = {0, 1, 2, 1, 3, 2};
    const std::uint32_t offsets[] = {0, 3};
    MeshData mesh = MeshData::fromArrays(positions, {}, {}, indices, offsets);
    ASSERT_EQ(mesh.submeshCount(), 2u);
    EXPECT_EQ(mesh.submeshes[1].firstIndex, 3u);
    EXPECT_EQ(mesh.submeshes[1].indexCount, 3u);
    ASSERT_EQ(mesh.normals.size(), 4u);
    EXPECT_TRUE(mesh.normals[0].isApprox(Eigen::Vector3f::UnitZ()));
    EXPECT_EQ(mesh.uvs.size(), 4u);
}

TEST(MeshDataTest, BadIndexIsRejectedWithItsPosition) {
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::uint32_t indices[] = {0, 1, 7};
    try {
        MeshData::fromArrays(positions, {}, {}, indices);
        FAIL();
    } catch (const InvalidArgument& e) {
        EXPECT_STREQ(e.what(), "MeshData::fromArrays(): mesh '' index[2] = 7 is out of range for 3 vertices");
    }
    const float oddPositions[] = {0, 0};
    EXPECT_THROW(MeshData::fromArrays(oddPositions, {}, {}, indices), InvalidArgument);
}

TEST(MeshDataTest, PrimitivesAreClosedAndUnit) {
    for (const MeshData& mesh : {primitives::box({1, 2, 3}), primitives::sphere(0.5f),
                                 primitives::plane(2, 2), primitives::cylinder(0.5f, 1.0f)}) {
        EXPECT_EQ(mesh.submeshCount(), 1u) << mesh.name;
        for (const Eigen::Vector3f& n : mesh.normals)
            EXPECT_NEAR(n.norm(), 1.0f, 1e-5f) << mesh.name;
        Eigen::Vector3f min, max;
        mesh.bounds(min, max);
        EXPECT_TRUE((min + max).isZero(1e-5f)) << mesh.name;
    }
    Eigen::Vector3f min, max;
    primitives::box({1, 2, 3}).bounds(min, max);
    EXPECT_TRUE(max.isApprox(Eigen::Vector3f(0.5f, 1.0f, 1.5f)));
    EXPECT_THROW(primitives::sphere(-1.0f), InvalidArgument);
}

} // namespace
} // namespace sp::render

namespace sp::render {
namespace {

TEST(MeshDataTest, ConvexAndFacetedMeshesAreToldApart) {
    EXPECT_TRUE(primitives::box({2.0f, 1.0f, 0.1f}).convex());
    EXPECT_TRUE(primitives::sphere(0.45f, 32, 16).convex());
    EXPECT_TRUE(primitives::cylinder(0.3f, 1.0f, 24).convex());
    EXPECT_TRUE(primitives::plane(8, 8).convex()); // flat: every vertex on every triangle's plane
    // Two boxes side by side: the faces of one have the other's vertices on both sides.
    MeshData two = primitives::box();
    const MeshData other = primitives::box();
    const auto base = std::uint32_t(two.positions.size());
    for (const Eigen::Vector3f& p : other.positions)
        two.positions.push_back(p + Eigen::Vector3f(0.4f, 0.3f, 0.0f));
    two.normals.insert(two.normals.end(), other.normals.begin(), other.normals.end());
    two.uvs.insert(two.uvs.end(), other.uvs.begin(), other.uvs.end());
    for (std::uint32_t index : other.indices)
        two.indices.push_back(base + index);
    two.submeshes.clear();
    two.validate("test");
    EXPECT_FALSE(two.convex());
    EXPECT_FALSE(MeshData().convex()); // no triangles: no body
    // Flat shading: a box's and a plane's faces, not a sphere's smooth normals.
    EXPECT_TRUE(primitives::box({2.0f, 1.0f, 0.1f}).faceted());
    EXPECT_TRUE(primitives::plane(8, 8).faceted());
    EXPECT_FALSE(primitives::sphere(0.45f, 32, 16).faceted());
}

TEST(MeshDataTest, WindingSpreadTellsHowFarNormalsLeanFromTheirTrianglesWinding) {
    // Shaded flat and wound outward: the normals are the windings' own.
    EXPECT_LT(primitives::box({2.0f, 1.0f, 0.1f}).windingSpread(), 1e-5f);
    EXPECT_LT(primitives::plane(8, 8).windingSpread(), 1e-5f);
    // Smooth: a vertex normal leans from its triangles' planes by about half the angle between facets
    // (11.25 degrees for 16 segments; the pole triangles lean most).
    const float sphere = primitives::sphere(0.45f, 16, 8).windingSpread();
    EXPECT_GT(sphere, std::tan(0.1f));
    EXPECT_LT(sphere, std::tan(0.5f));
    EXPECT_LT(primitives::sphere(0.45f, 64, 32).windingSpread(), sphere);
    // The tangent of the largest angle, as the angles themselves give it.
    const MeshData smooth = primitives::sphere(0.45f, 16, 8);
    double largestAngle = 0.0;
    for (std::size_t t = 0; t + 2 < smooth.indices.size(); t += 3) {
        const Eigen::Vector3d a = smooth.positions[smooth.indices[t]].cast<double>();
        const Eigen::Vector3d ab = smooth.positions[smooth.indices[t + 1]].cast<double>() - a;
        const Eigen::Vector3d ac = smooth.positions[smooth.indices[t + 2]].cast<double>() - a;
        const Eigen::Vector3d winding = ab.cross(ac);
        if (winding.norm() <= 1e-7 * std::max(ab.squaredNorm(), ac.squaredNorm()))
            continue; // the poles' triangles, degenerate within float precision
        for (std::size_t v = t; v < t + 3; ++v) {
            const Eigen::Vector3d normal = smooth.normals[smooth.indices[v]].cast<double>().normalized();
            largestAngle =
                std::max(largestAngle, std::acos(std::clamp(winding.normalized().dot(normal), -1.0, 1.0)));
        }
    }
    EXPECT_NEAR(sphere, std::tan(largestAngle), 1e-4 * std::tan(largestAngle));
    // Wound inward, or one normal flipped: the facing says nothing.
    EXPECT_TRUE(std::isinf(test::rewound(primitives::box()).windingSpread()));
    MeshData flipped = primitives::sphere(0.45f, 16, 8);
    flipped.normals[5] = -flipped.normals[5];
    EXPECT_TRUE(std::isinf(flipped.windingSpread()));
    EXPECT_EQ(MeshData().windingSpread(), 0.0f);
}

TEST(MeshDataTest, WindingTurnsNormalsUnderTransformsThatKeepThemOnTheirWindingsSide) {
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d rotated = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    const Eigen::Matrix3d squashed = Eigen::Vector3d(40.0, 40.0, 0.01).asDiagonal();
    const Eigen::Matrix3d mirrored = Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal() * rotated;
    const float tan20 = std::tan(20.0f * float(M_PI) / 180.0f);
    // Flat meshes: any invertible transform.
    EXPECT_TRUE(windingTurnsNormals(0.0f, squashed));
    EXPECT_TRUE(windingTurnsNormals(0.0f, mirrored));
    // Smooth meshes: rotations, uniform scales and mirrors; scales as uneven as the bound allows, not more
    // (tan 20 degrees (k^2 - 1) < 1: k up to 1.93).
    EXPECT_TRUE(windingTurnsNormals(tan20, identity));
    EXPECT_TRUE(windingTurnsNormals(tan20, 3.0 * rotated));
    EXPECT_TRUE(windingTurnsNormals(tan20, mirrored));
    EXPECT_TRUE(windingTurnsNormals(tan20, Eigen::Vector3d(1.9, 1.0, 1.0).asDiagonal() * rotated));
    EXPECT_FALSE(windingTurnsNormals(tan20, Eigen::Vector3d(2.0, 1.0, 1.0).asDiagonal() * rotated));
    EXPECT_FALSE(windingTurnsNormals(tan20, squashed));
    // Nothing to turn by: a mesh whose normals leave their windings' side, or a transform that flattens it.
    EXPECT_FALSE(windingTurnsNormals(std::numeric_limits<float>::infinity(), identity));
    EXPECT_FALSE(windingTurnsNormals(0.0f, Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal()));
}

TEST(PrimitivesTest, TubeRingsSitAtTheRadiusAroundThePath) {
    const std::vector<Eigen::Vector3f> path{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 1, 0}, {2, 1, 1}};
    const MeshData tube = primitives::tube(path, 0.05f, 6);
    ASSERT_EQ(tube.positions.size(), 4u * 6u); // the repeated point is skipped
    EXPECT_EQ(tube.indices.size(), 3u * 6u * 6u);
    const std::vector<Eigen::Vector3f> kept{{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {2, 1, 1}};
    for (size_t i = 0; i < tube.positions.size(); ++i) {
        const Eigen::Vector3f offset = tube.positions[i] - kept[i / 6];
        EXPECT_NEAR(offset.norm(), 0.05f, 1e-5f);
        EXPECT_TRUE(tube.normals[i].isApprox(offset / 0.05f, 1e-4f)); // pointing out of the tube
    }
    EXPECT_THROW(primitives::tube({{0, 0, 0}, {0, 0, 0}}, 0.05f), InvalidArgument);
    EXPECT_THROW(primitives::tube(path, 0.0f), InvalidArgument);
}

TEST(MeshDataTest, SubdividingKeepsTheSurfaceAndSharesEdgeMidpoints) {
    // A unit box of 24 vertices, 12 triangles, one submesh; twice subdivided: 16 times the triangles, the
    // same bounds, the same area, every vertex on the box, every normal unit and every face's normal its
    // face's (a box is faceted: its faces share no vertices, so no normal is averaged across an edge).
    MeshData box = primitives::box();
    box.validate("test");
    const MeshData twice = box.subdivided(2);
    EXPECT_EQ(twice.indices.size(), box.indices.size() * 16);
    ASSERT_EQ(twice.submeshes.size(), 1u);
    EXPECT_EQ(twice.submeshes[0].indexCount, twice.indices.size());
    Eigen::Vector3f min, max;
    twice.bounds(min, max);
    EXPECT_TRUE(min.isApprox(Eigen::Vector3f::Constant(-0.5f)) &&
                max.isApprox(Eigen::Vector3f::Constant(0.5f)));
    const auto area = [](const MeshData& m) {
        double sum = 0.0;
        for (std::size_t t = 0; t < m.indices.size(); t += 3)
            sum += 0.5 * double((m.positions[m.indices[t + 1]] - m.positions[m.indices[t]])
                                    .cross(m.positions[m.indices[t + 2]] - m.positions[m.indices[t]])
                                    .norm());
        return sum;
    };
    EXPECT_NEAR(area(twice), 6.0, 1e-5);
    for (std::size_t i = 0; i < twice.positions.size(); ++i) {
        EXPECT_NEAR(twice.positions[i].cwiseAbs().maxCoeff(), 0.5f, 1e-6f) << i;
        EXPECT_NEAR(twice.normals[i].norm(), 1.0f, 1e-5f) << i;
        EXPECT_NEAR(twice.normals[i].cwiseAbs().maxCoeff(), 1.0f, 1e-6f) << i;
    }
    // Each face of 2 triangles becomes a 5 x 5 grid of vertices: shared edges split once.
    EXPECT_EQ(twice.positions.size(), 6u * 25u);
    EXPECT_NEAR(twice.longestEdge(), box.longestEdge() / 4.0f, 1e-6f);
    // Two submeshes stay two, in order.
    MeshData two = box;
    two.submeshes = {{0, 18}, {18, 18}};
    const MeshData once = two.subdivided(1);
    ASSERT_EQ(once.submeshes.size(), 2u);
    EXPECT_EQ(once.submeshes[0].firstIndex, 0u);
    EXPECT_EQ(once.submeshes[0].indexCount, 72u);
    EXPECT_EQ(once.submeshes[1].firstIndex, 72u);
}

} // namespace
} // namespace sp::render
