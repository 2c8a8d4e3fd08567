"""Vectorised environments: N environments stepped together, each in a world of its own, across the worlds of
one engine and across spear-server processes, with observations stacked into numpy arrays.

    envs = spear.vector.VectorEnv.in_worlds(Reach, num_envs=16)                     # one engine, 16 worlds
    envs = spear.vector.VectorEnv.on_servers(Reach, num_servers=4, worlds_per_server=4)
    observations, infos = envs.reset(seed=0)
    observations, rewards, terminated, truncated, infos = envs.step(actions)

An environment is a class of the Env protocol: reset() builds or rearranges its world, act() applies an action,
observe() reads the observation, reward and end of episode. A step is SPEAR's frame: every engine opens one frame,
its environments act (or reset) inside begin_frame, the engine ticks all its worlds once, and the environments
observe inside end_frame. Engines on separate servers step concurrently, one thread each waiting on its socket.

The API is Gymnasium's vector API (1.x): single_observation_space and single_action_space are one environment's,
observation_space and action_space the batched ones (a leading environment axis; a Discrete action becomes a
MultiDiscrete), infos is a dict of arrays, one entry per environment, with a boolean mask "_key" saying which
environments set "key", and metadata["autoreset_mode"] says the auto-reset mode: "NextStep", Gymnasium's
AutoresetMode.NEXT_STEP (that enum itself when gymnasium is installed). An environment whose step ended its
episode (terminated or truncated) is reset during the following step() instead of acting; that step returns
its first observation, reward 0, terminated and truncated False, and infos["reset"] True for it.

An observation that is a camera's image is best returned as CameraImage(camera, modality) instead of the array
observe() would read: VectorEnv then reads the images of every environment of an engine in one call
(UCameraSensorComponent.read_pixels_stacked: one round trip over RPC, no read per environment), straight into
the stacked observation.

A server that goes away is reported once (a warning naming the environments it held); its environments stay
failed: their observations are zeros, truncated is True, infos["error"] holds the error in their rows, and
`failed` maps their indices to it. The other environments keep running.
"""

from __future__ import annotations

import concurrent.futures
import importlib
import logging
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Generic, Protocol, TypeVar

import numpy as np
from numpy.typing import DTypeLike, NDArray

from spear._engine import api
from spear.errors import ConnectionLostError, InvalidArgumentError, InvalidStateError
from spear.instance import Instance

_log = logging.getLogger("spear")

ActionT = TypeVar("ActionT")
A = TypeVar("A")  # the constructors' own: a class's TypeVar is bound (to Unknown, in pyright) before they run
ActionT_contra = TypeVar("ActionT_contra", contravariant=True)

