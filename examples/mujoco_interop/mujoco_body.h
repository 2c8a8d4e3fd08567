#pragma once
// AMujocoBody: the spear actor that shows one MuJoCo body. AMujocoScene spawns one per body of the model it
// loads (the world body included) and moves it to the body's pose after every step; the body's geoms are
// the actor's mesh components, placed relative to its root as MuJoCo places them relative to the body.

#include <cstdint>
#include <string>

#include "core/world/actor.h"

/// One body of a MuJoCo model, shown in spear: its root is the body frame, its mesh components its geoms.
SPCLASS()
class AMujocoBody : public AActor {
    SP_GENERATED_BODY()
  public:
    AMujocoBody() { Body = CreateDefaultSubobject<USceneComponent>("Body"); }

    /// The body's name in the model ("world" for body 0, "body_<id>" for an unnamed body).
    SPPROPERTY(VisibleAnywhere)
    std::string BodyName;

    /// The body's index in the model (its row in AMujocoScene.GetBodyPoses()); -1 before it is loaded.
    SPPROPERTY(VisibleAnywhere)
    int32_t BodyId = -1;

    /// True for bodies welded to the world (Static components that never move); false for moving ones.
    SPPROPERTY(VisibleAnywhere)
    bool bStaticBody = false;

    /// The number of MuJoCo geoms the body has (a capsule is one geom shown by three meshes).
    SPPROPERTY(VisibleAnywhere)
    int32_t NumGeoms = 0;

    /// The body frame (the root component); each geom is a component attached to it, named after the geom.
    SPPROPERTY(ReadOnly, NotNull)
    USceneComponent* Body = nullptr;
};
