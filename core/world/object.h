#pragma once
// UObject: the root of the engine's reflected class hierarchy (actors, components, worlds).

#include <string>

#include "core/reflect/macros.h"
#include "core/reflect/object_base.h"

class UWorld;

/// The base class of every engine object.
SPCLASS(Abstract)
class UObject : public sp::reflect::ObjectBase {
    SP_GENERATED_BODY()
  public:
    UObject() = default;
    ~UObject() override = default;

    /// Returns the object's name, unique among its siblings.
    SPFUNCTION()
    std::string GetName() const { return name_; }

    /// Returns the name of the object's class: its blueprint when it was spawned from one, else its most
    /// derived native class.
    SPFUNCTION()
    std::string GetClassName() const;

    /// Returns the world this object lives in, or None for objects outside any world.
    SPFUNCTION()
    UWorld* GetWorld() const { return world_; }

    std::string GetDebugName() const override;

    // Set by whoever creates the object, before anyone else can see it.
    void InitObject(std::string name, UWorld* world) {
        name_ = std::move(name);
        world_ = world;
    }

  private:
    std::string name_;
    UWorld* world_ = nullptr;
};
