#include "core/physics/detail/collision_shape_builder.h"

#include <algorithm>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <LinearMath/btConvexHullComputer.h>

#include "core/base/error.h"
#include "core/physics/detail/bullet_convert.h"

namespace sp::physics::detail {

namespace {

// Bullet's default collision margin. Boxes and cylinders carry it inside their extents and hulls are
// shrunk by it, so it only rounds edges; it is reduced for small shapes so that it never dominates them.
constexpr btScalar kMaxMargin = 0.04;

btScalar marginFor(double smallestHalfSize) {
    return std::min(kMaxMargin, btScalar(0.2 * smallestHalfSize));
}

BuiltShape buildConvexHull(const Shape& shape) {
    // Eigen's 3-vectors of doubles are three packed btScalars (the double build), read in place.
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(btScalar));
    const std::vector<Eigen::Vector3d> points = shape.scaledPoints();
    const btScalar* coords = points.front().data();
    const int stride = int(sizeof(Eigen::Vector3d)), count = int(points.size());
    // Bullet inflates a hull by its margin; shrinking the hull by the same amount first keeps the
    // collision surface on the given points. The shrink is clamped for thin hulls, and the margin set
    // to whatever shrink was achieved.
    btConvexHullComputer computer;
    btScalar shrunk = computer.compute(coords, stride, count, kMaxMargin, 0.25);
    if (shrunk < 0 || computer.vertices.size() < 4) {
        computer.compute(coords, stride, count, 0, 0);
        shrunk = 0;
    }
    auto hull = std::make_unique<btConvexHullShape>();
    for (int i = 0; i < computer.vertices.size(); ++i)
        hull->addPoint(computer.vertices[i], false);
    hull->recalcLocalAabb();
    hull->setMargin(shrunk);
    BuiltShape built;
    built.shape = std::move(hull);
    return built;
}

BuiltShape buildTriangleMesh(const Shape& shape) {
    BuiltShape built;
    built.staticOnly = true;
    built.vertices.reserve(shape.points().size() * 3);
    for (const Eigen::Vector3d& p : shape.scaledPoints())
        built.vertices.insert(built.vertices.end(), {p.x(), p.y(), p.z()});
    built.indices.assign(shape.indices().begin(), shape.indices().end());

    btIndexedMesh part;
    part.m_numTriangles = int(built.indices.size() / 3);
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(built.indices.data());
    part.m_triangleIndexStride = int(3 * sizeof(int));
    part.m_numVertices = int(shape.points().size());
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(built.vertices.data());
    part.m_vertexStride = int(3 * sizeof(btScalar));
    part.m_vertexType = PHY_DOUBLE;
    built.mesh = std::make_unique<btTriangleIndexVertexArray>();
    built.mesh->addIndexedMesh(part, PHY_INTEGER);
    built.shape = std::make_unique<btBvhTriangleMeshShape>(built.mesh.get(), true);
    return built;
}

} // namespace

BuiltShape buildCollisionShape(const Shape& shape) {
    static_assert(sizeof(btScalar) == sizeof(double), "spear_physics needs Bullet in double precision");
    const Eigen::Vector3d& scale = shape.scale();
    BuiltShape built;
    switch (shape.type()) {
    case ShapeType::Box: {
        const Eigen::Vector3d half = shape.halfExtents().cwiseProduct(scale);
        auto box = std::make_unique<btBoxShape>(toBullet(half));
        box->setMargin(marginFor(half.minCoeff()));
        const Eigen::Vector3d centre = shape.centre().cwiseProduct(scale);
        if (centre.isZero()) {
            built.shape = std::move(box);
            return built;
        }
        // Off the origin: a compound of one child, which Bullet collides as the box itself (box-box and
        // sphere-box contacts, not a triangle's).
        built.child = std::move(box);
        auto compound = std::make_unique<btCompoundShape>(false, 1);
        compound->addChildShape(btTransform(btQuaternion::getIdentity(), toBullet(centre)),
                                built.child.get());
        built.shape = std::move(compound);
        built.staticOnly = true;
        return built;
    }
    case ShapeType::Sphere:
        // A sphere is all margin in Bullet: its surface is exact.
        built.shape = std::make_unique<btSphereShape>(shape.radius() * scale.x());
        return built;
    case ShapeType::Capsule:
        built.shape = std::make_unique<btCapsuleShapeZ>(shape.radius() * scale.x(),
                                                        2.0 * shape.halfHeight() * scale.z());
        return built;
    case ShapeType::Cylinder: {
        const double radius = shape.radius() * scale.x();
        const double halfHeight = shape.halfHeight() * scale.z();
        auto cylinder = std::make_unique<btCylinderShapeZ>(btVector3(radius, radius, halfHeight));
        cylinder->setMargin(marginFor(std::min(radius, halfHeight)));
        built.shape = std::move(cylinder);
        return built;
    }
    case ShapeType::Plane:
        built.shape =
            std::make_unique<btStaticPlaneShape>(toBullet(shape.scaledNormal()), shape.scaledOffset());
        built.staticOnly = true;
        return built;
    case ShapeType::ConvexHull:
        return buildConvexHull(shape);
    case ShapeType::TriangleMesh:
        return buildTriangleMesh(shape);
    }
    SP_THROW(InvalidArgument, "buildCollisionShape(): unknown shape type ", int(shape.type()));
}

} // namespace sp::physics::detail