# -- spaces ------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Box:
    """Arrays of one shape and dtype with every element in [low, high]: one bound for all elements, or one per
    element (a sequence of shape's size, row-major: a robot's joint limits); infinite bounds allowed."""

    shape: tuple[int, ...]
    dtype: DTypeLike = np.float32
    low: float | Sequence[float] | NDArray[Any] = -math.inf
    high: float | Sequence[float] | NDArray[Any] = math.inf

    def __post_init__(self) -> None:
        # One bound is kept as a float, per-element bounds as a tuple, so that spaces compare (and hash) by value.
        size = int(np.prod(self.shape))
        for name in ("low", "high"):
            bound = getattr(self, name)
            if np.ndim(bound) == 0:  # a number, numpy scalars and 0-d arrays included
                values: float | tuple[float, ...] = float(bound)
            else:
                values = tuple(float(v) for v in np.asarray(bound, dtype=np.float64).ravel())
                if len(values) != size:
                    raise InvalidArgumentError(f"Box(): {name} has {len(values)} values for shape {self.shape} "
                                               f"({size} elements)")
            if np.any(np.isnan(values)):
                raise InvalidArgumentError(f"Box(): {name} is NaN")
            object.__setattr__(self, name, values)
        low, high = self.bounds()
        if np.any(low > high):
            raise InvalidArgumentError(f"Box(): low exceeds high at element {int(np.argmax(low > high))}")

    def bounds(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(low, high) as arrays of the box's shape."""
        def full(bound: float | Sequence[float] | NDArray[Any]) -> NDArray[np.float64]:
            array = np.asarray(bound, dtype=np.float64)
            return np.broadcast_to(array if array.ndim == 0 else array.reshape(self.shape), self.shape)
        return full(self.low), full(self.high)

    def zeros(self) -> NDArray[Any]:
        return np.zeros(self.shape, dtype=self.dtype)

    def contains(self, value: object) -> bool:
        array = np.asarray(value)
        if array.shape != self.shape or array.dtype != np.dtype(self.dtype):
            return False
        low, high = self.bounds()
        return bool(np.all(array >= low)) and bool(np.all(array <= high))

    def sample(self, rng: np.random.Generator) -> NDArray[Any]:
        """Uniform where both bounds are finite; low + an exponential where only low is, high - an exponential
        where only high is, a standard normal where neither is (gymnasium's rule). Integer boxes draw uniformly
        from the bounds clipped to the dtype's range."""
        dtype = np.dtype(self.dtype)
        low, high = self.bounds()
        if np.issubdtype(dtype, np.integer):
            # The integers inside each element's bounds, in Python ints (a float64 cannot hold 2**63 - 1).
            info = np.iinfo(dtype)

            def integers(bounds: NDArray[np.float64], rounding: Any, infinite: int) -> NDArray[Any]:
                values = [min(max(int(rounding(b)), info.min), info.max) if math.isfinite(b) else infinite
                          for b in bounds.ravel()]
                return np.array(values, dtype=dtype).reshape(self.shape)

            first, last = integers(low, math.ceil, int(info.min)), integers(high, math.floor, int(info.max))
            # numpy 1.24's stubs type dtype= per literal dtype, not a dtype object.
            drawn: NDArray[Any] = rng.integers(first, last, endpoint=True, dtype=dtype)  # type: ignore[arg-type]
            return np.asarray(drawn)
        below, above = np.isfinite(low), np.isfinite(high)
        uniform = rng.uniform(np.where(below, low, 0.0), np.where(above, high, 1.0))
        exponential = rng.exponential(size=self.shape)
        normal = rng.standard_normal(size=self.shape)
        drawn = np.where(below & above, uniform,
                         np.where(below, low + exponential, np.where(above, high - exponential, normal)))
        return drawn.astype(dtype)


@dataclass(frozen=True)
class Discrete:
    """One of the integers 0, 1, ..., n - 1."""

    n: int

    def contains(self, value: object) -> bool:
        return isinstance(value, (int, np.integer)) and 0 <= int(value) < self.n

    def sample(self, rng: np.random.Generator) -> int:
        return int(rng.integers(self.n))


@dataclass(frozen=True)
class MultiDiscrete:
    """One integer per element, element i one of 0, ..., nvec[i] - 1 (what a batch of Discrete actions is)."""

    nvec: tuple[int, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        return (len(self.nvec),)

    def contains(self, value: object) -> bool:
        array = np.asarray(value)
        return (array.shape == self.shape and np.issubdtype(array.dtype, np.integer)
                and bool(np.all(array >= 0)) and bool(np.all(array < np.asarray(self.nvec))))

    def sample(self, rng: np.random.Generator) -> NDArray[np.int64]:
        return rng.integers(np.asarray(self.nvec, dtype=np.int64)).astype(np.int64)


def _batched_box(space: Box, n: int) -> Box:
    """`space` with a leading axis of n environments (per-element bounds repeated for each)."""
    def bound(value: float | Sequence[float] | NDArray[Any]) -> float | NDArray[np.float64]:
        return value if isinstance(value, float) else np.tile(np.asarray(value, dtype=np.float64), n)
    return Box(shape=(n, *space.shape), dtype=space.dtype, low=bound(space.low), high=bound(space.high))


def _autoreset_next_step() -> Any:
    """Gymnasium's AutoresetMode.NEXT_STEP when gymnasium is installed, else its value, "NextStep"."""
    try:
        gymnasium_vector = importlib.import_module("gymnasium.vector")  # optional: not in Debian 12
    except ImportError:
        return "NextStep"
    return gymnasium_vector.AutoresetMode.NEXT_STEP


def _gathered(infos: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Gymnasium's vector infos from one dict per environment: for each key any environment set, an array with a
    row per environment (numbers and bools in a numeric array, anything else in an object array; rows of the
    environments that did not set it are zero or None) and "_key", a bool array of which environments set it."""
    n = len(infos)
    out: dict[str, Any] = {}
    for key in dict.fromkeys(k for info in infos for k in info):  # first-seen order
        mask = np.array([key in info for info in infos], dtype=np.bool_)
        values = [info.get(key) for info in infos]
        given = [v for v, m in zip(values, mask) if m]
        if all(isinstance(v, (bool, np.bool_)) for v in given):
            array: NDArray[Any] = np.array([bool(v) if m else False for v, m in zip(values, mask)], dtype=np.bool_)
        elif all(isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))
                 for v in given):
            array = np.zeros(n, dtype=np.result_type(*[np.asarray(v).dtype for v in given]))
            array[mask] = given
        else:
            array = np.empty(n, dtype=object)
            for i, value in enumerate(values):
                array[i] = value
        out[key] = array
        out[f"_{key}"] = mask
    return out


# -- one environment ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class CameraImage:
    """An observation that is one modality of a camera's images (the frame read at the end of the step). Returned
    by observe() in place of the array: VectorEnv reads the cameras of all the environments of one engine
    together, in one read_pixels_stacked call, instead of one read_pixels per environment."""

    camera: api.UCameraSensorComponent
    modality: str = "final_color"  # a key of the camera's read_pixels() result


@dataclass
class StepResult:
    """What an environment observes at the end of a frame."""

    observation: dict[str, NDArray[Any] | CameraImage]
    reward: float = 0.0
    terminated: bool = False  # the episode reached a terminal state
    truncated: bool = False  # the episode was cut short (a time limit)
    info: dict[str, Any] = field(default_factory=dict)


class Env(Protocol[ActionT_contra]):
    """One environment in one world. reset() and act() run inside begin_frame, observe() inside end_frame."""

    @property
    def observation_space(self) -> Mapping[str, Box]: ...

    @property
    def action_space(self) -> Box | Discrete: ...

    def reset(self, world: api.UWorld, seed: int) -> None:
        """Starts an episode: builds the world's scene on the first call, rearranges it on later ones."""

    def act(self, world: api.UWorld, action: ActionT_contra) -> None:
        """Applies one action."""

    def observe(self, world: api.UWorld) -> StepResult:
        """Reads the observation (one array per observation_space key), reward and end of episode."""
        ...


# -- many environments -------------------------------------------------------------------------------------


@dataclass
class _Group:
    """The environments one engine holds: stepped in one frame of that engine."""

    instance: Instance
    indices: list[int]


# One engine's frame: each environment's result, and the camera observations read together, per key: the
# environments in row order and the stack (VectorEnv._frame).
_Observed = tuple[dict[int, StepResult], dict[str, tuple[list[int], NDArray[Any]]]]

# (observations, rewards, terminated, truncated, infos) of one step; the public signatures spell it out (pyright's
# --verifytypes counts a module-level alias of a numpy array type as unknown).
_Batch = tuple[dict[str, NDArray[Any]], NDArray[np.float32], NDArray[np.bool_], NDArray[np.bool_], dict[str, Any]]


class VectorEnv(Generic[ActionT]):
    """num_envs environments, each in its own world of one of the instances, stepped together."""

    def __init__(self, make_env: Callable[[], Env[ActionT]], slots: Sequence[tuple[Instance, api.UWorld]], *,
                 owned: Sequence[Instance] = (), destroy_worlds: bool = False) -> None:
        """make_env: builds one environment (called once per slot). slots: (instance, world) per environment, in
        environment order. owned: instances close() closes. destroy_worlds: close() destroys the slots' worlds
        in the instances it does not close."""
        if not slots:
            raise InvalidArgumentError("VectorEnv(): slots must hold at least one (instance, world)")
        self._owned = list(owned)
        self._slots = list(slots) if destroy_worlds else []
        self._worlds = [world for _, world in slots]
        self._envs = [make_env() for _ in slots]
        self.single_observation_space: Mapping[str, Box] = dict(self._envs[0].observation_space)
        """One environment's observation space (each array of a step has a leading environment axis more)."""
        self.single_action_space: Box | Discrete = self._envs[0].action_space
        """One environment's action space."""
        self.metadata: dict[str, Any] = {"autoreset_mode": _autoreset_next_step()}
        """Gymnasium's vector metadata: the auto-reset mode (see the module's documentation)."""
        for i, env in enumerate(self._envs):
            if (dict(env.observation_space) != self.single_observation_space
                    or env.action_space != self.single_action_space):
                raise InvalidArgumentError(f"VectorEnv(): environment {i}'s spaces differ from environment 0's")
        self._groups: list[_Group] = []
        for i, (instance, _) in enumerate(slots):
            group = next((g for g in self._groups if g.instance is instance), None)
            if group is None:
                self._groups.append(group := _Group(instance, []))
            group.indices.append(i)
        # Engines over RPC step concurrently, one pool thread each waiting on its socket; an in-process engine
        # steps on the calling thread (its GL contexts are current there).
        remote = sum(1 for g in self._groups if g.instance.transport == "rpc")
        self._pool = (concurrent.futures.ThreadPoolExecutor(remote, thread_name_prefix="spear-vector")
                      if remote > 1 else None)
        self._seeds: list[np.random.Generator] = []
        self._needs_reset = [True] * len(slots)
        self.failed: dict[int, BaseException] = {}
        """Environments whose server went away, by index, with the error."""

    # -- construction ------------------------------------------------------------------------------------

    @classmethod
    def in_worlds(cls, make_env: Callable[[], Env[A]], *, num_envs: int, instance: Instance | None = None,
                  prefix: str = "env") -> VectorEnv[A]:
        """num_envs environments in new worlds named prefix0, prefix1, ... of one engine: `instance` (close()
        destroys the worlds), or an in-process engine that close() closes."""
        if num_envs < 1:
            raise InvalidArgumentError(f"VectorEnv.in_worlds(): num_envs must be >= 1, got {num_envs}")
        engine = Instance() if instance is None else instance
        slots: list[tuple[Instance, api.UWorld]] = []
        try:
            for i in range(num_envs):
                slots.append((engine, engine.create_world(name=f"{prefix}{i}")))
            return VectorEnv(make_env, slots, owned=[engine] if instance is None else [], destroy_worlds=True)
        except BaseException:
            _release(slots, [engine] if instance is None else [])
            raise

    @classmethod
    def on_servers(cls, make_env: Callable[[], Env[A]], *, num_servers: int, worlds_per_server: int = 1,
                   servers: Sequence[str] | None = None, token: str | None = None,
                   prefix: str = "env") -> VectorEnv[A]:
        """num_servers * worlds_per_server environments, worlds_per_server in each of num_servers spear-server
        processes launched here, or in the running servers at the addresses `servers` ("unix:PATH",
        "tcp:HOST:PORT"; token: their TCP token). Worlds are named prefix0, prefix1, ... across the servers.
        close() destroys the worlds and stops the launched servers (or disconnects from the running ones)."""
        if num_servers < 1 or worlds_per_server < 1:
            raise InvalidArgumentError("VectorEnv.on_servers(): num_servers and worlds_per_server must be >= 1, got "
                                       f"{num_servers} and {worlds_per_server}")
        if servers is not None and len(servers) != num_servers:
            raise InvalidArgumentError(f"VectorEnv.on_servers(): {len(servers)} server addresses for num_servers="
                                       f"{num_servers}")
        addresses = list(servers) if servers is not None else ["launch"] * num_servers
        # Servers start concurrently, each launch waiting for its process to listen (a launched server lives as
        # long as this process, not the thread that launched it).
        with concurrent.futures.ThreadPoolExecutor(num_servers) as pool:
            futures = [pool.submit(Instance, server=address, token=token) for address in addresses]
        instances = [future.result() for future in futures if future.exception() is None]
        slots: list[tuple[Instance, api.UWorld]] = []
        try:
            for future in futures:
                future.result()  # the first failure to start, if any
            for s, engine in enumerate(instances):
                for w in range(worlds_per_server):
                    slots.append((engine, engine.create_world(name=f"{prefix}{s * worlds_per_server + w}")))
            return VectorEnv(make_env, slots, owned=instances, destroy_worlds=True)
        except BaseException:
            _release(slots, instances)
            raise

    # -- the loop ----------------------------------------------------------------------------------------

    @property
    def num_envs(self) -> int:
        return len(self._envs)

    @property
    def observation_space(self) -> dict[str, Box]:
        """The batched observation space: each key's Box with a leading axis of num_envs environments."""
        return {key: _batched_box(space, self.num_envs) for key, space in self.single_observation_space.items()}

    @property
    def action_space(self) -> Box | MultiDiscrete:
        """The batched action space: a Box with a leading environment axis, or a MultiDiscrete for Discrete."""
        space = self.single_action_space
        if isinstance(space, Discrete):
            return MultiDiscrete((space.n,) * self.num_envs)
        return _batched_box(space, self.num_envs)

    @property
    def envs(self) -> Sequence[Env[ActionT]]:
        """The environments, in index order."""
        return self._envs

    @property
    def worlds(self) -> Sequence[api.UWorld]:
        """Each environment's world, in index order."""
        return self._worlds

    def reset(self, *, seed: int | None = None) -> tuple[dict[str, NDArray[Any]], dict[str, Any]]:
        """Starts an episode in every environment (environment i's seeds come from SeedSequence(seed) child i)."""
        children = np.random.SeedSequence(seed).spawn(self.num_envs)
        self._seeds = [np.random.default_rng(child) for child in children]
        plan: dict[int, tuple[bool, Any]] = {i: (True, None) for i in range(self.num_envs)}
        observations, _, _, _, infos = self._run(plan)
        return observations, infos

    def step(self, actions: Sequence[ActionT] | NDArray[Any]) -> tuple[
            dict[str, NDArray[Any]], NDArray[np.float32], NDArray[np.bool_], NDArray[np.bool_], dict[str, Any]]:
        """Applies actions[i] to environment i (resetting the ones whose episode ended last step) and returns
        (observations, rewards, terminated, truncated, infos) with a leading environment axis (infos as Gymnasium
        gathers them: see the module's documentation); actions may be a sequence or an array with a leading
        environment axis."""
        if not self._seeds:
            raise InvalidStateError("VectorEnv.step(): call reset() first")
        if len(actions) != self.num_envs:
            raise InvalidArgumentError(f"VectorEnv.step(): {len(actions)} actions for {self.num_envs} environments")
        plan = {i: (self._needs_reset[i], actions[i]) for i in range(self.num_envs)}
        return self._run(plan)

    def close(self) -> None:
        """Stops the thread pool, destroys the worlds this vector env created (on servers that are still there),
        and closes the instances it opened."""
        if self._pool is not None:
            self._pool.shutdown()
            self._pool = None
        gone = [self._slots[i][0] for i in self.failed] if self._slots else []
        slots = [(instance, world) for instance, world in self._slots if all(instance is not g for g in gone)]
        owned, self._slots, self._owned = self._owned, [], []
        _release(slots, owned)

    def __enter__(self) -> VectorEnv[ActionT]:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- internals ---------------------------------------------------------------------------------------

    def _run(self, plan: dict[int, tuple[bool, Any]]) -> _Batch:
        groups = [g for g in self._groups if g.indices[0] not in self.failed]
        outcomes: dict[int, _Observed | ConnectionLostError] = {}
        pooled = {id(g): self._pool.submit(self._guarded, g, plan) for g in groups
                  if self._pool is not None and g.instance.transport == "rpc"}
        try:
            for group in groups:
                if id(group) not in pooled:
                    outcomes[id(group)] = self._guarded(group, plan)
        finally:
            # Every engine's frame ends before this step returns or raises: the next step (or close()) must
            # not meet an engine still inside this one.
            concurrent.futures.wait(pooled.values())
        for key, future in pooled.items():
            outcomes[key] = future.result()  # an error other than a lost server propagates
        results: dict[int, StepResult] = {}
        stacks: dict[str, tuple[list[int], NDArray[Any]]] = {}
        for group in groups:
            outcome = outcomes[id(group)]
            if isinstance(outcome, ConnectionLostError):
                self._fail(group, outcome)
            else:
                results.update(outcome[0])
                # In-process only: over RPC a stack is a view of the connection's shared memory, which an
                # observation kept for long (a replay buffer) would hold on to, one mapping each.
                stacks = outcome[1] if len(groups) == 1 and group.instance.transport == "inprocess" else {}
        # A camera observation read for every environment in one stack, in environment order, is that stack.
        whole = {key: stack for key, (indices, stack) in stacks.items() if indices == list(range(self.num_envs))}
        return self._stack(plan, results, whole)

    def _guarded(self, group: _Group, plan: dict[int, tuple[bool, Any]]) -> _Observed | ConnectionLostError:
        """The group's frame, or the error that says its server went away (any other error propagates)."""
        try:
            return self._frame(group, plan)
        except ConnectionLostError as error:
            return error

    def _frame(self, group: _Group, plan: dict[int, tuple[bool, Any]]) -> _Observed:
        """One frame of one engine: its environments act or reset, the engine ticks, they observe; the results,
        and the camera observations read together (see _read_cameras)."""
        instance = group.instance
        with instance.begin_frame():
            for i in group.indices:
                reset, action = plan[i]
                if reset:
                    self._envs[i].reset(self._worlds[i], int(self._seeds[i].integers(2**63)))
                else:
                    self._envs[i].act(self._worlds[i], action)
        results: dict[int, StepResult] = {}
        with instance.end_frame():
            for i in group.indices:
                results[i] = self._envs[i].observe(self._worlds[i])
            stacks = _read_cameras(results)
        return results, stacks

    def _fail(self, group: _Group, error: BaseException) -> None:
        for i in group.indices:
            self.failed[i] = error
        _log.warning("environments %s failed and are left out from now on (%d of %d keep running): %s",
                     group.indices, self.num_envs - len(self.failed), self.num_envs, error)

    def _stack(self, plan: dict[int, tuple[bool, Any]], results: dict[int, StepResult],
               whole: Mapping[str, NDArray[Any]]) -> _Batch:
        """The step's batch; `whole`: observations already stacked for every environment (a camera stack, in
        environment order), used as they are when they fit the space, instead of copied row by row."""
        n = self.num_envs
        observations: dict[str, NDArray[Any]] = {}
        expected = []
        for key, space in self.single_observation_space.items():
            stack = whole.get(key)
            if (stack is not None and stack.shape == (n, *space.shape) and stack.dtype == np.dtype(space.dtype)
                    and all(stack is not taken for taken in observations.values())):  # two keys, two arrays
                observations[key] = stack  # its rows are the environments' observations: nothing to check or copy
            else:
                observations[key] = np.zeros((n, *space.shape), dtype=space.dtype)
                expected.append((key, space.shape, np.dtype(space.dtype)))
        rewards = np.zeros(n, dtype=np.float32)
        terminated = np.zeros(n, dtype=np.bool_)
        truncated = np.zeros(n, dtype=np.bool_)
        infos: list[dict[str, Any]] = [{} for _ in range(n)]
        for i in range(n):
            if i in self.failed:
                truncated[i] = True
                infos[i] = {"error": self.failed[i]}
                continue
            result = results[i]
            for key, shape, dtype in expected:
                value: Any = result.observation.get(key)
                # An array (what cameras and most observations are) is checked by its attributes; anything
                # else by what numpy makes of it.
                fits = (value.shape == shape and value.dtype == dtype if isinstance(value, np.ndarray)
                        else value is not None and np.shape(value) == shape and np.asarray(value).dtype == dtype)
                if not fits:
                    got = ("nothing" if value is None
                           else f"shape {np.shape(value)} {np.asarray(value).dtype}")
                    raise InvalidArgumentError(f"VectorEnv: environment {i} observed {got} for '{key}', its "
                                               f"observation_space says shape {shape} {dtype}")
                observations[key][i] = value
            infos[i] = dict(result.info)
            if plan[i][0]:
                infos[i]["reset"] = True  # the first observation of an episode: no reward, not over
            else:
                rewards[i] = result.reward
                terminated[i] = result.terminated
                truncated[i] = result.truncated
            self._needs_reset[i] = bool(terminated[i] or truncated[i])
        return observations, rewards, terminated, truncated, _gathered(infos)


def _read_cameras(results: dict[int, StepResult]) -> dict[str, tuple[list[int], NDArray[Any]]]:
    """Replaces the CameraImage observations of one engine's environments by their images: the cameras each
    observation key names are read in one read_pixels_stacked call (one per distinct list of cameras, so keys
    that are modalities of the same cameras share it), and each environment gets its row of the stack.
    Returns, per key read so, the environments in row order and the stack."""
    wanted: dict[str, list[tuple[int, CameraImage]]] = {}
    for i, result in results.items():
        for key, value in result.observation.items():
            if isinstance(value, CameraImage):
                wanted.setdefault(key, []).append((i, value))
    stacks: list[tuple[list[api.UCameraSensorComponent], api.FCameraPixels]] = []
    read: dict[str, tuple[list[int], NDArray[Any]]] = {}
    for key, images in wanted.items():
        cameras = [image.camera for _, image in images]
        stack = next((pixels for listed, pixels in stacks if listed == cameras), None)
        if stack is None:
            try:
                # Called on the first camera, so that its engine (in-process, or its server) reads them all.
                stack = cameras[0].read_pixels_stacked(Cameras=cameras)
            except InvalidArgumentError as error:  # cameras of different sizes or modalities
                raise InvalidArgumentError(f"VectorEnv: the cameras of observation '{key}' cannot be read together: "
                                           f"{error}") from None
            stacks.append((cameras, stack))
        stacked: Any = stack.get(images[0][1].modality)
        if all(image.modality == images[0][1].modality for _, image in images) and stacked is not None:
            read[key] = ([i for i, _ in images], stacked)
        for row, (i, image) in enumerate(images):
            stacked = stack.get(image.modality)
            if stacked is None:  # the camera is priming (Latency > 0) or does not render that modality
                del results[i].observation[key]  # observed nothing: the stacking says so, naming the key
            else:
                results[i].observation[key] = stacked[row]
    return read


def _release(slots: Sequence[tuple[Instance, api.UWorld]], instances: Sequence[Instance]) -> None:
    """Destroys the slots' worlds in the instances not about to close, then closes `instances`; every step is
    tried, and the first error raised after the rest were done."""
    failure: BaseException | None = None
    for instance, world in slots:
        if any(instance is closing for closing in instances):
            continue  # its worlds go with it
        try:
            instance.destroy_world(world=world)
        except Exception as error:  # a server that went away: the other worlds still go
            failure = failure or error
    for instance in instances:
        try:
            instance.close()
        except Exception as error:
            failure = failure or error
    if failure is not None:
        raise failure
