"""spear.vector: environments in worlds of one engine (both transports) and across servers, stacked
observations in environment order, next-step auto-reset, a dead server reported while the rest keep running."""

from __future__ import annotations

import importlib
import importlib.util
import itertools
import logging
import os
import signal
from collections.abc import Callable, Iterator, Mapping
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

import spear
from spear.vector import Box, CameraImage, StepResult, VectorEnv

CUBE = "/Engine/BasicShapes/Cube"


class Slide:
    """A cube on a frictionless-enough floor at x = its environment's index, pushed along X by the action. The
    episode is truncated after `horizon` steps; the reward is the cube's x."""

    observation_space: Mapping[str, Box] = {"position": Box((3,), np.float64)}
    action_space = Box((1,), np.float32, -1.0, 1.0)

    def __init__(self, index: int, horizon: int = 1000) -> None:
        self.index = index
        self.horizon = horizon
        self.steps = 0
        self.cube: spear.AStaticMeshActor | None = None
        self.resets = 0

    def reset(self, world: spear.UWorld, seed: int) -> None:
        if self.cube is None:
            self.cube = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube")
            self.cube.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
        self.cube.SetActorLocation(NewLocation=spear.FVector(X=float(self.index), Z=5.0))
        self.steps = 0
        self.resets += 1

    def act(self, world: spear.UWorld, action: NDArray[np.float32]) -> None:
        assert self.cube is not None
        location = self.cube.GetActorLocation()
        self.cube.SetActorLocation(NewLocation=spear.FVector(X=location.X + float(action[0]), Z=5.0))
        self.steps += 1

    def observe(self, world: spear.UWorld) -> StepResult:
        assert self.cube is not None
        location = self.cube.GetActorLocation()
        return StepResult(observation={"position": np.array([location.X, location.Y, location.Z])},
                          reward=location.X, truncated=self.steps >= self.horizon, info={"steps": self.steps})


def numbered(horizon: int = 1000) -> Callable[[], Slide]:
    """A make_env that numbers the environments it builds 0, 1, 2, ..."""
    counter = itertools.count()
    return lambda: Slide(next(counter), horizon)


@pytest.fixture
def worlds_env(instance: spear.Instance) -> Iterator[VectorEnv[NDArray[np.float32]]]:
    envs = VectorEnv.in_worlds(numbered(horizon=3), num_envs=3, instance=instance)
    with instance.begin_frame():
        assert [world.GetName() for world in envs.worlds] == ["env0", "env1", "env2"]
    with instance.end_frame():
        pass
    yield envs
    envs.close()  # destroys the worlds it made: the instance has its game world alone again
    assert instance.get_worlds() == [instance.get_game()]


def test_observations_are_stacked_in_environment_order(worlds_env: VectorEnv[NDArray[np.float32]]) -> None:
    observations, infos = worlds_env.reset(seed=7)
    assert observations["position"].shape == (3, 3)
    assert observations["position"][:, 0].tolist() == [0.0, 1.0, 2.0]
    assert infos["reset"].tolist() == [True, True, True] and infos["_reset"].all()
    actions = [np.array([0.5], np.float32)] * 3
    observations, rewards, terminated, truncated, infos = worlds_env.step(actions)
    assert observations["position"][:, 0].tolist() == [0.5, 1.5, 2.5]
    assert rewards.dtype == np.float32 and rewards.tolist() == [0.5, 1.5, 2.5]
    assert not terminated.any() and not truncated.any()
    assert infos["steps"].tolist() == [1, 1, 1] and infos["_steps"].all()
    assert "reset" not in infos  # no environment set it this step


def test_the_vector_api_is_gymnasiums(worlds_env: VectorEnv[NDArray[np.float32]]) -> None:
    """Gymnasium 1.x's vector API, checked against its documented shape (gymnasium is not in Debian 12): batched
    spaces with a leading environment axis, infos as a dict of arrays with "_key" masks, the auto-reset mode in
    metadata."""
    single = worlds_env.single_observation_space["position"]
    batched = worlds_env.observation_space["position"]
    assert batched.shape == (3, *single.shape) and np.dtype(batched.dtype) == np.dtype(single.dtype)
    low, high = batched.bounds()
    assert (low == np.broadcast_to(single.bounds()[0], batched.shape)).all()
    assert (high == np.broadcast_to(single.bounds()[1], batched.shape)).all()
    action_space = worlds_env.action_space
    assert isinstance(action_space, spear.vector.Box) and action_space.shape == (3, 1)
    assert action_space.contains(np.zeros((3, 1), np.float32))
    if importlib.util.find_spec("gymnasium") is None:
        assert worlds_env.metadata["autoreset_mode"] == "NextStep"  # AutoresetMode.NEXT_STEP's value
    else:
        assert worlds_env.metadata["autoreset_mode"] is importlib.import_module("gymnasium.vector").AutoresetMode.NEXT_STEP
    observations, infos = worlds_env.reset(seed=1)
    assert all(batched_space.contains(observations[key]) for key, batched_space in worlds_env.observation_space.items())
    assert infos["reset"].dtype == np.bool_ and infos["_reset"].dtype == np.bool_


