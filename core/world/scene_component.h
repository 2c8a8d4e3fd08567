#pragma once
// USceneComponent: a component with a transform, attachable to other scene components. World
// transforms are computed from the attachment chain when asked (no cached state to go stale).

#include <string>
#include <vector>

#include "core/world/actor_component.h"
#include "core/world/math.h"

/// Whether a component may move after it has been placed in a world.
SPENUM()
enum class EComponentMobility : uint8_t {
    /// Never moves once in play; moving it is an error.
    Static = 0,
    /// Does not move but its lighting may change.
    Stationary = 1,
    /// Free to move.
    Movable = 2,
};

/// A component with a location, rotation and scale, that can be attached to another one.
SPCLASS()
class USceneComponent : public UActorComponent {
    SP_GENERATED_BODY()
  public:
    /// Location relative to the attach parent (or the world), in metres.
    SPPROPERTY(Setter = SetRelativeLocation)
    FVector RelativeLocation;

    /// Rotation relative to the attach parent (or the world).
    SPPROPERTY(Setter = SetRelativeRotation)
    FRotator RelativeRotation;

    /// Scale relative to the attach parent (or the world).
    SPPROPERTY(Setter = SetRelativeScale3D)
    FVector RelativeScale3D{1.0, 1.0, 1.0};

    /// Whether the component may move once in play.
    SPPROPERTY()
    EComponentMobility Mobility = EComponentMobility::Movable;

    /// Whether the component is rendered.
    SPPROPERTY()
    bool bVisible = true;

    /// The socket of the attach parent this component follows (a skeletal mesh's bone: a camera on a head);
    /// empty: the parent itself. A name the parent does not have is followed as the parent itself.
    SPPROPERTY()
    std::string AttachSocketName;

    /// Sets the location relative to the attach parent; fails for a static component in play.
    SPFUNCTION()
    void SetRelativeLocation(const FVector& NewLocation);

    /// Sets the rotation relative to the attach parent; fails for a static component in play.
    SPFUNCTION()
    void SetRelativeRotation(const FRotator& NewRotation);

    /// Sets the scale relative to the attach parent; fails for a static component in play.
    SPFUNCTION()
    void SetRelativeScale3D(const FVector& NewScale3D);

    /// Sets location, rotation and scale relative to the attach parent.
    SPFUNCTION()
    void SetRelativeTransform(const FTransform& NewTransform);

    /// Returns the transform relative to the attach parent.
    SPFUNCTION()
    FTransform GetRelativeTransform() const;

    /// Sets the mobility (Static, Stationary or Movable).
    SPFUNCTION()
    void SetMobility(EComponentMobility NewMobility) { Mobility = NewMobility; }

    /// Returns the world-space transform.
    SPFUNCTION()
    FTransform GetComponentTransform() const;

    /// Returns the world-space location in metres.
    SPFUNCTION()
    FVector GetComponentLocation() const;

    /// Returns the world-space location in metres (the Blueprint name of GetComponentLocation).
    SPFUNCTION()
    FVector K2_GetComponentLocation() const { return GetComponentLocation(); }

    /// Returns the world-space rotation.
    SPFUNCTION()
    FRotator GetComponentRotation() const;

    /// Returns the world-space scale.
    SPFUNCTION()
    FVector GetComponentScale() const;

    /// Moves the component so that its world-space location is NewLocation.
    SPFUNCTION()
    void SetWorldLocation(const FVector& NewLocation);

    /// Rotates the component so that its world-space rotation is NewRotation.
    SPFUNCTION()
    void SetWorldRotation(const FRotator& NewRotation);

    /// Sets the world-space transform.
    SPFUNCTION()
    void SetWorldTransform(const FTransform& NewTransform);

    /// Returns the unit vector along the component's world-space X axis.
    SPFUNCTION()
    FVector GetForwardVector() const;

    /// Returns the unit vector along the component's world-space Y axis (left).
    SPFUNCTION()
    FVector GetRightVector() const;

    /// Returns the unit vector along the component's world-space Z axis.
    SPFUNCTION()
    FVector GetUpVector() const;

    /// Attaches this component to Parent, following its socket SocketName when one is named (a skeletal
    /// mesh's bone); keeps the world transform when bKeepWorldTransform is true. Raises NotFoundError when
    /// Parent has no socket SocketName.
    SPFUNCTION()
    void AttachToComponent(USceneComponent* Parent, bool bKeepWorldTransform = false,
                           const std::string& SocketName = "");

    /// Detaches this component from its parent; keeps the world transform when bKeepWorldTransform is true.
    SPFUNCTION()
    void DetachFromComponent(bool bKeepWorldTransform = true);

    /// Returns the world transform of socket InSocketName: the component's own for an empty name or a
    /// component without sockets; a skeletal mesh's sockets are its bones.
    SPFUNCTION()
    virtual FTransform GetSocketTransform(const std::string& InSocketName) const;

    /// Returns true when the component has a socket named InSocketName.
    SPFUNCTION()
    virtual bool DoesSocketExist(const std::string& InSocketName) const;

    /// Returns the component this one is attached to, or None.
    SPFUNCTION()
    USceneComponent* GetAttachParent() const { return parent_; }

    /// Returns the attached children, and their descendants when bIncludeAllDescendants is true.
    SPFUNCTION()
    std::vector<USceneComponent*> GetChildrenComponents(bool bIncludeAllDescendants = false) const;

    ~USceneComponent() override;

  private:
    // Throws InvalidState for a static component that is in play: moving it would desynchronise the
    // renderer and physics, which treat it as fixed.
    void checkMovable(const char* function) const;

    USceneComponent* parent_ = nullptr;
    std::vector<USceneComponent*> children_;
};
