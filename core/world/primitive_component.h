#pragma once
// UPrimitiveComponent: a scene component with geometry: bounds, and a rigid body in the world's
// PhysicsSubsystem while it is in play. The physics properties below are plain data; the subsystem
// reads them when it synchronises (before each physics step, raycast or physics call), so they may be
// set through their setters, the registry or a scene file, before or during play.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/reflect/class_ref.h"

#include "core/world/scene_component.h"

/// Which collision geometry a primitive component gets in the physics world.
SPENUM()
enum class ECollisionPrimitive : uint8_t {
    /// The shape of the mesh: Cube is a box, Sphere a sphere, Cylinder a cylinder, Plane a plane; a mesh
    /// file is its convex hull when it simulates physics and its triangles otherwise.
    FromMesh = 0,
    /// A box filling the mesh bounds.
    Box = 1,
    /// A sphere around the mesh bounds (radius: the largest half extent).
    Sphere = 2,
    /// A cylinder along local Z around the mesh bounds.
    Cylinder = 3,
    /// A two-sided rectangle across the mesh bounds at their centre height; cannot be simulated.
    Plane = 4,
    /// No collision: the component has no body, is not simulated and is not hit by traces.
    NoCollision = 5,
    /// The convex hull of a mesh file's vertices (what a simulated mesh file collides as).
    ConvexHull = 6,
    /// The triangles of a mesh file; static or kinematic only (what an unsimulated mesh file collides as).
    TriangleMesh = 7,
    /// A capsule along local Z filling the bounds: radius the larger XY half extent, height the Z extent.
    Capsule = 8,
};