def test_infos_gather_as_gymnasium_does() -> None:
    gathered = spear.vector._gathered([{"steps": 1, "name": "a"}, {}, {"steps": 3, "ok": True}])
    assert gathered["steps"].tolist() == [1, 0, 3] and gathered["_steps"].tolist() == [True, False, True]
    assert gathered["name"].dtype == object and gathered["name"].tolist() == ["a", None, None]
    assert gathered["ok"].tolist() == [False, False, True] and gathered["_ok"].tolist() == [False, False, True]
    assert list(gathered) == ["steps", "_steps", "name", "_name", "ok", "_ok"]


def test_a_discrete_action_space_batches_to_multidiscrete() -> None:
    space = spear.vector.MultiDiscrete((4, 4))
    assert space.shape == (2,) and space.contains(np.array([0, 3])) and not space.contains(np.array([0, 4]))
    assert space.contains(space.sample(np.random.default_rng(0)))


def test_an_ended_episode_resets_on_the_next_step(worlds_env: VectorEnv[NDArray[np.float32]]) -> None:
    worlds_env.reset(seed=0)
    push = [np.array([1.0], np.float32)] * 3
    for _ in range(2):
        _, _, _, truncated, _ = worlds_env.step(push)
        assert not truncated.any()
    observations, rewards, _, truncated, _ = worlds_env.step(push)  # the third step ends the episodes
    assert truncated.all() and rewards.tolist() == [3.0, 4.0, 5.0]
    observations, rewards, terminated, truncated, infos = worlds_env.step(push)  # reset instead of acting
    assert observations["position"][:, 0].tolist() == [0.0, 1.0, 2.0]
    assert rewards.tolist() == [0.0, 0.0, 0.0] and not terminated.any() and not truncated.any()
    assert infos["reset"].all() and infos["_reset"].all()
    assert [env.resets for env in worlds_env.envs if isinstance(env, Slide)] == [2, 2, 2]


class Looks:
    """A camera facing a wall at 2 + index metres; observes its depth (and colour) as CameraImage, or, with
    read=True, by reading the camera itself."""

    observation_space: Mapping[str, Box] = {"depth": Box((12, 16), np.float32, 0.0),
                                            "color": Box((12, 16, 4), np.uint8, 0, 255)}
    action_space = Box((1,), np.float32)

    def __init__(self, index: int, *, read: bool = False, width: int = 16,
                 modality: str = "depth") -> None:
        self.index, self.read, self.width, self.modality = index, read, width, modality
        self.camera: spear.UCameraSensorComponent | None = None

    def reset(self, world: spear.UWorld, seed: int) -> None:
        wall = world.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=2.05 + self.index))
        wall.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
        wall.SetActorScale3D(NewScale3D=spear.FVector(0.1, 10, 10))
        self.camera = world.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
        self.camera.Width, self.camera.Height = self.width, 12
        self.camera.Modalities = [spear.ECameraModality.Depth, spear.ECameraModality.FinalColor]

    def act(self, world: spear.UWorld, action: Any) -> None:
        pass

    def observe(self, world: spear.UWorld) -> StepResult:
        assert self.camera is not None
        if self.read:
            pixels = self.camera.read_pixels()
            return StepResult(observation={"depth": pixels["depth"], "color": pixels["final_color"]})
        return StepResult(observation={"depth": CameraImage(self.camera, self.modality),
                                       "color": CameraImage(self.camera)})


def test_camera_images_stack_per_world(instance: spear.Instance) -> None:
    counter = itertools.count()
    with VectorEnv.in_worlds(lambda: Looks(next(counter), read=True), num_envs=3, instance=instance) as envs:
        observations, _ = envs.reset(seed=1)
        depth = observations["depth"]
        assert depth.shape == (3, 12, 16) and depth.dtype == np.float32
        for i in range(3):
            assert np.allclose(depth[i], 2.0 + i, atol=1e-3)


