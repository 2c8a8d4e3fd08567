#pragma once
// A collision shape description: a value type that says what a body's geometry is. PhysicsWorld builds
// the Bullet shape from it when a body is added, so a Shape can be kept, copied and reused freely.

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace sp::physics {

// The kind of geometry a Shape describes.
enum class ShapeType { Box, Sphere, Capsule, Cylinder, Plane, ConvexHull, TriangleMesh };

// Writes the type's name ("Box", "TriangleMesh", ...).
std::ostream& operator<<(std::ostream& out, ShapeType type);

// Geometry in the body's local frame, centred on the body origin (which is also its centre of mass).
// Capsules and cylinders run along local Z. Planes and triangle meshes cannot be simulated (they may
// be static, or movable without simulation).
class Shape {
  public:
    // A box with the given half extents in metres (each > 0), its centre at `centre` in the body's frame. A
    // box off the body's origin suits static geometry (a floor slab under a flat mesh's face) and cannot be
    // simulated: a simulated body turns about its origin.
    static Shape box(const Eigen::Vector3d& halfExtents,
                     const Eigen::Vector3d& centre = Eigen::Vector3d::Zero());
    // A sphere of the given radius in metres (> 0).
    static Shape sphere(double radius);
    // A capsule along Z: a segment of length 2 * halfLength capped by hemispheres of the given radius,
    // so its total height is 2 * (halfLength + radius). radius > 0, halfLength >= 0.
    static Shape capsule(double radius, double halfLength);
    // A cylinder along Z of the given radius and total height 2 * halfHeight (both > 0).
    static Shape cylinder(double radius, double halfHeight);
    // The infinite plane {x : normal . x = offset} in local coordinates; the solid side is opposite the
    // normal. normal: 3 doubles, nonzero (normalised here).
    static Shape plane(const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ(), double offset = 0.0);
    // The convex hull of the given points (at least 4, not all in one plane), local coordinates.
    static Shape convexHull(std::vector<Eigen::Vector3d> points);
    // A triangle mesh: vertices in local coordinates, indices as triples into vertices (size a nonzero
    // multiple of 3). Triangles collide from both sides.
    static Shape triangleMesh(std::vector<Eigen::Vector3d> vertices, std::vector<uint32_t> indices);

    // This shape with its geometry scaled per local axis (each factor > 0). Spheres take a uniform
    // scale only; capsules and cylinders need scale.x() == scale.y(). Scales compose by multiplication.
    Shape scaled(const Eigen::Vector3d& scale) const;

    ShapeType type() const { return type_; }
    // Per-axis scale applied to the unscaled parameters below; (1, 1, 1) unless scaled() was used.
    const Eigen::Vector3d& scale() const { return scale_; }
    // Box half extents before scaling; zero for other shapes.
    const Eigen::Vector3d& halfExtents() const { return halfExtents_; }
    // Box centre before scaling; zero for other shapes.
    const Eigen::Vector3d& centre() const { return centre_; }
    // Sphere, capsule or cylinder radius before scaling; zero for other shapes.
    double radius() const { return radius_; }
    // Capsule halfLength or cylinder halfHeight before scaling; zero for other shapes.
    double halfHeight() const { return halfHeight_; }
    // Plane unit normal before scaling; zero for other shapes.
    const Eigen::Vector3d& normal() const { return normal_; }
    // Plane offset before scaling; zero for other shapes.
    double offset() const { return offset_; }
    // Convex hull points or mesh vertices before scaling; empty for other shapes.
    const std::vector<Eigen::Vector3d>& points() const;
    // The same with the scale applied (what the solver and the triangles use): points scaled per axis, and
    // the plane {x : normal . x = offset} after scaling space by S, which maps n . x = d to
    // (S^-1 n) . x = d, renormalised.
    std::vector<Eigen::Vector3d> scaledPoints() const;
    Eigen::Vector3d scaledNormal() const;
    double scaledOffset() const;
    // Mesh indices; empty for other shapes.
    const std::vector<uint32_t>& indices() const;

  private:
    explicit Shape(ShapeType type) : type_(type) {}

    ShapeType type_;
    Eigen::Vector3d scale_ = Eigen::Vector3d::Ones();
    Eigen::Vector3d halfExtents_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
    double radius_ = 0.0;
    double halfHeight_ = 0.0;
    Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();
    double offset_ = 0.0;
    // Shared so that copying a BodyDesc does not copy a large mesh.
    std::shared_ptr<const std::vector<Eigen::Vector3d>> points_;
    std::shared_ptr<const std::vector<uint32_t>> indices_;
};

} // namespace sp::physics
