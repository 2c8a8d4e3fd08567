"""Mistakes mypy must catch in code that uses a plugin."""

from __future__ import annotations

import numpy as np

import spear
from my_plugin.api import AMyActor, APointFilter


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    points_filter = game.spawn_actor(uclass=APointFilter)
    points_filter.Filter(Points=np.zeros((4, 3)), Center=spear.FVector(), Radius=0.5)  # E: Argument "Points" to "Filter" of "APointFilter" has incompatible type "ndarray[Any, dtype[floating[_64Bit]]]"; expected "ndarray[Any, dtype[floating[_32Bit]]]"  [arg-type]
    points_filter.Filter(Point=np.zeros((4, 3), dtype=np.float32), Center=spear.FVector(), Radius=0.5)  # E: Unexpected keyword argument "Point" for "Filter" of "APointFilter"; did you mean "Points"?  [call-arg]
    result = points_filter.Filter(Points=np.zeros((4, 3), dtype=np.float32), Center=spear.FVector(), Radius=0.5)
    print(result["Indexes"])  # E: TypedDict "FPointFilterResult" has no key "Indexes"  [typeddict-item]
    points_filter.PointsSeen = 3  # E: Property "PointsSeen" defined in "APointFilter" is read-only  [misc]
    my_actor = game.spawn_actor(uclass=AMyActor)
    my_actor.Initialise()  # E: "AMyActor" has no attribute "Initialise"; maybe "Initialize"?  [attr-defined]
    sp_result = my_actor.call_sp_func("my_sp_func", arrays={"input": np.zeros(3)})
    print(sp_result["array"])  # E: TypedDict "SpFuncResult" has no key "array"  [typeddict-item]
    my_actor.call_sp_func("my_sp_func", info=3)  # E: Argument "info" to "call_sp_func" of "SpObject" has incompatible type "int"; expected "str"  [arg-type]