def test_camera_images_are_read_together_and_equal_each_cameras_own_read(instance: spear.Instance) -> None:
    counter = itertools.count()
    with VectorEnv.in_worlds(lambda: Looks(next(counter)), num_envs=3, instance=instance, prefix="a") as envs:
        together, _ = envs.reset(seed=1)
    counter = itertools.count()
    with VectorEnv.in_worlds(lambda: Looks(next(counter), read=True), num_envs=3, instance=instance,
                             prefix="b") as envs:
        one_by_one, _ = envs.reset(seed=1)
    assert together["depth"].shape == (3, 12, 16) and together["color"].shape == (3, 12, 16, 4)
    for i in range(3):
        assert np.allclose(together["depth"][i], 2.0 + i, atol=1e-3)
    assert np.array_equal(together["depth"], one_by_one["depth"])
    assert np.array_equal(together["color"], one_by_one["color"])
    if instance.transport == "rpc":
        # Copied out of the connection's shared memory: an observation kept for long holds no mapping.
        assert together["depth"].flags.owndata and together["color"].flags.owndata


def test_two_observations_of_one_camera_image_are_two_arrays(instance: spear.Instance) -> None:
    class Twice(Looks):
        observation_space: Mapping[str, Box] = {"a": Looks.observation_space["color"],
                                                "b": Looks.observation_space["color"]}

        def observe(self, world: spear.UWorld) -> StepResult:
            assert self.camera is not None
            return StepResult(observation={"a": CameraImage(self.camera), "b": CameraImage(self.camera)})

    counter = itertools.count()
    with VectorEnv.in_worlds(lambda: Twice(next(counter)), num_envs=2, instance=instance) as envs:
        observations, _ = envs.reset(seed=1)
    assert observations["a"] is not observations["b"] and np.array_equal(observations["a"], observations["b"])
    observations["a"][...] = 0  # the user's to change: the other is not
    assert observations["b"].any()


def test_camera_images_that_cannot_be_read_together_are_refused_naming_the_observation(
        instance: spear.Instance) -> None:
    counter = itertools.count()
    with VectorEnv.in_worlds(lambda: Looks(next(counter), width=16 + next(counter)), num_envs=2,
                             instance=instance) as envs:
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^VectorEnv: the cameras of observation 'depth' cannot be read together: "
                                 r"UCameraSensorComponent\.read_pixels_stacked\(\): Cameras\[1\] "):
            envs.reset()
    with VectorEnv.in_worlds(lambda: Looks(0, modality="normal"), num_envs=2, instance=instance) as envs:
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^VectorEnv: environment 0 observed nothing for 'depth', its observation_space "):
            envs.reset()


def test_an_observation_that_is_not_an_array_is_checked_and_stacked_as_numpy_reads_it(
        instance: spear.Instance) -> None:
    # Arrays are checked by their attributes; anything else (a list from untyped code) by what numpy makes of it.
    class Listed(Slide):
        def observe(self, world: spear.UWorld) -> StepResult:
            position = super().observe(world).observation["position"]
            return StepResult(observation={"position": [float(v) for v in position]})  # type: ignore[dict-item]

    stacked = []
    for make in (lambda: Listed(0), lambda: Slide(0)):
        with VectorEnv.in_worlds(make, num_envs=1, instance=instance) as envs:
            stacked.append(envs.reset(seed=1)[0]["position"])
    assert stacked[0].dtype == stacked[1].dtype and np.array_equal(stacked[0], stacked[1])

    class Short(Slide):
        def observe(self, world: spear.UWorld) -> StepResult:
            position = super().observe(world).observation["position"]
            return StepResult(observation={"position": [float(v) for v in position[:2]]})  # type: ignore[dict-item]

    with VectorEnv.in_worlds(lambda: Short(0), num_envs=1, instance=instance) as envs:
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^VectorEnv: environment 0 observed shape \(2,\) float64 for 'position', its "
                                 r"observation_space says shape \(3,\) float64$"):
            envs.reset()


