#include "core/render/primitives.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/base/error.h"

namespace sp::render::primitives {
namespace {

void addQuad(MeshData& mesh, const Eigen::Vector3f& corner, const Eigen::Vector3f& du,
             const Eigen::Vector3f& dv, const Eigen::Vector3f& normal) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const Eigen::Vector2f uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const Eigen::Vector3f p[4] = {corner, corner + du, corner + du + dv, corner + dv};
    for (int i = 0; i < 4; ++i) {
        mesh.positions.push_back(p[i]);
        mesh.normals.push_back(normal);
        mesh.uvs.push_back(uv[i]);
    }
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
        mesh.indices.push_back(base + i);
}

} // namespace

MeshData box(const Eigen::Vector3f& size) {
    SP_CHECK((size.array() > 0.0f).all(), InvalidArgument, "primitives::box(): size must be positive, got (",
             size.transpose(), ")");
    MeshData mesh;
    mesh.name = "box";
    const Eigen::Vector3f h = 0.5f * size;
    const Eigen::Vector3f X = Eigen::Vector3f::UnitX() * size.x(), Y = Eigen::Vector3f::UnitY() * size.y(),
                          Z = Eigen::Vector3f::UnitZ() * size.z();
    // Each face is counter-clockwise seen from outside (du x dv = outward normal).
    addQuad(mesh, {h.x(), -h.y(), -h.z()}, Y, Z, Eigen::Vector3f::UnitX());
    addQuad(mesh, {-h.x(), h.y(), -h.z()}, -Y, Z, -Eigen::Vector3f::UnitX());
    addQuad(mesh, {h.x(), h.y(), -h.z()}, -X, Z, Eigen::Vector3f::UnitY());
    addQuad(mesh, {-h.x(), -h.y(), -h.z()}, X, Z, -Eigen::Vector3f::UnitY());
    addQuad(mesh, {-h.x(), -h.y(), h.z()}, X, Y, Eigen::Vector3f::UnitZ());
    addQuad(mesh, {-h.x(), h.y(), -h.z()}, X, -Y, -Eigen::Vector3f::UnitZ());
    mesh.validate("primitives::box");
    return mesh;
}

MeshData sphere(float radius, int segments, int rings) {
    SP_CHECK(radius > 0.0f, InvalidArgument, "primitives::sphere(): radius must be positive, got ", radius);
    SP_CHECK(segments >= 3 && rings >= 2, InvalidArgument,
             "primitives::sphere(): need segments >= 3 and rings >= 2, got ", segments, " and ", rings);
    MeshData mesh;
    mesh.name = "sphere";
    for (int r = 0; r <= rings; ++r) {
        const float theta = float(M_PI) * r / rings; // from +Z down
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * float(M_PI) * s / segments;
            Eigen::Vector3f n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
            mesh.positions.push_back(radius * n);
            mesh.normals.push_back(n);
            mesh.uvs.push_back({float(s) / segments, float(r) / rings});
        }
    }
    const auto stride = static_cast<std::uint32_t>(segments + 1);
    for (std::uint32_t r = 0; r < std::uint32_t(rings); ++r)
        for (std::uint32_t s = 0; s < std::uint32_t(segments); ++s) {
            const std::uint32_t a = r * stride + s, b = a + stride;
            for (std::uint32_t i : {a, b, b + 1, a, b + 1, a + 1})
                mesh.indices.push_back(i);
        }
    mesh.validate("primitives::sphere");
    return mesh;
}

MeshData plane(float sizeX, float sizeY) {
    SP_CHECK(sizeX > 0.0f && sizeY > 0.0f, InvalidArgument,
             "primitives::plane(): sizes must be positive, got ", sizeX, " x ", sizeY);
    MeshData mesh;
    mesh.name = "plane";
    addQuad(mesh, {-0.5f * sizeX, -0.5f * sizeY, 0.0f}, {sizeX, 0, 0}, {0, sizeY, 0},
            Eigen::Vector3f::UnitZ());
    mesh.validate("primitives::plane");
    return mesh;
}

