#pragma once
// UInputComponent: receives the input actions injected for its actor (UWorld.inject_input_for_actor) and
// holds each one for the next world tick, where the actor's Tick reads it. Actions are continuous,
// vector-valued (like UE's Enhanced Input Axis3D); scalar actions use X.

#include <map>
#include <string>

#include "core/world/actor_component.h"
#include "core/world/math.h"

/// A component that receives input actions injected for the actor that owns it.
SPCLASS()
class UInputComponent : public UActorComponent {
    SP_GENERATED_BODY()
  public:
    /// Returns the value of ActionName injected for the current tick, or zero when it was not injected.
    SPFUNCTION()
    FVector GetActionValue(const std::string& ActionName) const;

    /// Returns true when ActionName was injected for the current tick.
    SPFUNCTION()
    bool IsActionTriggered(const std::string& ActionName) const;

    // Records an action for the next world tick (a later injection of the same action replaces it).
    void InjectAction(const std::string& actionName, const FVector& value);

  private:
    // Whether actions_ belong to the current tick: an injection holds for the first tick after it.
    bool isCurrent() const;

    std::map<std::string, FVector> actions_;
    int64_t injectedForFrame_ = -1; // the world's frame count during the tick that consumes the actions
};
