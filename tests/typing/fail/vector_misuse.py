"""Negative typing case: a vector env's actions have the type its environments take, and an environment
class must have the whole Env protocol."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

import spear
from spear.vector import Box, Discrete, StepResult, VectorEnv


class Turn:
    observation_space: Mapping[str, Box] = {"angle": Box((1,), np.float32)}
    action_space = Discrete(3)

    def reset(self, world: spear.UWorld, seed: int) -> None: ...

    def act(self, world: spear.UWorld, action: int) -> None: ...

    def observe(self, world: spear.UWorld) -> StepResult:
        return StepResult(observation={"angle": np.zeros(1, np.float32)})


class Blind:
    observation_space: Mapping[str, Box] = {}
    action_space = Discrete(2)

    def reset(self, world: spear.UWorld, seed: int) -> None: ...

    def act(self, world: spear.UWorld, action: int) -> None: ...


def misuse() -> None:
    envs = VectorEnv.in_worlds(Turn, num_envs=2)
    envs.step([1, 2])
    envs.step([0.5])  # E: List item 0 has incompatible type "float"; expected "int"  [list-item]  # P: reportArgumentType: Argument of type "list[float]" cannot be assigned to parameter "actions" of type "Sequence[int] | NDArray[Any]" in function "step" / "float" is not assignable to "int"
    VectorEnv.in_worlds(Blind, num_envs=2)  # E: Argument 1 to "in_worlds" of "VectorEnv" has incompatible type "Type[Blind]"; expected "Callable[[], Env[<nothing>]]"  [arg-type]  # P: reportArgumentType: Argument of type "type[Blind]" cannot be assigned to parameter "make_env" of type "() -> Env[A@in_worlds]" in function "in_worlds" / Type "type[Blind]" is not assignable to type "() -> Env[A@in_worlds]" / Function return type "Blind" is incompatible with type "Env[A@in_worlds]" / "Blind" is incompatible with protocol "Env[A@in_worlds]" / "observe" is not present
