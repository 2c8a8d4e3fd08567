"""Mistakes mypy (`# E:`) and pyright (`# P:`) must catch in code that uses a plugin."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import numpy as np

import spear
from my_plugin.api import AMyActor, APointFilter


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    points_filter = game.spawn_actor(uclass=APointFilter)
    points_filter.Filter(Points=np.zeros((4, 3)), Center=spear.FVector(), Radius=0.5)  # E: Argument "Points" to "Filter" of "APointFilter" has incompatible type "ndarray[Any, dtype[floating[_64Bit]]]"; expected "ndarray[Any, dtype[floating[_32Bit]]]"  [arg-type]  # P: reportArgumentType: Argument of type "NDArray[float64]" cannot be assigned to parameter "Points" of type "NDArray[float32]" in function "Filter" / "ndarray[Any, dtype[float64]]" is not assignable to "ndarray[Any, dtype[float32]]" / Type parameter "_DType_co@ndarray" is covariant, but "dtype[float64]" is not a subtype of "dtype[float32]" / "dtype[float64]" is not assignable to "dtype[float32]" / Type parameter "_DTypeScalar_co@dtype" is covariant, but "float64" is not a subtype of "float32" / "floating[_64Bit]" is not assignable to "floating[_32Bit]"
    points_filter.Filter(Point=np.zeros((4, 3), dtype=np.float32), Center=spear.FVector(), Radius=0.5)  # E: Unexpected keyword argument "Point" for "Filter" of "APointFilter"; did you mean "Points"?  [call-arg]  # P: reportCallIssue: Argument missing for parameter "Points"  # P: reportCallIssue: No parameter named "Point"
    result = points_filter.Filter(Points=np.zeros((4, 3), dtype=np.float32), Center=spear.FVector(), Radius=0.5)
    print(result["Indexes"])  # E: TypedDict "FPointFilterResult" has no key "Indexes"  [typeddict-item]  # P: reportGeneralTypeIssues: Could not access item in TypedDict / "Indexes" is not a defined key in "FPointFilterResult"
    points_filter.PointsSeen = 3  # E: Property "PointsSeen" defined in "APointFilter" is read-only  [misc]  # P: reportAttributeAccessIssue: Cannot assign to attribute "PointsSeen" for class "APointFilter" / "Literal[3]" is not assignable to "property"
    my_actor = game.spawn_actor(uclass=AMyActor)
    my_actor.Initialise()  # E: "AMyActor" has no attribute "Initialise"; maybe "Initialize"?  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "Initialise" for class "AMyActor" / Attribute "Initialise" is unknown
    sp_result = my_actor.call_sp_func("my_sp_func", arrays={"input": np.zeros(3)})
    print(sp_result["array"])  # E: TypedDict "SpFuncResult" has no key "array"  [typeddict-item]  # P: reportGeneralTypeIssues: Could not access item in TypedDict / "array" is not a defined key in "SpFuncResult"
    my_actor.call_sp_func("my_sp_func", info=3)  # E: Argument "info" to "call_sp_func" of "SpObject" has incompatible type "int"; expected "str"  [arg-type]  # P: reportArgumentType: Argument of type "Literal[3]" cannot be assigned to parameter "info" of type "str" in function "call_sp_func" / "Literal[3]" is not assignable to "str"
