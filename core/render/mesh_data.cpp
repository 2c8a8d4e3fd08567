#include "core/render/mesh_data.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "core/base/error.h"

namespace sp::render {

MeshData MeshData::fromArrays(std::span<const float> positions, std::span<const float> normals,
                              std::span<const float> uvs, std::span<const std::uint32_t> indices,
                              std::span<const std::uint32_t> submeshOffsets) {
    constexpr const char* fn = "MeshData::fromArrays";
    SP_CHECK(positions.size() % 3 == 0, InvalidArgument, fn, "(): positions must have shape (N,3), got ",
             positions.size(), " floats");
    const std::size_t n = positions.size() / 3;
    SP_CHECK(normals.empty() || normals.size() == n * 3, InvalidArgument, fn,
             "(): normals must be empty or have shape (", n, ",3), got ", normals.size(), " floats");
    SP_CHECK(uvs.empty() || uvs.size() == n * 2, InvalidArgument, fn, "(): uvs must be empty or have shape (",
             n, ",2), got ", uvs.size(), " floats");
    MeshData mesh;
    mesh.positions.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        mesh.positions[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    if (!normals.empty()) {
        mesh.normals.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            mesh.normals[i] = {normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    }
    if (!uvs.empty()) {
        mesh.uvs.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            mesh.uvs[i] = {uvs[2 * i], uvs[2 * i + 1]};
    }
    mesh.indices.assign(indices.begin(), indices.end());
    for (std::size_t s = 0; s < submeshOffsets.size(); ++s) {
        const std::uint32_t first = submeshOffsets[s];
        const std::uint32_t end = s + 1 < submeshOffsets.size() ? submeshOffsets[s + 1]
                                                                : static_cast<std::uint32_t>(indices.size());
        SP_CHECK(first <= end, InvalidArgument, fn, "(): submeshOffsets must be increasing, got ", first,
                 " before ", end);
        mesh.submeshes.push_back({first, end - first});
    }
    mesh.validate(fn);
    return mesh;
}

void MeshData::validate(const char* function) {
    const std::size_t n = positions.size();
    SP_CHECK(n > 0, InvalidArgument, function, "(): mesh '", name, "' has no vertices");
    SP_CHECK(!indices.empty() && indices.size() % 3 == 0, InvalidArgument, function, "(): mesh '", name,
             "' needs a non-empty triangle list (indices divisible by 3), got ", indices.size(), " indices");
    for (std::size_t i = 0; i < indices.size(); ++i)
        SP_CHECK(indices[i] < n, InvalidArgument, function, "(): mesh '", name, "' index[", i,
                 "] = ", indices[i], " is out of range for ", n, " vertices");
    for (std::size_t i = 0; i < n; ++i)
        SP_CHECK(positions[i].allFinite(), InvalidArgument, function, "(): mesh '", name, "' position[", i,
                 "] is not finite");
    SP_CHECK(normals.empty() || normals.size() == n, InvalidArgument, function, "(): mesh '", name, "' has ",
             normals.size(), " normals for ", n, " vertices");
    SP_CHECK(uvs.empty() || uvs.size() == n, InvalidArgument, function, "(): mesh '", name, "' has ",
             uvs.size(), " uvs for ", n, " vertices");
    if (submeshes.empty())
        submeshes.push_back({0, static_cast<std::uint32_t>(indices.size())});
    for (std::size_t s = 0; s < submeshes.size(); ++s) {
        const Submesh& sub = submeshes[s];
        SP_CHECK(sub.indexCount % 3 == 0 && sub.firstIndex % 3 == 0 &&
                     std::size_t(sub.firstIndex) + sub.indexCount <= indices.size(),
                 InvalidArgument, function, "(): mesh '", name, "' submesh ", s, " [", sub.firstIndex, ", +",
                 sub.indexCount, ") must cover whole triangles within ", indices.size(), " indices");
    }
    if (uvs.empty())
        uvs.assign(n, Eigen::Vector2f::Zero());
    if (normals.empty()) {
        normals.assign(n, Eigen::Vector3f::Zero());
        for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
            const Eigen::Vector3f& a = positions[indices[t]];
            // Unnormalized cross product weights each face by its area.
            Eigen::Vector3f faceNormal = (positions[indices[t + 1]] - a).cross(positions[indices[t + 2]] - a);
            for (int k = 0; k < 3; ++k)
                normals[indices[t + k]] += faceNormal;
        }
    }
    for (Eigen::Vector3f& normal : normals) {
        const float length = normal.norm();
        normal = length > 0.0f && std::isfinite(length) ? Eigen::Vector3f(normal / length)
                                                        : Eigen::Vector3f::UnitZ();
    }
}

void MeshData::bounds(Eigen::Vector3f& min, Eigen::Vector3f& max) const {
    min = max = Eigen::Vector3f::Zero();
    if (positions.empty())
        return;
    min = max = positions[0];
    for (const Eigen::Vector3f& p : positions) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
}

bool MeshData::convex() const {
    const std::size_t triangles = indices.size() / 3;
    if (triangles == 0 || triangles * positions.size() > kConvexCheckLimit)
        return false;
    Eigen::Vector3f min, max;
    bounds(min, max);
    // Tolerances relative to the mesh's size: float rounding of the vertices (a tessellated sphere's lie on
    // it only to that precision), and slivers whose plane that rounding decides (a sphere's pole triangles).
    const double size = std::max(double((max - min).norm()), 1e-9);
    const double tolerance = 1e-5 * size, sliver = 1e-10 * size * size;
    for (std::size_t t = 0; t < triangles; ++t) {
        const Eigen::Vector3d a = positions[indices[3 * t]].cast<double>();
        const Eigen::Vector3d normal = (positions[indices[3 * t + 1]].cast<double>() - a)
                                           .cross(positions[indices[3 * t + 2]].cast<double>() - a);
        if (normal.norm() <= sliver)
            continue;
        const Eigen::Vector3d unit = normal.normalized();
        bool above = false, below = false;
        for (const Eigen::Vector3f& p : positions) {
            const double side = unit.dot(p.cast<double>() - a);
            above = above || side > tolerance;
            below = below || side < -tolerance;
        }
        if (above && below)
            return false;
    }
    return true;
}

float MeshData::windingSpread() const {
    // The smallest cosine between a vertex normal and its triangle's winding normal gives the largest
    // tangent; compared squared (no square root or normalisation per vertex: a skinned mesh is described
    // again every frame).
    double smallestSquaredCosine = 1.0;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Eigen::Vector3d a = positions[indices[t]].cast<double>();
        const Eigen::Vector3d ab = positions[indices[t + 1]].cast<double>() - a;
        const Eigen::Vector3d ac = positions[indices[t + 2]].cast<double>() - a;
        const Eigen::Vector3d winding = ab.cross(ac);
        const double windingSquared = winding.squaredNorm();
        // Degenerate within float precision (a sphere's pole, where sin(pi) is not 0 in float): its winding
        // is rounding, and it covers no pixel (nor would its screen derivatives say anything there).
        const double edgeSquared = std::max(ab.squaredNorm(), ac.squaredNorm());
        if (windingSquared <= 1e-14 * edgeSquared * edgeSquared)
            continue;
        for (std::size_t v = t; v < t + 3; ++v) {
            const Eigen::Vector3d normal = normals[indices[v]].cast<double>();
            const double dot = winding.dot(normal);
            const double squaredCosine = dot * dot / (windingSquared * normal.squaredNorm());
            if (!(dot > 0.0 && squaredCosine > 1e-12)) // a cosine of 1e-6 or less, or a zero normal
                return std::numeric_limits<float>::infinity();
            smallestSquaredCosine = std::min(smallestSquaredCosine, squaredCosine);
        }
    }
    const double cosine = std::sqrt(std::min(1.0, smallestSquaredCosine));
    return float(std::sqrt(std::max(0.0, 1.0 - cosine * cosine)) / cosine);
}

bool windingTurnsNormals(float spread, const Eigen::Matrix3d& linear) {
    if (!std::isfinite(spread))
        return false;
    const double determinant = linear.determinant();
    if (!std::isfinite(determinant) || determinant == 0.0)
        return false; // draws nothing; no need to decide
    if (spread == 0.0f)
        return true;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(linear.transpose() * linear, Eigen::EigenvaluesOnly);
    const Eigen::Vector3d squares = solver.eigenvalues(); // the singular values squared, ascending
    return squares(0) > 0.0 && double(spread) * (squares(2) / squares(0) - 1.0) < 1.0;
}

bool MeshData::faceted() const {
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Eigen::Vector3f& a = positions[indices[t]];
        const Eigen::Vector3f normal = (positions[indices[t + 1]] - a).cross(positions[indices[t + 2]] - a);
        if (normal.squaredNorm() <= 0.0f)
            continue; // degenerate: no plane
        const Eigen::Vector3f unit = normal.normalized();
        for (std::size_t v = t; v < t + 3; ++v)
            if (std::abs(unit.dot(normals[indices[v]])) < 0.9999f)
                return false;
    }
    return true;
}

