#pragma once
// CPU-side triangle mesh: positions, normals, uvs, indices and submeshes (one material slot each).
// Pure logic, no GL.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sp::render {

// A contiguous range of `indices` drawn with one material slot.
struct Submesh {
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
};

struct MeshData {
    std::vector<Eigen::Vector3f> positions; // metres, mesh-local
    std::vector<Eigen::Vector3f> normals;   // unit; empty = computed (area-weighted smooth normals)
    std::vector<Eigen::Vector2f> uvs;       // empty = all zero
    std::vector<std::uint32_t> indices;     // triangle list, 3 per triangle
    std::vector<Submesh> submeshes;         // empty = one submesh covering all indices
    std::string name;

    // Builds a mesh from flat arrays: positions float32 (N,3), normals float32 (N,3) or empty,
    // uvs float32 (N,2) or empty, indices uint32 (M*3,), submeshOffsets uint32 (S,) = first index of
    // each submesh (empty = one submesh). Validates and fills defaults (see validate()).
    static MeshData fromArrays(std::span<const float> positions, std::span<const float> normals,
                               std::span<const float> uvs, std::span<const std::uint32_t> indices,
                               std::span<const std::uint32_t> submeshOffsets = {});

    // Checks consistency and fills defaults (normals, uvs, one submesh). Throws sp::InvalidArgument
    // "<function>(): <what is wrong>".
    void validate(const char* function);

    std::size_t submeshCount() const { return submeshes.size(); }
    // Axis-aligned bounds in mesh-local coordinates (zero when empty).
    void bounds(Eigen::Vector3f& min, Eigen::Vector3f& max) const;
    // Whether the mesh bounds a convex body (or is flat and convex): every vertex lies on one side of every
    // triangle's plane, either side, since imported windings are unreliable. False past kConvexCheckLimit
    // vertex-plane tests, without checking.
    bool convex() const;
    // Whether every triangle's vertex normals are its plane's normal (either sign): shaded flat, as a box's
    // faces. A convex, faceted surface cannot shadow itself (see shadow_reach.h); a smooth-shaded one can,
    // where its facets turn from the light before its normals do.
    bool faceted() const;
    // How far the vertex normals lean from the normals their triangles' windings give ((b - a) x (c - a)):
    // the tangent of the largest angle between a vertex normal and its triangle's winding normal, 0 for a
    // mesh shaded flat and wound as its normals face; +infinity where a vertex normal does not lean to its
    // triangle's winding side (inward windings, flipped normals). Triangles degenerate within float
    // precision are left out: they cover no pixel. Where it is finite, every fragment's
    // interpolated normal lies on the side its triangle is wound towards, so the rasteriser's facing tells
    // which way to turn it to the camera (see windingTurnsNormals()).
    float windingSpread() const;
    static constexpr std::size_t kConvexCheckLimit = 16u << 20;

    // The longest triangle edge, in mesh-local metres.
    float longestEdge() const;
    // Every triangle split into four at its edges' midpoints, `times` times over (shared edges split once,
    // so no cracks); normals (renormalised) and uvs interpolated, submeshes kept in order. The surface is
    // the same; what changes is where vertices are: the rasteriser's per-vertex indirect light needs them
    // no further apart than its probes (see Renderer::refineLevel()). Needs a validated mesh.
    MeshData subdivided(int times) const;
};

// Whether a mesh of windingSpread() `spread` drawn with `linear` (the instance's transform's linear part)
// keeps every vertex normal on its triangle's winding side, so that the rasteriser's facing turns its
// normals as screen derivatives of the position would. Normals and windings both turn by the cofactor of
// `linear`; for unit normals u (a vertex's) and w (its triangle's) at angle t, that keeps u's image on w's
// image's side while tan(t) (k^2 - 1) < 2, k the condition number of `linear` (half of it kept here, for
// rounding). A flat mesh keeps it under any invertible transform; a smooth one under near-uniform scales.
bool windingTurnsNormals(float spread, const Eigen::Matrix3d& linear);

} // namespace sp::render
