"""Negative typing case: every marked line must be rejected by mypy --strict with the pinned message."""

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
    actor.SetActorLocation(NewLocation="here")  # E: Argument "NewLocation" to "SetActorLocation" of "AActor" has incompatible type "str"; expected "FVector"  [arg-type]
    actor.Tagz  # E: "AStaticMeshActor" has no attribute "Tagz"  [attr-defined]
    actor.SetActorLocation()  # E: Missing named argument "NewLocation" for "SetActorLocation" of "AActor"  [call-arg]
    actor.SetActorLocation(spear.FVector())  # E: Too many positional arguments for "SetActorLocation" of "AActor"  [misc]
    height: int = actor.GetActorLocation()  # E: Incompatible types in assignment (expression has type "FVector", variable has type "int")  [assignment]
    mesh: spear.AStaticMeshActor = game.spawn_actor(uclass=spear.AActor)  # E: Incompatible types in assignment (expression has type "AActor", variable has type "AStaticMeshActor")  [assignment]
    game.find_actor_by_name(name="x").GetName()  # E: Item "None" of "Optional[AActor]" has no attribute "GetName"  [union-attr]
    actor.RootComponent = None  # E: Property "RootComponent" defined in "AActor" is read-only  [misc]
    actor.StaticMeshComponent.Mobility = 2  # E: Incompatible types in assignment (expression has type "int", variable has type "EComponentMobility")  [assignment]
    spear.FVector(Q=1.0)  # E: Unexpected keyword argument "Q" for "FVector"  [call-arg]
    game.spawn_actor(uclass=spear.FVector)  # E: Value of type variable "_AActorT" of "spawn_actor" of "UWorld" cannot be "FVector"  [type-var]
    actor.StaticMeshComponent.SetMaterial(ElementIndex=0.5, Material="m")  # E: Argument "ElementIndex" to "SetMaterial" of "UStaticMeshComponent" has incompatible type "float"; expected "int"  [arg-type]


def misuse_async(instance: spear.Instance) -> None:
    actor = instance.get_game().spawn_actor(uclass=spear.AActor)
    wrong: spear.FVector = actor.call_async.GetActorLocation()  # E: Incompatible types in assignment (expression has type "Future[FVector]", variable has type "FVector")  [assignment]
    actor.call_async.SetActorLocation(NewLocation=1.0)  # E: Argument "NewLocation" to "SetActorLocation" of "AActorAsync" has incompatible type "float"; expected "FVector"  [arg-type]