float MeshData::longestEdge() const {
    float longest = 0.0f; // squared, until the end: one square root, not one an edge
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
        for (int e = 0; e < 3; ++e)
            longest = std::max(longest, (positions[indices[t + std::size_t(e)]] -
                                         positions[indices[t + std::size_t((e + 1) % 3)]])
                                            .squaredNorm());
    return std::sqrt(longest);
}

MeshData MeshData::subdivided(int times) const {
    MeshData mesh = *this;
    for (int k = 0; k < times; ++k) {
        MeshData next;
        next.positions = mesh.positions;
        next.normals = mesh.normals;
        next.uvs = mesh.uvs;
        next.indices.reserve(mesh.indices.size() * 4);
        // One midpoint per edge, whichever triangle asks first.
        std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            const auto [it, added] = midpoints.try_emplace(key, std::uint32_t(next.positions.size()));
            if (added) {
                next.positions.push_back(0.5f * (mesh.positions[a] + mesh.positions[b]));
                const Eigen::Vector3f n = mesh.normals[a] + mesh.normals[b];
                next.normals.push_back(n.squaredNorm() > 1e-12f ? n.normalized() : mesh.normals[a]);
                next.uvs.push_back(0.5f * (mesh.uvs[a] + mesh.uvs[b]));
            }
            return it->second;
        };
        for (const Submesh& sub : mesh.submeshes) {
            const std::uint32_t first = std::uint32_t(next.indices.size());
            const std::uint32_t end = sub.firstIndex + sub.indexCount / 3 * 3;
            for (std::uint32_t t = sub.firstIndex; t < end; t += 3) {
                const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
                const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
                next.indices.insert(next.indices.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
            }
            next.submeshes.push_back({first, std::uint32_t(next.indices.size()) - first});
        }
        mesh = std::move(next);
    }
    return mesh;
}

} // namespace sp::render
