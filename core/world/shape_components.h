#pragma once
// Shape components: invisible collision shapes that generate overlaps (UE's UShapeComponent family), and
// the trigger actors built on them. They are sensors: bodies and traces pass through them; what enters
// or leaves them is read with GetOverlappingActors / GetBeginOverlaps / GetEndOverlaps.

#include "core/world/actor.h"
#include "core/world/primitive_component.h"

/// An invisible collision shape that generates overlaps; bodies and traces pass through it.
SPCLASS(Abstract)
class UShapeComponent : public UPrimitiveComponent {
    SP_GENERATED_BODY()
  public:
    UShapeComponent();
    bool IsOverlapOnly() const override { return true; }
};

/// A box-shaped sensor.
SPCLASS()
class UBoxComponent : public UShapeComponent {
    SP_GENERATED_BODY()
  public:
    /// Half the box's size along each axis, in metres before the component's scale (each > 0).
    SPPROPERTY(Setter = SetBoxExtent)
    FVector BoxExtent{0.5, 0.5, 0.5};

    /// Sets BoxExtent (each component finite and > 0).
    SPFUNCTION()
    void SetBoxExtent(const FVector& InBoxExtent);

    Eigen::AlignedBox3d GetLocalBounds() const override;
    ECollisionPrimitive GetMeshCollisionPrimitive() const override { return ECollisionPrimitive::Box; }

    // The world-axis box that holds this (possibly turned and scaled) box: a region for navigation or
    // procedural generation.
    Eigen::AlignedBox3d worldBox() const;
};

/// A sphere-shaped sensor.
SPCLASS()
class USphereComponent : public UShapeComponent {
    SP_GENERATED_BODY()
  public:
    /// The sphere's radius in metres before the component's scale (> 0).
    SPPROPERTY(Setter = SetSphereRadius)
    double SphereRadius = 0.5;

    /// Sets SphereRadius (finite, > 0).
    SPFUNCTION()
    void SetSphereRadius(double InSphereRadius);

    Eigen::AlignedBox3d GetLocalBounds() const override;
    ECollisionPrimitive GetMeshCollisionPrimitive() const override { return ECollisionPrimitive::Sphere; }
};

/// A capsule-shaped sensor standing along its Z axis (a character's collision capsule).
SPCLASS()
class UCapsuleComponent : public UShapeComponent {
    SP_GENERATED_BODY()
  public:
    /// The radius in metres before the component's scale (> 0).
    SPPROPERTY(Setter = SetCapsuleRadius)
    double CapsuleRadius = 0.35;

    /// Half the height in metres, hemispheres included, before the component's scale (> 0); a half height
    /// below the radius counts as the radius (a sphere), as in UE.
    SPPROPERTY(Setter = SetCapsuleHalfHeight)
    double CapsuleHalfHeight = 0.9;

    /// Sets CapsuleRadius (finite, > 0).
    SPFUNCTION()
    void SetCapsuleRadius(double Radius);
    /// Sets CapsuleHalfHeight (finite, > 0).
    SPFUNCTION()
    void SetCapsuleHalfHeight(double HalfHeight);

    Eigen::AlignedBox3d GetLocalBounds() const override;
    ECollisionPrimitive GetMeshCollisionPrimitive() const override { return ECollisionPrimitive::Capsule; }
};

/// A box-shaped trigger volume: an actor whose root is a UBoxComponent.
SPCLASS()
class ATriggerBox : public AActor {
    SP_GENERATED_BODY()
  public:
    ATriggerBox();

    /// The trigger's shape (the root component).
    SPPROPERTY(ReadOnly, NotNull)
    UBoxComponent* CollisionComponent = nullptr;
};

/// A sphere-shaped trigger volume: an actor whose root is a USphereComponent.
SPCLASS()
class ATriggerSphere : public AActor {
    SP_GENERATED_BODY()
  public:
    ATriggerSphere();

    /// The trigger's shape (the root component).
    SPPROPERTY(ReadOnly, NotNull)
    USphereComponent* CollisionComponent = nullptr;
};
