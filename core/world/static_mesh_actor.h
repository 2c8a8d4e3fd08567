#pragma once
// AStaticMeshActor: an actor whose root is a static mesh component.

#include "core/world/actor.h"
#include "core/world/static_mesh_component.h"

/// An actor that shows one static mesh.
SPCLASS()
class AStaticMeshActor : public AActor {
    SP_GENERATED_BODY()
  public:
    AStaticMeshActor() {
        StaticMeshComponent = CreateDefaultSubobject<UStaticMeshComponent>("StaticMeshComponent");
    }

    /// The mesh component (also the root component).
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* StaticMeshComponent = nullptr;
};
