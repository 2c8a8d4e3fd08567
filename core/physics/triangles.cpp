#include "core/physics/triangles.h"

#include <cmath>
#include <utility>

#include <LinearMath/btConvexHullComputer.h>

#include "core/base/error.h"

namespace sp::physics {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Appends the vertices of `local` (already scaled) placed at `pose`; returns the index of the first.
uint32_t appendVertices(const std::vector<Eigen::Vector3d>& local, const Eigen::Isometry3d& pose,
                        TriangleSoup& out) {
    const auto first = uint32_t(out.vertices.size());
    for (const Eigen::Vector3d& v : local)
        out.vertices.push_back(pose * v);
    return first;
}

void appendBox(const Eigen::Vector3d& half, const Eigen::Isometry3d& pose, TriangleSoup& out) {
    std::vector<Eigen::Vector3d> corners;
    std::vector<uint32_t> indices;
    for (int axis = 0; axis < 3; ++axis) {
        for (double sign : {1.0, -1.0}) {
            // u x v points along sign * axis, so (-,-), (+,-), (+,+), (-,+) winds outwards.
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            if (sign < 0)
                std::swap(u, v);
            const auto base = uint32_t(corners.size());
            for (auto [su, sv] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) {
                Eigen::Vector3d p = Eigen::Vector3d::Zero();
                p[axis] = sign * half[axis];
                p[u] = su * half[u];
                p[v] = sv * half[v];
                corners.push_back(p);
            }
            indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    }
    const uint32_t first = appendVertices(corners, pose, out);
    for (uint32_t i : indices)
        out.indices.push_back(first + i);
}

// A surface of revolution about local Z through the profile (radius, z), listed from the bottom pole to
// the top; a zero radius is a pole (one vertex). Each band winds outwards.
void appendRevolved(const std::vector<std::pair<double, double>>& profile, const Eigen::Isometry3d& pose,
                    TriangleSoup& out) {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<uint32_t> ringStart;
    for (auto [radius, z] : profile) {
        ringStart.push_back(uint32_t(vertices.size()));
        if (radius == 0.0) {
            vertices.emplace_back(0.0, 0.0, z);
            continue;
        }
        for (int s = 0; s < kRoundSegments; ++s) {
            const double angle = 2.0 * kPi * s / kRoundSegments;
            vertices.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
        }
    }
    const uint32_t first = appendVertices(vertices, pose, out);
    auto at = [&](size_t ring, int segment) {
        if (profile[ring].first == 0.0)
            return first + ringStart[ring];
        return first + ringStart[ring] + uint32_t(segment % kRoundSegments);
    };
    for (size_t ring = 0; ring + 1 < profile.size(); ++ring) {
        const bool lowerPole = profile[ring].first == 0.0, upperPole = profile[ring + 1].first == 0.0;
        for (int s = 0; s < kRoundSegments; ++s) {
            const uint32_t a = at(ring, s), b = at(ring, s + 1), c = at(ring + 1, s + 1), d = at(ring + 1, s);
            if (!lowerPole)
                out.indices.insert(out.indices.end(), {a, b, c});
            if (!upperPole)
                out.indices.insert(out.indices.end(), {a, c, d});
        }
    }
}

// The profile of a sphere of `radius` split at the equator, the halves shifted by -/+ halfLength (a
// capsule; a sphere for halfLength 0).
std::vector<std::pair<double, double>> capsuleProfile(double radius, double halfLength) {
    std::vector<std::pair<double, double>> profile;
    const int rings = kRoundSegments / 2;
    for (int k = 0; k <= rings; ++k) {
        const double theta = -kPi / 2 + kPi * k / rings;
        const double r = k == 0 || k == rings ? 0.0 : radius * std::cos(theta);
        const double z = radius * std::sin(theta);
        if (2 * k == rings) { // the equator: one ring per half
            profile.emplace_back(r, z - halfLength);
            if (halfLength > 0.0)
                profile.emplace_back(r, z + halfLength);
            continue;
        }
        profile.emplace_back(r, z + (2 * k < rings ? -halfLength : halfLength));
    }
    return profile;
}

void appendConvexHull(const Shape& shape, const Eigen::Isometry3d& pose, TriangleSoup& out) {
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
    const std::vector<Eigen::Vector3d> points = shape.scaledPoints(); // packed doubles, read in place
    btConvexHullComputer hull;
    hull.compute(points.front().data(), int(sizeof(Eigen::Vector3d)), int(points.size()), 0, 0);
    std::vector<Eigen::Vector3d> vertices;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int i = 0; i < hull.vertices.size(); ++i) {
        vertices.emplace_back(hull.vertices[i].x(), hull.vertices[i].y(), hull.vertices[i].z());
        centroid += vertices.back();
    }
    if (vertices.empty())
        return;
    centroid /= double(vertices.size());
    const uint32_t first = appendVertices(vertices, pose, out);
    for (int f = 0; f < hull.faces.size(); ++f) {
        std::vector<int> loop;
        const btConvexHullComputer::Edge* start = &hull.edges[hull.faces[f]];
        const btConvexHullComputer::Edge* edge = start;
        do {
            loop.push_back(edge->getTargetVertex());
            edge = edge->getNextEdgeOfFace();
        } while (edge != start && loop.size() <= vertices.size());
        // A fan over the face, turned to face away from the centroid (the hull is convex).
        for (size_t i = 1; i + 1 < loop.size(); ++i) {
            const Eigen::Vector3d &p0 = vertices[size_t(loop[0])], &p1 = vertices[size_t(loop[i])],
                                  &p2 = vertices[size_t(loop[i + 1])];
            const bool outward = (p1 - p0).cross(p2 - p0).dot(p0 - centroid) >= 0.0;
            const uint32_t i0 = first + uint32_t(loop[0]), i1 = first + uint32_t(loop[i]),
                           i2 = first + uint32_t(loop[i + 1]);
            if (outward)
                out.indices.insert(out.indices.end(), {i0, i1, i2});
            else
                out.indices.insert(out.indices.end(), {i0, i2, i1});
        }
    }
}

void appendPlane(const Shape& shape, const Eigen::Isometry3d& pose, const Eigen::AlignedBox3d& bounds,
                 TriangleSoup& out) {
    if (bounds.isEmpty())
        return;
    const Eigen::Vector3d localNormal = shape.scaledNormal();
    const double offset = shape.scaledOffset();
    const Eigen::Vector3d normal = pose.linear() * localNormal;
    const Eigen::Vector3d onPlane = pose * (localNormal * offset);
    const Eigen::Vector3d centre = bounds.center() - normal * normal.dot(bounds.center() - onPlane);
    const double half = bounds.diagonal().norm();
    // u x v = normal, so the square winds towards the normal.
    const Eigen::Vector3d u = normal.unitOrthogonal() * half;
    const Eigen::Vector3d v = normal.cross(u);
    const auto first = uint32_t(out.vertices.size());
    out.vertices.insert(out.vertices.end(), {centre - u - v, centre + u - v, centre + u + v, centre - u + v});
    out.indices.insert(out.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

} // namespace

Eigen::AlignedBox3d TriangleSoup::bounds() const {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& v : vertices)
        box.extend(v);
    return box;
}

void TriangleSoup::append(const TriangleSoup& other) {
    const auto first = uint32_t(vertices.size());
    vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
    for (uint32_t i : other.indices)
        indices.push_back(first + i);
}

void appendTriangles(const Shape& shape, const Eigen::Isometry3d& pose, const Eigen::AlignedBox3d& bounds,
                     TriangleSoup& out) {
    const Eigen::Vector3d& scale = shape.scale();
    switch (shape.type()) {
    case ShapeType::Box:
        appendBox(shape.halfExtents().cwiseProduct(scale),
                  pose * Eigen::Translation3d(shape.centre().cwiseProduct(scale)), out);
        return;
    case ShapeType::Sphere:
        appendRevolved(capsuleProfile(shape.radius() * scale.x(), 0.0), pose, out);
        return;
    case ShapeType::Capsule:
        appendRevolved(capsuleProfile(shape.radius() * scale.x(), shape.halfHeight() * scale.z()), pose, out);
        return;
    case ShapeType::Cylinder: {
        const double radius = shape.radius() * scale.x(), half = shape.halfHeight() * scale.z();
        appendRevolved({{0.0, -half}, {radius, -half}, {radius, half}, {0.0, half}}, pose, out);
        return;
    }
    case ShapeType::Plane:
        appendPlane(shape, pose, bounds, out);
        return;
    case ShapeType::ConvexHull:
        appendConvexHull(shape, pose, out);
        return;
    case ShapeType::TriangleMesh: {
        const uint32_t first = appendVertices(shape.scaledPoints(), pose, out);
        for (uint32_t i : shape.indices())
            out.indices.push_back(first + i);
        return;
    }
    }
    SP_THROW(InvalidArgument, "appendTriangles(): unknown shape type ", int(shape.type()));
}

} // namespace sp::physics
