"""Negative typing case: misuse of a wheeled vehicle, of trigger volumes and of splines. Every marked line must be rejected by mypy --strict
(`# E:`) and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    car = instance.get_game().spawn_actor(uclass=spear.AWheeledVehiclePawn)
    car.GetWheelState(WheelIndex="0")  # E: Argument "WheelIndex" to "GetWheelState" of "AWheeledVehiclePawn" has incompatible type "str"; expected "int"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['0']" cannot be assigned to parameter "WheelIndex" of type "int" in function "GetWheelState" / "Literal['0']" is not assignable to "int"
    car.MaxSteerAngle = "35"  # E: Incompatible types in assignment (expression has type "str", variable has type "float")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "MaxSteerAngle" for class "AWheeledVehiclePawn" / "Literal['35']" is not assignable to "float"
    car.Mesh = car.Cabin  # E: Property "Mesh" defined in "AWheeledVehiclePawn" is read-only  [misc]  # P: reportAttributeAccessIssue: Cannot assign to attribute "Mesh" for class "AWheeledVehiclePawn" / "UStaticMeshComponent" is not assignable to "property"
    car.GetWheelState(WheelIndex=0).bInContact = 1  # E: Incompatible types in assignment (expression has type "int", variable has type "bool")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "bInContact" for class "FWheelState" / "Literal[1]" is not assignable to "bool"


def overlap_misuse(instance: spear.Instance) -> None:
    trigger = instance.get_game().spawn_actor(uclass=spear.ATriggerSphere)
    trigger.CollisionComponent.SphereRadius = "1"  # E: Incompatible types in assignment (expression has type "str", variable has type "float")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "SphereRadius" for class "USphereComponent" / "Literal['1']" is not assignable to "float"
    trigger.GetOverlappingActors(ClassFilter=spear.UBoxComponent)  # E: Value of type variable "_AActorT" of "GetOverlappingActors" of "AActor" cannot be "UBoxComponent"  [type-var]  # P: reportArgumentType: Argument of type "type[UBoxComponent]" cannot be assigned to parameter "ClassFilter" of type "str" in function "GetOverlappingActors" / Type "type[UBoxComponent]" is not assignable to type "str"  # P: reportCallIssue: No overloads for "GetOverlappingActors" match the provided arguments
    trigger.CollisionComponent.BoxExtent  # E: "USphereComponent" has no attribute "BoxExtent"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "BoxExtent" for class "USphereComponent" / Attribute "BoxExtent" is unknown


def spline_misuse(instance: spear.Instance) -> None:
    spline = instance.get_game().spawn_actor(uclass=spear.ASplineActor).SplineComponent
    spline.GetLocationAtDistanceAlongSpline(Distance=1.0, CoordinateSpace="World")  # E: Argument "CoordinateSpace" to "GetLocationAtDistanceAlongSpline" of "USplineComponent" has incompatible type "str"; expected "ESplineCoordinateSpace"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['World']" cannot be assigned to parameter "CoordinateSpace" of type "ESplineCoordinateSpace" in function "GetLocationAtDistanceAlongSpline" / "Literal['World']" is not assignable to "ESplineCoordinateSpace"