def test_misuse_is_refused_with_the_reason(instance: spear.Instance) -> None:
    with VectorEnv.in_worlds(numbered(), num_envs=2, instance=instance) as envs:
        with pytest.raises(spear.InvalidStateError, match=r"^VectorEnv.step\(\): call reset\(\) first$"):
            envs.step([np.zeros(1, np.float32)] * 2)
        envs.reset()
        with pytest.raises(spear.InvalidArgumentError, match=r"^VectorEnv.step\(\): 1 actions for 2 environments$"):
            envs.step([np.zeros(1, np.float32)])

    class Wrong(Slide):
        observation_space: Mapping[str, Box] = {"position": Box((2,), np.float64)}

    with VectorEnv.in_worlds(lambda: Wrong(0), num_envs=1, instance=instance) as envs:
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^VectorEnv: environment 0 observed shape \(3,\) float64 for 'position', its "
                                 r"observation_space says shape \(2,\) float64$"):
            envs.reset()

    class Mismatched(Slide):
        def __init__(self) -> None:
            super().__init__(0)
            self.observation_space = {"position": Box((3,), np.float64, 0.0 if next(calls) else -1.0)}

    calls = itertools.count()
    with pytest.raises(spear.InvalidArgumentError, match=r"^VectorEnv\(\): environment 1's spaces differ from "
                                                         r"environment 0's$"):
        VectorEnv.in_worlds(Mismatched, num_envs=2, instance=instance)
    # A failed construction leaves nothing behind: the worlds it made are gone, so the names are free again.
    assert instance.get_worlds() == [instance.get_game()]
    with VectorEnv.in_worlds(numbered(), num_envs=2, instance=instance) as envs:
        observations, _ = envs.reset(seed=0)
        observations, *_ = envs.step(np.full((2, 1), 0.5, np.float32))  # actions as one array
        assert observations["position"][:, 0].tolist() == [0.5, 1.5]


def test_a_dead_server_is_reported_and_the_others_keep_running(caplog: pytest.LogCaptureFixture) -> None:
    with VectorEnv.on_servers(numbered(), num_servers=2, worlds_per_server=2) as envs:
        observations, _ = envs.reset(seed=3)
        assert observations["position"][:, 0].tolist() == [0.0, 1.0, 2.0, 3.0]
        doomed = envs._groups[1].instance.server_pid  # the second server holds environments 2 and 3
        assert doomed is not None
        os.kill(doomed, signal.SIGKILL)  # its socket closes as the process dies
        push = [np.array([1.0], np.float32)] * 4
        with caplog.at_level(logging.WARNING, logger="spear"):
            observations, _, _, truncated, infos = envs.step(push)
        assert sorted(envs.failed) == [2, 3]
        assert isinstance(infos["error"][2], spear.ConnectionLostError)
        assert infos["_error"].tolist() == [False, False, True, True] and infos["error"][0] is None
        assert truncated.tolist() == [False, False, True, True]
        assert observations["position"][:, 0].tolist() == [1.0, 2.0, 0.0, 0.0]
        assert "environments [2, 3] failed" in caplog.text and "2 of 4 keep running" in caplog.text
        observations, _, _, truncated, _ = envs.step(push)  # the survivors go on
        assert observations["position"][:2, 0].tolist() == [2.0, 3.0]
        assert truncated.tolist() == [False, False, True, True]


def test_boxes_take_per_element_bounds_and_sample_inside_them() -> None:
    rng = np.random.default_rng(0)
    joints = Box((2,), np.float32, [-1.0, 0.0], [1.0, 2.0])
    samples = np.stack([joints.sample(rng) for _ in range(1000)])
    assert samples.dtype == np.float32 and samples.shape == (1000, 2)
    assert samples[:, 0].min() >= -1 and samples[:, 0].max() <= 1 and samples[:, 1].min() >= 0
    assert samples[:, 1].max() <= 2 and samples[:, 1].max() > 1.5  # uniform over each element's own range
    assert joints.contains(np.array([0.5, 1.5], np.float32)) and not joints.contains(np.array([0.5, 2.5], np.float32))
    assert joints == Box((2,), np.float32, (-1.0, 0.0), np.array([1.0, 2.0]))  # compared by value
    # One finite bound: gymnasium's rule (an exponential off the bound), not a pile of samples at the bound.
    half = Box((1000,), np.float64, low=0.0).sample(rng)
    assert half.min() > 0.0 and 0.8 < half.mean() < 1.2
    steps = Box((3,), np.int64, 0, [1, 5, 10]).sample(rng)
    assert steps.dtype == np.int64 and (steps >= 0).all() and (steps <= [1, 5, 10]).all()
    with pytest.raises(spear.InvalidArgumentError, match=r"^Box\(\): low has 3 values for shape \(2,\) \(2 elements\)$"):
        Box((2,), low=[0.0, 0.0, 0.0])
    with pytest.raises(spear.InvalidArgumentError, match=r"^Box\(\): low exceeds high at element 1$"):
        Box((2,), np.float32, [0.0, 3.0], 2.0)