MeshData cylinder(float radius, float height, int segments) {
    SP_CHECK(radius > 0.0f && height > 0.0f && segments >= 3, InvalidArgument,
             "primitives::cylinder(): need radius > 0, height > 0, segments >= 3, got ", radius, ", ", height,
             ", ", segments);
    MeshData mesh;
    mesh.name = "cylinder";
    const float h = 0.5f * height;
    for (int s = 0; s <= segments; ++s) { // side: pairs of (bottom, top) vertices
        const float phi = 2.0f * float(M_PI) * s / segments;
        Eigen::Vector3f n(std::cos(phi), std::sin(phi), 0.0f);
        for (float z : {-h, h}) {
            mesh.positions.push_back(Eigen::Vector3f(radius * n.x(), radius * n.y(), z));
            mesh.normals.push_back(n);
            mesh.uvs.push_back({float(s) / segments, z > 0 ? 1.0f : 0.0f});
        }
    }
    for (std::uint32_t s = 0; s < std::uint32_t(segments); ++s) {
        const std::uint32_t a = 2 * s;
        for (std::uint32_t i : {a, a + 2, a + 3, a, a + 3, a + 1})
            mesh.indices.push_back(i);
    }
    for (float side : {-1.0f, 1.0f}) { // caps: a centre vertex and a ring
        const auto centre = static_cast<std::uint32_t>(mesh.positions.size());
        const Eigen::Vector3f n(0, 0, side);
        mesh.positions.push_back(Eigen::Vector3f(0, 0, side * h));
        mesh.normals.push_back(n);
        mesh.uvs.push_back({0.5f, 0.5f});
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * float(M_PI) * s / segments;
            mesh.positions.push_back(
                Eigen::Vector3f(radius * std::cos(phi), radius * std::sin(phi), side * h));
            mesh.normals.push_back(n);
            mesh.uvs.push_back({0.5f + 0.5f * std::cos(phi), 0.5f + 0.5f * std::sin(phi)});
        }
        for (std::uint32_t s = 0; s < std::uint32_t(segments); ++s) {
            const std::uint32_t a = centre + 1 + s;
            if (side > 0)
                mesh.indices.insert(mesh.indices.end(), {centre, a, a + 1});
            else
                mesh.indices.insert(mesh.indices.end(), {centre, a + 1, a});
        }
    }
    mesh.validate("primitives::cylinder");
    return mesh;
}

MeshData tube(const std::vector<Eigen::Vector3f>& path, float radius, int sides) {
    SP_CHECK(radius > 0.0f && std::isfinite(radius) && sides >= 3, InvalidArgument,
             "primitives::tube(): radius ", radius, " must be > 0 and sides ", sides, " >= 3");
    std::vector<Eigen::Vector3f> points;
    for (const Eigen::Vector3f& p : path)
        if (points.empty() || (p - points.back()).norm() > 1e-6f)
            points.push_back(p);
    SP_CHECK(points.size() >= 2, InvalidArgument,
             "primitives::tube(): the path needs two distinct points, got ", points.size());
    MeshData mesh;
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();
    for (size_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector3f tangent =
            (points[std::min(i + 1, points.size() - 1)] - points[i == 0 ? 0 : i - 1]).normalized();
        // The previous ring's normal, turned into this ring's plane (the first: any perpendicular).
        normal = i == 0 ? tangent.unitOrthogonal() : (normal - tangent * tangent.dot(normal));
        if (normal.norm() < 1e-6f)
            normal = tangent.unitOrthogonal();
        normal.normalize();
        const Eigen::Vector3f binormal = tangent.cross(normal);
        for (int s = 0; s < sides; ++s) {
            const float angle = 2.0f * float(M_PI) * float(s) / float(sides);
            const Eigen::Vector3f out = std::cos(angle) * normal + std::sin(angle) * binormal;
            mesh.positions.push_back(points[i] + radius * out);
            mesh.normals.push_back(out);
            mesh.uvs.emplace_back(float(s) / float(sides), float(i) / float(points.size() - 1));
        }
    }
    const auto ring = [&](size_t i, int s) { return std::uint32_t(i * size_t(sides) + size_t(s % sides)); };
    for (size_t i = 0; i + 1 < points.size(); ++i)
        for (int s = 0; s < sides; ++s)
            mesh.indices.insert(mesh.indices.end(), {ring(i, s), ring(i, s + 1), ring(i + 1, s + 1),
                                                     ring(i, s), ring(i + 1, s + 1), ring(i + 1, s)});
    mesh.name = "tube";
    mesh.validate("primitives::tube()");
    return mesh;
}

} // namespace sp::render::primitives