/// A scene component that has geometry.
SPCLASS(Abstract)
class UPrimitiveComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Whether physics moves this component (gravity, forces, contacts); it must be Movable.
    SPPROPERTY(Setter = SetSimulatePhysics)
    bool bSimulatePhysics = false;

    /// The collision geometry used by physics and traces.
    SPPROPERTY()
    ECollisionPrimitive CollisionPrimitive = ECollisionPrimitive::FromMesh;

    /// Mass in kilograms (> 0 to simulate); inertia follows the collision shape at uniform density.
    SPPROPERTY(Setter = SetMassOverrideInKg)
    double MassInKg = 1.0;

    /// Coulomb friction coefficient (>= 0); the two coefficients at a contact are multiplied.
    SPPROPERTY(Setter = SetFriction)
    double Friction = 0.5;

    /// Bounciness in [0, 1]; the two coefficients at a contact are multiplied.
    SPPROPERTY(Setter = SetRestitution, meta = (ClampMin = 0, ClampMax = 1))
    double Restitution = 0.0;

    /// Fraction of linear velocity lost per second, in [0, 1].
    SPPROPERTY(Setter = SetLinearDamping, meta = (ClampMin = 0, ClampMax = 1))
    double LinearDamping = 0.0;

    /// Fraction of angular velocity lost per second, in [0, 1].
    SPPROPERTY(Setter = SetAngularDamping, meta = (ClampMin = 0, ClampMax = 1))
    double AngularDamping = 0.0;

    /// Whether this component takes part in overlaps: two components overlap only when both have it set
    /// (as in UE). Shape components (UBoxComponent, USphereComponent) have it set by default.
    SPPROPERTY()
    bool bGenerateOverlapEvents = false;

    /// Whether navigation meshes are built over this component when it is Static and collides (as in UE).
    SPPROPERTY()
    bool bCanEverAffectNavigation = true;

    /// Returns the world-space axis-aligned bounds as centre Origin and half size BoxExtent.
    SPFUNCTION()
    void GetBounds(FVector& Origin, FVector& BoxExtent) const;

    /// Turns physics simulation on or off; turning it on needs a Movable component with collision.
    SPFUNCTION()
    void SetSimulatePhysics(bool bSimulate);

    /// Returns true while physics moves this component.
    SPFUNCTION()
    bool IsSimulatingPhysics() const;

    /// Sets the mass in kilograms (> 0).
    SPFUNCTION()
    void SetMassOverrideInKg(double MassInKg);

    /// Sets the Coulomb friction coefficient (finite, >= 0).
    SPFUNCTION()
    void SetFriction(double NewFriction);

    /// Sets the bounciness, in [0, 1].
    SPFUNCTION()
    void SetRestitution(double NewRestitution);

    /// Sets the fraction of linear velocity lost per second, in [0, 1].
    SPFUNCTION()
    void SetLinearDamping(double NewLinearDamping);

    /// Sets the fraction of angular velocity lost per second, in [0, 1].
    SPFUNCTION()
    void SetAngularDamping(double NewAngularDamping);

    /// Returns the mass in kilograms.
    SPFUNCTION()
    double GetMass() const { return MassInKg; }

    /// Adds a force in newtons at the centre of mass for the next physics step (an acceleration in m/s^2
    /// when bAccelChange is true).
    SPFUNCTION()
    void AddForce(const FVector& Force, bool bAccelChange = false);

    /// Adds a torque in newton-metres about world axes for the next physics step.
    SPFUNCTION()
    void AddTorqueInRadians(const FVector& Torque);

    /// Changes the velocity at once by Impulse / mass (Impulse in N*s; a velocity change in m/s when
    /// bVelChange is true).
    SPFUNCTION()
    void AddImpulse(const FVector& Impulse, bool bVelChange = false);

    /// Sets the linear velocity in m/s (adds it to the current one when bAddToCurrent is true).
    SPFUNCTION()
    void SetPhysicsLinearVelocity(const FVector& NewVel, bool bAddToCurrent = false);

    /// Returns the linear velocity in m/s (zero when not simulated).
    SPFUNCTION()
    FVector GetPhysicsLinearVelocity() const;

    /// Sets the angular velocity in degrees per second about world axes.
    SPFUNCTION()
    void SetPhysicsAngularVelocityInDegrees(const FVector& NewAngVel, bool bAddToCurrent = false);

    /// Returns the angular velocity in degrees per second about world axes (zero when not simulated).
    SPFUNCTION()
    FVector GetPhysicsAngularVelocityInDegrees() const;

    /// Returns true while this component's body is awake (false for sleeping or non-simulated ones).
    SPFUNCTION()
    bool IsAnyRigidBodyAwake() const;

    /// Returns the components of other actors whose collision shapes touch or intersect this one's now
    /// (both must generate overlap events), in the order they entered play.
    SPFUNCTION()
    std::vector<UPrimitiveComponent*> GetOverlappingComponents() const;

    /// Returns the actors (of class ClassFilter or a subclass) that own the components overlapping this one.
    SPFUNCTION(DeterminesOutputType = ClassFilter)
    std::vector<AActor*> GetOverlappingActors(TSubclassOf<AActor> ClassFilter) const;

    /// Returns true when OtherComp overlaps this component now.
    SPFUNCTION()
    bool IsOverlappingComponent(const UPrimitiveComponent* OtherComp) const;

    /// Returns true when a component of Other overlaps this component now.
    SPFUNCTION()
    bool IsOverlappingActor(const AActor* Other) const;

    /// Returns the components that began overlapping this one in the last frame's physics step (UE's
    /// OnComponentBeginOverlap, polled).
    SPFUNCTION()
    std::vector<UPrimitiveComponent*> GetBeginOverlaps() const;

    /// Returns the components that stopped overlapping this one in the last frame's physics step (UE's
    /// OnComponentEndOverlap, polled); destroyed ones are left out.
    SPFUNCTION()
    std::vector<UPrimitiveComponent*> GetEndOverlaps() const;

    // True for sensors (trigger shapes): bodies and traces pass through them; they only overlap.
    virtual bool IsOverlapOnly() const { return false; }

    // Bounds in the component's own space (before its scale); empty when it has no geometry.
    virtual Eigen::AlignedBox3d GetLocalBounds() const { return {}; }
    // World-space bounds of the transformed local box.
    Eigen::AlignedBox3d GetWorldBounds() const;
    // The primitive that FromMesh resolves to; NoCollision for a component without a known shape.
    virtual ECollisionPrimitive GetMeshCollisionPrimitive() const { return ECollisionPrimitive::Box; }

    void BeginPlay() override;
};

namespace sp::world {
// A mesh component's SetMaterial (static and skeletal alike): sets slot `index` of `materials`, growing the
// list as needed; an index outside [0, 256) is refused naming `function`.
void setMaterialSlot(std::vector<std::string>& materials, int index, const std::string& material,
                     const char* function);
} // namespace sp::world
