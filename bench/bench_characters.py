"""What animated characters cost: a 1080p frame of N walking humanoids against N static copies of the same mesh
in the same places, still and moving, and reading back all of 64 characters' poses every frame over RPC against
in-process.

    PYTHONPATH=python /usr/bin/python3 bench/bench_characters.py [--counts 1,16,64] [--frames 20]
        [--width 1920 --height 1080] [--no-rpc]

Each scene: a ground, a sun and a sky light, N humanoids (/Game/characters/humanoid.glb, 4,480 triangles) on a
grid 1.2 m apart, one camera rendering final_color with the default quality (global illumination on) seeing
them all. The skinned ones play "walk" (staggered), so each frame poses and skins every one of them; the static
ones are AStaticMeshActor copies, either still (what an unanimated crowd costs: its shadow maps are drawn once
and kept) or moving a millimetre each frame (rigid motion: the shadow maps are drawn again every frame, as they
are for walking characters). Printed: mean ms a frame (begin_frame to the read pixels) after a warm-up, and the
ratios; skinned over moving static is what skinning itself adds (goal <= 1.3x). Then 64 walking characters
without a camera, every pose read each frame, per character (call_async.GetBoneTransforms: one message per frame
over RPC, an array per character) and in one call (call_async.GetBoneTransformsOfComponents): ms a frame on each transport
and the ratio (goal <= 1.2x).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

HUMANOID = "/Game/characters/humanoid.glb"


def grid(count: int) -> list[tuple[float, float]]:
    side = math.ceil(math.sqrt(count))
    return [((i // side - (side - 1) / 2) * 1.2, (i % side - (side - 1) / 2) * 1.2) for i in range(count)]


def populate(game: spear.UWorld, count: int, skinned: bool) -> list[spear.AActor]:
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(Z=-0.05))
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    ground.SetActorScale3D(NewScale3D=spear.FVector(30.0, 30.0, 0.1))
    game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                     rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0)).LightComponent.Intensity = 10.0
    game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
    actors: list[spear.AActor] = []
    for i, (x, y) in enumerate(grid(count)):
        location, rotation = spear.FVector(x, y, 0.0), spear.FRotator(Yaw=180.0)
        if skinned:
            actor = game.spawn_actor(uclass=spear.ASkeletalMeshActor, location=location, rotation=rotation)
            mesh = actor.SkeletalMeshComponent
            mesh.SetSkeletalMesh(NewMesh=HUMANOID)
            mesh.PlayAnimation(NewAnimToPlay="walk", bLoop=True)
            mesh.SetPosition(InPos=(i * 0.137) % 1.1)
            actors.append(actor)
        else:
            static = game.spawn_actor(uclass=spear.AStaticMeshActor, location=location, rotation=rotation)
            static.StaticMeshComponent.SetStaticMesh(NewMesh=HUMANOID)
            actors.append(static)
    return actors


def render_frame_ms(count: int, kind: str, frames: int, width: int, height: int) -> float:
    """kind: "still" or "moving" static copies, or "skinned" walking characters."""
    instance = spear.Instance()
    game = instance.get_game()
    with instance.begin_frame():
        actors = populate(game, count, kind == "skinned")
        places = [actor.GetActorLocation() for actor in actors]
        reach = math.ceil(math.sqrt(count)) * 1.2 / 2 + 1.0
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                  location=spear.FVector(reach + 2.5 * reach, 0.0, 0.6 * reach + 1.5),
                                  rotation=spear.FRotator(Pitch=-25.0, Yaw=180.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = width, height, 60.0
        camera.Modalities = [spear.ECameraModality.FinalColor]
    times: list[float] = []
    for frame in range(frames + 5):
        start = time.perf_counter()
        if frame:
            with instance.begin_frame():
                if kind == "moving":
                    for actor, place in zip(actors, places):
                        actor.SetActorLocation(NewLocation=spear.FVector(place.X, place.Y, place.Z + 0.001 * (frame % 2)))
        with instance.end_frame():
            camera.read_pixels()
        if frame >= 5:  # after the first frames (probes placed and lit, programs compiled)
            times.append(time.perf_counter() - start)
    instance.close()
    return sum(times) / len(times) * 1000.0


def pose_readback_ms(server: str | None, frames: int, batched: bool) -> float:
    instance = spear.Instance(server=server)
    game = instance.get_game()
    with instance.begin_frame():
        meshes = [actor.SkeletalMeshComponent for actor in populate(game, 64, skinned=True)
                  if isinstance(actor, spear.ASkeletalMeshActor)]
    with instance.end_frame():
        pass
    times: list[float] = []
    for frame in range(frames + 5):
        start = time.perf_counter()
        with instance.begin_frame():
            if batched:  # the crowd in one array, with the frame's message
                poses = [meshes[0].call_async.GetBoneTransformsOfComponents(Components=meshes,
                                                                            Space=spear.EBoneSpaces.WorldSpace)]
            else:
                poses = [mesh.call_async.GetBoneTransforms(Space=spear.EBoneSpaces.WorldSpace) for mesh in meshes]
        with instance.end_frame():
            assert all(pose.get().shape == ((64, 18, 4, 4) if batched else (18, 4, 4)) for pose in poses)
        if frame >= 5:
            times.append(time.perf_counter() - start)
    instance.close()
    return sum(times) / len(times) * 1000.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--counts", default="1,16,64", help="numbers of characters (default: %(default)s)")
    parser.add_argument("--frames", type=int, default=20, help="frames timed per case (default: %(default)s)")
    parser.add_argument("--width", type=int, default=1920)
    parser.add_argument("--height", type=int, default=1080)
    parser.add_argument("--no-rpc", action="store_true", help="skip the pose read-back comparison")
    args = parser.parse_args()

    print(f"{args.width}x{args.height}, ms a frame:\n")
    print("| characters | static, still | static, moving | skinned, walking | skinned / moving (goal <= 1.3) "
          "| skinned / still |")
    print("|---:|---:|---:|---:|---:|---:|")
    for count in (int(c) for c in args.counts.split(",")):
        still, moving, skinned = (render_frame_ms(count, kind, args.frames, args.width, args.height)
                                  for kind in ("still", "moving", "skinned"))
        print(f"| {count} | {still:.1f} | {moving:.1f} | {skinned:.1f} | {skinned / moving:.2f} | {skinned / still:.2f} |",
              flush=True)
    if not args.no_rpc:
        print("\npose read-back, 64 walking characters, every pose each frame, ms a frame:\n")
        print("| how | in-process | RPC | RPC / in-process (goal <= 1.2) | RPC - in-process |")
        print("|---|---:|---:|---:|---:|")
        for batched, how in ((False, "GetBoneTransforms per character (call_async)"),
                             (True, "GetBoneTransformsOfComponents, one (64, 18, 4, 4) array (call_async)")):
            inprocess = pose_readback_ms(None, args.frames * 3, batched)
            rpc = pose_readback_ms("launch", args.frames * 3, batched)
            # The difference too: the transport's cost a frame, which the ratio sets against the engine's frame.
            print(f"| {how} | {inprocess:.2f} | {rpc:.2f} | {rpc / inprocess:.2f} | {rpc - inprocess:.2f} |", flush=True)


if __name__ == "__main__":
    main()
