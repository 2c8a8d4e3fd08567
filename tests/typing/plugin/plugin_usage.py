"""A plugin's classes type-check like the engine's: spawn by class, typed SPFUNCTIONs with dtype-typed
arrays, typed SpFunc results."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

import spear
from my_plugin.api import AArrayTools, AMyActor, APointFilter, FPointFilterResult


def use(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        my_actor: AMyActor = game.spawn_actor(uclass=AMyActor)
        my_actor.Initialize()
        result: spear.SpFuncResult = my_actor.call_sp_func("my_sp_func", arrays={"input": np.zeros(3)})
        output: NDArray[np.float64] = result["arrays"]["output"]
        info: str = result["info"]
        names: list[str] = my_actor.get_sp_func_names()

        points_filter = game.spawn_actor(uclass=APointFilter)
        inside: FPointFilterResult = points_filter.Filter(
            Points=np.zeros((4, 3), dtype=np.float32), Center=spear.FVector(), Radius=0.5)
        rows: NDArray[np.int64] = inside["Indices"]
        seen: int = points_filter.PointsSeen

        tools = game.spawn_actor(uclass=AArrayTools)
        held: list[str] = tools.SpFuncComponent.GetFuncNames()
        mine: list[AMyActor] = game.find_actors_by_class(uclass=AMyActor)
        print(output, info, names, rows, seen, held, mine)
