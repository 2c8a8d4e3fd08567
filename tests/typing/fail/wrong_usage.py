"""Negative typing case: every marked line must be rejected by mypy --strict (`# E:`) and by
pyright (`# P: rule: message`) with the pinned messages."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
    actor.SetActorLocation(NewLocation="here")  # E: Argument "NewLocation" to "SetActorLocation" of "AActor" has incompatible type "str"; expected "FVector"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['here']" cannot be assigned to parameter "NewLocation" of type "FVector" in function "SetActorLocation" / "Literal['here']" is not assignable to "FVector"
    actor.Tagz  # E: "AStaticMeshActor" has no attribute "Tagz"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "Tagz" for class "AStaticMeshActor" / Attribute "Tagz" is unknown
    actor.SetActorLocation()  # E: Missing named argument "NewLocation" for "SetActorLocation" of "AActor"  [call-arg]  # P: reportCallIssue: Argument missing for parameter "NewLocation"
    actor.SetActorLocation(spear.FVector())  # E: Too many positional arguments for "SetActorLocation" of "AActor"  [misc]  # P: reportCallIssue: Expected 0 positional arguments
    height: int = actor.GetActorLocation()  # E: Incompatible types in assignment (expression has type "FVector", variable has type "int")  [assignment]  # P: reportAssignmentType: Type "FVector" is not assignable to declared type "int" / "FVector" is not assignable to "int"
    mesh: spear.AStaticMeshActor = game.spawn_actor(uclass=spear.AActor)  # E: Incompatible types in assignment (expression has type "AActor", variable has type "AStaticMeshActor")  [assignment]  # P: reportAssignmentType: Type "AActor" is not assignable to declared type "AStaticMeshActor" / "AActor" is not assignable to "AStaticMeshActor"
    game.find_actor_by_name(name="x").GetName()  # E: Item "None" of "Optional[AActor]" has no attribute "GetName"  [union-attr]  # P: reportOptionalMemberAccess: "GetName" is not a known attribute of "None"
    actor.RootComponent = None  # E: Property "RootComponent" defined in "AActor" is read-only  [misc]  # P: reportAttributeAccessIssue: Cannot assign to attribute "RootComponent" for class "AStaticMeshActor" / "None" is not assignable to "property"
    actor.StaticMeshComponent.Mobility = 2  # E: Incompatible types in assignment (expression has type "int", variable has type "EComponentMobility")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "Mobility" for class "UStaticMeshComponent" / "Literal[2]" is not assignable to "EComponentMobility"
    actor.GetActorLocation().x = 5.0  # E: "FVector" has no attribute "x"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot assign to attribute "x" for class "FVector" / Attribute "x" is unknown
    spear.FVector(Q=1.0)  # E: Unexpected keyword argument "Q" for "FVector"  [call-arg]  # P: reportCallIssue: No parameter named "Q"
    game.spawn_actor(uclass=spear.FVector)  # E: Value of type variable "_AActorT" of "spawn_actor" of "UWorld" cannot be "FVector"  [type-var]  # P: reportArgumentType: Argument of type "type[FVector]" cannot be assigned to parameter "uclass" of type "str" in function "spawn_actor" / Type "type[FVector]" is not assignable to type "str"  # P: reportCallIssue: No overloads for "spawn_actor" match the provided arguments
    actor.StaticMeshComponent.SetMaterial(ElementIndex=0.5, Material="m")  # E: Argument "ElementIndex" to "SetMaterial" of "UStaticMeshComponent" has incompatible type "float"; expected "int"  [arg-type]  # P: reportArgumentType: Argument of type "float" cannot be assigned to parameter "ElementIndex" of type "int" in function "SetMaterial" / "float" is not assignable to "int"


def misuse_async(instance: spear.Instance) -> None:
    actor = instance.get_game().spawn_actor(uclass=spear.AActor)
    wrong: spear.FVector = actor.call_async.GetActorLocation()  # E: Incompatible types in assignment (expression has type "Future[FVector]", variable has type "FVector")  [assignment]  # P: reportAssignmentType: Type "Future[FVector]" is not assignable to declared type "FVector" / "Future[FVector]" is not assignable to "FVector"
    actor.call_async.SetActorLocation(NewLocation=1.0)  # E: Argument "NewLocation" to "SetActorLocation" of "AActorAsync" has incompatible type "float"; expected "FVector"  [arg-type]  # P: reportArgumentType: Argument of type "float" cannot be assigned to parameter "NewLocation" of type "FVector" in function "SetActorLocation" / "float" is not assignable to "FVector"
