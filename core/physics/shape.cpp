#include "core/physics/shape.h"

#include <cmath>
#include <ostream>

#include <Eigen/Eigenvalues>

#include "core/base/error.h"
#include "core/physics/detail/format.h"

namespace sp::physics {

namespace {

using detail::Vec;

bool isPositive(double value) {
    return std::isfinite(value) && value > 0.0;
}

void checkPoints(const char* function, const char* what, const std::vector<Eigen::Vector3d>& points) {
    for (size_t i = 0; i < points.size(); ++i)
        SP_CHECK(points[i].allFinite(), InvalidArgument, function, ": ", what, " ", i, " ", Vec{points[i]},
                 " is not finite");
}

const std::vector<Eigen::Vector3d> kNoPoints;
const std::vector<uint32_t> kNoIndices;

} // namespace

std::ostream& operator<<(std::ostream& out, ShapeType type) {
    switch (type) {
    case ShapeType::Box:
        return out << "Box";
    case ShapeType::Sphere:
        return out << "Sphere";
    case ShapeType::Capsule:
        return out << "Capsule";
    case ShapeType::Cylinder:
        return out << "Cylinder";
    case ShapeType::Plane:
        return out << "Plane";
    case ShapeType::ConvexHull:
        return out << "ConvexHull";
    case ShapeType::TriangleMesh:
        return out << "TriangleMesh";
    }
    return out << "ShapeType(" << int(type) << ')';
}

Shape Shape::box(const Eigen::Vector3d& halfExtents, const Eigen::Vector3d& centre) {
    SP_CHECK(isPositive(halfExtents.x()) && isPositive(halfExtents.y()) && isPositive(halfExtents.z()),
             InvalidArgument, "Shape::box(): half extents ", Vec{halfExtents}, " must all be > 0");
    SP_CHECK(centre.allFinite(), InvalidArgument, "Shape::box(): centre ", Vec{centre}, " is not finite");
    Shape shape(ShapeType::Box);
    shape.halfExtents_ = halfExtents;
    shape.centre_ = centre;
    return shape;
}

Shape Shape::sphere(double radius) {
    SP_CHECK(isPositive(radius), InvalidArgument, "Shape::sphere(): radius ", radius, " must be > 0");
    Shape shape(ShapeType::Sphere);
    shape.radius_ = radius;
    return shape;
}

Shape Shape::capsule(double radius, double halfLength) {
    SP_CHECK(isPositive(radius), InvalidArgument, "Shape::capsule(): radius ", radius, " must be > 0");
    SP_CHECK(std::isfinite(halfLength) && halfLength >= 0.0, InvalidArgument, "Shape::capsule(): halfLength ",
             halfLength, " must be >= 0");
    Shape shape(ShapeType::Capsule);
    shape.radius_ = radius;
    shape.halfHeight_ = halfLength;
    return shape;
}

Shape Shape::cylinder(double radius, double halfHeight) {
    SP_CHECK(isPositive(radius), InvalidArgument, "Shape::cylinder(): radius ", radius, " must be > 0");
    SP_CHECK(isPositive(halfHeight), InvalidArgument, "Shape::cylinder(): halfHeight ", halfHeight,
             " must be > 0");
    Shape shape(ShapeType::Cylinder);
    shape.radius_ = radius;
    shape.halfHeight_ = halfHeight;
    return shape;
}

Shape Shape::plane(const Eigen::Vector3d& normal, double offset) {
    SP_CHECK(normal.allFinite() && normal.norm() > 1e-12, InvalidArgument, "Shape::plane(): normal ",
             Vec{normal}, " must be finite and nonzero");
    SP_CHECK(std::isfinite(offset), InvalidArgument, "Shape::plane(): offset ", offset, " must be finite");
    Shape shape(ShapeType::Plane);
    // Keep the same plane when normalising: n.x = d  <=>  (n/|n|).x = d/|n|.
    shape.normal_ = normal.normalized();
    shape.offset_ = offset / normal.norm();
    return shape;
}

Shape Shape::convexHull(std::vector<Eigen::Vector3d> points) {
    SP_CHECK(points.size() >= 4, InvalidArgument, "Shape::convexHull(): ", points.size(),
             " points given; a hull needs at least 4");
    checkPoints("Shape::convexHull()", "point", points);
    // A hull with no volume (all points on a plane or a line) has no inertia and no inside; the
    // smallest principal spread of the points says whether they span 3D.
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points)
        mean += p;
    mean /= double(points.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    double extent = 0.0;
    for (const Eigen::Vector3d& p : points) {
        covariance += (p - mean) * (p - mean).transpose();
        extent = std::max(extent, (p - mean).norm());
    }
    covariance /= double(points.size());
    const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues()(0);
    SP_CHECK(extent > 0.0 && std::sqrt(std::max(smallest, 0.0)) > 1e-6 * extent, InvalidArgument,
             "Shape::convexHull(): the ", points.size(), " points lie in one plane; a hull needs volume");
    Shape shape(ShapeType::ConvexHull);
    shape.points_ = std::make_shared<const std::vector<Eigen::Vector3d>>(std::move(points));
    return shape;
}

Shape Shape::triangleMesh(std::vector<Eigen::Vector3d> vertices, std::vector<uint32_t> indices) {
    SP_CHECK(!indices.empty() && indices.size() % 3 == 0, InvalidArgument,
             "Shape::triangleMesh(): ", indices.size(), " indices given; need a nonzero multiple of 3");
    checkPoints("Shape::triangleMesh()", "vertex", vertices);
    for (size_t i = 0; i < indices.size(); ++i)
        SP_CHECK(indices[i] < vertices.size(), InvalidArgument, "Shape::triangleMesh(): index ", i, " is ",
                 indices[i], " but there are only ", vertices.size(), " vertices");
    Shape shape(ShapeType::TriangleMesh);
    shape.points_ = std::make_shared<const std::vector<Eigen::Vector3d>>(std::move(vertices));
    shape.indices_ = std::make_shared<const std::vector<uint32_t>>(std::move(indices));
    return shape;
}

Shape Shape::scaled(const Eigen::Vector3d& scale) const {
    SP_CHECK(isPositive(scale.x()) && isPositive(scale.y()) && isPositive(scale.z()), InvalidArgument,
             "Shape::scaled(): scale ", Vec{scale}, " must be > 0 on every axis");
    Eigen::Vector3d combined = scale_.cwiseProduct(scale);
    // Bullet's sphere, capsule and cylinder keep one radius, so their cross-section must stay round. Equal
    // within a relative 1e-6, then made equal: a scale read back from a rotated transform (a quaternion and a
    // matrix's column norms) differs from 1 in its last bits, which is no request for an ellipsoid.
    const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(a, b); };
    if (type_ == ShapeType::Sphere) {
        SP_CHECK(same(combined.x(), combined.y()) && same(combined.y(), combined.z()), InvalidArgument,
                 "Shape::scaled(): scale ", Vec{combined},
                 " is not uniform; a sphere takes a uniform scale only");
        combined.setConstant(combined.x());
    }
    if (type_ == ShapeType::Capsule || type_ == ShapeType::Cylinder) {
        SP_CHECK(same(combined.x(), combined.y()), InvalidArgument, "Shape::scaled(): scale ", Vec{combined},
                 " has x != y; a ", type_, " along Z needs the same scale on x and y");
        combined.y() = combined.x();
    }
    Shape result = *this;
    result.scale_ = combined;
    return result;
}

const std::vector<Eigen::Vector3d>& Shape::points() const {
    return points_ ? *points_ : kNoPoints;
}

std::vector<Eigen::Vector3d> Shape::scaledPoints() const {
    std::vector<Eigen::Vector3d> scaled;
    scaled.reserve(points().size());
    for (const Eigen::Vector3d& p : points())
        scaled.push_back(p.cwiseProduct(scale_));
    return scaled;
}

Eigen::Vector3d Shape::scaledNormal() const {
    return normal_.cwiseQuotient(scale_).normalized();
}

double Shape::scaledOffset() const {
    return offset_ / normal_.cwiseQuotient(scale_).norm();
}

const std::vector<uint32_t>& Shape::indices() const {
    return indices_ ? *indices_ : kNoIndices;
}

} // namespace sp::physics
