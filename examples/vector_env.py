"""Step 16 environments together with random actions and write a grid of their camera images into one PNG.

Each environment is a puck on a floor, pushed by a horizontal force towards a goal disc; the observation is
an overhead camera's final colour and the puck's position, the reward the negative distance to the goal. By
default the environments are worlds of one in-process engine; --servers N spreads them over N spear-server
processes (launched here) that step concurrently.

    PYTHONPATH=python /usr/bin/python3 examples/vector_env.py [--envs 16] [--steps 60] [--servers N] \\
        [--out out/vector_env.png]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Mapping
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
from spear.vector import Box, CameraImage, StepResult, VectorEnv

SIZE = 96  # camera pixels per side
HORIZON = 200  # steps before an episode is truncated
ARENA = 2.0  # the puck and the goal start within +-ARENA metres of the centre


class PushPuck:
    """A 0.4 m puck on a 6 x 6 m floor, an overhead camera, and a goal disc; the action is a force in newtons
    along X and Y. The episode ends (terminated) when the puck's centre is within 0.3 m of the goal's."""

    observation_space: Mapping[str, Box] = {
        "final_color": Box((SIZE, SIZE, 4), np.uint8, 0, 255),
        "puck": Box((2,), np.float64),
    }
    action_space = Box((2,), np.float32, -1.0, 1.0)

    def __init__(self) -> None:
        self.puck: spear.AStaticMeshActor | None = None
        self.goal: spear.AStaticMeshActor | None = None
        self.camera: spear.UCameraSensorComponent | None = None
        self.steps = 0

    def reset(self, world: spear.UWorld, seed: int) -> None:
        if self.puck is None:
            self.build(world)
        assert self.puck is not None and self.goal is not None
        rng = np.random.default_rng(seed)
        start, goal = rng.uniform(-ARENA, ARENA, size=(2, 2))
        self.goal.SetActorLocation(NewLocation=spear.FVector(float(goal[0]), float(goal[1]), 0.005))
        body = self.puck.StaticMeshComponent
        body.SetSimulatePhysics(bSimulate=False)  # a teleport, then physics again from rest
        self.puck.SetActorLocation(NewLocation=spear.FVector(float(start[0]), float(start[1]), 0.15))
        body.SetSimulatePhysics(bSimulate=True)
        self.steps = 0

    def build(self, world: spear.UWorld) -> None:
        sun = world.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-60.0, Yaw=30.0))
        sun.LightComponent.Intensity = 3.0
        sky = world.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.SkyColor = spear.FLinearColor(0.15, 0.16, 0.2, 1.0)
        floor = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor", location=spear.FVector(Z=-0.05))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Plaster")
        floor.SetActorScale3D(NewScale3D=spear.FVector(6.0, 6.0, 0.1))
        floor.StaticMeshComponent.SetMobility(NewMobility=spear.EComponentMobility.Static)
        self.goal = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Goal")
        self.goal.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cylinder")
        self.goal.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Green")
        self.goal.SetActorScale3D(NewScale3D=spear.FVector(0.6, 0.6, 0.01))
        self.puck = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Puck")
        self.puck.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cylinder")
        self.puck.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Red")
        self.puck.SetActorScale3D(NewScale3D=spear.FVector(0.4, 0.4, 0.3))
        camera = world.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(Z=6.0),
                                   rotation=spear.FRotator(Pitch=-90.0))
        self.camera = camera.CameraSensor
        self.camera.Width, self.camera.Height, self.camera.FOV = SIZE, SIZE, 50.0
        self.camera.Modalities = [spear.ECameraModality.FinalColor]

    def act(self, world: spear.UWorld, action: NDArray[np.float32]) -> None:
        assert self.puck is not None
        force = 20.0 * np.clip(action, -1.0, 1.0)
        self.puck.StaticMeshComponent.AddForce(Force=spear.FVector(float(force[0]), float(force[1]), 0.0))
        self.steps += 1

    def observe(self, world: spear.UWorld) -> StepResult:
        assert self.puck is not None and self.goal is not None and self.camera is not None
        puck, goal = self.puck.GetActorLocation(), self.goal.GetActorLocation()
        distance = math.hypot(puck.X - goal.X, puck.Y - goal.Y)
        # The image is read by VectorEnv, with the other environments' cameras of the same engine, in one call.
        return StepResult(observation={"final_color": CameraImage(self.camera), "puck": np.array([puck.X, puck.Y])},
                          reward=-distance, terminated=distance < 0.3, truncated=self.steps >= HORIZON)


def grid(images: NDArray[np.uint8], gap: int = 2) -> NDArray[np.uint8]:
    """(N, H, W, 4) images tiled row by row into one RGB image, `gap` dark pixels between them."""
    n, h, w = images.shape[:3]
    columns = math.ceil(math.sqrt(n))
    rows = math.ceil(n / columns)
    sheet = np.full((rows * (h + gap) - gap, columns * (w + gap) - gap, 3), 40, np.uint8)
    for i in range(n):
        r, c = divmod(i, columns)
        y, x = r * (h + gap), c * (w + gap)
        sheet[y:y + h, x:x + w] = images[i, :, :, :3]
    return sheet


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--envs", type=int, default=16)
    parser.add_argument("--steps", type=int, default=60)
    parser.add_argument("--servers", type=int, default=0, help="spread the environments over N spear-servers")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("out/vector_env.png"))
    args = parser.parse_args()

    if args.servers:
        if args.envs % args.servers:
            parser.error(f"--envs {args.envs} must be a multiple of --servers {args.servers}")
        envs = VectorEnv.on_servers(PushPuck, num_servers=args.servers, worlds_per_server=args.envs // args.servers)
        where = f"{args.servers} spear-servers"
    else:
        envs = VectorEnv.in_worlds(PushPuck, num_envs=args.envs)
        where = "one in-process engine"
    rng = np.random.default_rng(args.seed)
    with envs:
        observations, _ = envs.reset(seed=args.seed)
        start = time.perf_counter()
        episodes, returns = 0, np.zeros(envs.num_envs)
        for _ in range(args.steps):
            actions = [PushPuck.action_space.sample(rng) for _ in range(envs.num_envs)]
            observations, rewards, terminated, truncated, _ = envs.step(actions)
            returns += rewards
            episodes += int(np.count_nonzero(terminated | truncated))
        elapsed = time.perf_counter() - start
        print(f"{envs.num_envs} environments in {where}: {args.steps} steps in {elapsed:.2f} s, "
              f"{envs.num_envs * args.steps / elapsed:.0f} environment steps/s; {episodes} episodes ended; "
              f"mean return {returns.mean():.1f}")
        args.out.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(grid(observations["final_color"])).save(args.out)
        print(f"wrote {args.out}: the {envs.num_envs} cameras after the last step")


if __name__ == "__main__":
    main()
