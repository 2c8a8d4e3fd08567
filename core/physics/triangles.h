#pragma once
// The surface of a collision shape as triangles, for those who need geometry rather than a solver
// shape: navigation meshes are rasterised from it, and it can be drawn. Curved shapes are tessellated;
// triangles wind counter-clockwise seen from outside (their right-hand normal points out of the solid),
// so a consumer can tell floors from ceilings by the normal.

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "core/physics/shape.h"

namespace sp::physics {

struct TriangleSoup {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<uint32_t> indices; // triples into vertices

    size_t triangleCount() const { return indices.size() / 3; }
    Eigen::AlignedBox3d bounds() const;
    // Appends another soup's triangles.
    void append(const TriangleSoup& other);
};

// Segments around the axis of a tessellated sphere, capsule or cylinder (half as many rings from pole
// to pole): a 1 m radius is within 2 cm of its polygon.
inline constexpr int kRoundSegments = 16;

// Appends the surface of `shape` placed at `pose` to `out`. Solids are closed surfaces; a triangle mesh
// keeps its own triangles and winding. An infinite plane becomes the square of it that covers `bounds`
// (the part of space the caller cares about), facing along the plane's normal; it adds nothing when
// `bounds` is empty.
void appendTriangles(const Shape& shape, const Eigen::Isometry3d& pose, const Eigen::AlignedBox3d& bounds,
                     TriangleSoup& out);

} // namespace sp::physics
