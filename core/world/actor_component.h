#pragma once
// UActorComponent: a piece of an actor's behaviour or data, owned by exactly one actor.

#include <string>
#include <vector>

#include "core/world/object.h"

class AActor;

/// A component that adds behaviour to the actor that owns it.
SPCLASS(Abstract)
class UActorComponent : public UObject {
    SP_GENERATED_BODY()
  public:
    /// Tags for finding this component.
    SPPROPERTY()
    std::vector<std::string> ComponentTags;

    /// Whether TickComponent runs every frame.
    SPPROPERTY()
    bool bTickEnabled = true;

    /// Returns the actor that owns this component.
    SPFUNCTION()
    AActor* GetOwner() const { return owner_; }

    /// Returns true when ComponentTags contains Tag.
    SPFUNCTION()
    bool ComponentHasTag(const std::string& Tag) const;

    // Engine hooks.
    virtual void BeginPlay() {}
    virtual void TickComponent(double /*deltaSeconds*/) {}
    virtual void EndPlay() {}

    void SetOwner(AActor* owner) { owner_ = owner; }
    // Between a successful BeginPlay() and EndPlay() (set by the owning actor): what the world's subsystems
    // have been told of (sp::world::WorldSubsystem::OnComponentBeginPlay).
    bool HasBegunPlay() const { return begunPlay_; }
    void SetBegunPlay(bool begun) { begunPlay_ = begun; }

  private:
    AActor* owner_ = nullptr;
    bool begunPlay_ = false;
};
