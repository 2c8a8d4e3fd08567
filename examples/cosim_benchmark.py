"""The SPEAR paper's Table 3 co-simulation benchmark: end-to-end frame time with N dynamic objects pushed
by a fixed set of forces every step and 1 or 2 RGB views at 1920x1080 from a camera rig moving on a
fixed path, the images landing in numpy arrays, latency 0.

    PYTHONPATH=python /usr/bin/python3 examples/cosim_benchmark.py                 # every Table 3 cell
    PYTHONPATH=python /usr/bin/python3 examples/cosim_benchmark.py --objects 16 --views 2 --frames 200
    PYTHONPATH=python /usr/bin/python3 examples/cosim_benchmark.py --server launch  # over RPC
    PYTHONPATH=python /usr/bin/python3 examples/cosim_benchmark.py --physics mujoco # MuJoCo steps, spear renders
                                        # (the mujoco_interop plugin, built with spear when MuJoCo is installed)
    PYTHONPATH=python /usr/bin/python3 examples/cosim_benchmark.py --forces batched # one add_forces call a frame
    PYTHONPATH=python /usr/bin/python3 examples/cosim_benchmark.py --no-shadows     # the sun casts none

The workload (bench/mujoco_cosim_peer.cpp runs the same one in MuJoCo alone, for comparison):
- frame dt 1/60 s, physics in 4 substeps of 1/240 s;
- a static 40 x 40 m ground; N objects on a 0.8 m grid, boxes (even i) and spheres (odd i) of 0.3 m,
  1 kg, friction 0.8;
- at frame k (t = k/60) object i is pushed by 4 N * (cos(1.5 t + 2 pi i / N), sin(1.5 t + 2 pi i / N), 0)
  for the whole frame, sent with the asynchronous API (one message per frame over RPC): one AddForce per
  object as the paper does, or with --forces batched all of them in one UWorld.add_forces call;
- one shadow-casting sun (2048-texel shadow map; with --no-shadows, none) and a uniform sky;
- the rig circles the scene at radius 0.4 * ceil(sqrt(N)) + 5 m, 2.5 m high, 0.3 rad/s, looking at
  (0, 0, 0.2); view 0 is at the rig, view 1 0.3 m to its right; horizontal FOV 60 degrees.
The time of a frame is from the start of its begin_frame block until every view's final_color is in a
numpy array, physics included; 10 warm-up frames are not counted.

--breakdown also prints where a frame's time went, per frame on average: `calls` (the begin_frame block:
forces and the rig's move queued or sent), `tick` (leaving that block: the engine runs the calls, steps
physics and submits the render), `read` (the views' read_pixels, waiting for the GPU included) and `end`
(leaving end_frame); then, inside tick, the world's own CPU times from get_frame_timings (physics, and
rendering: gathering the views and issuing their GPU work); then the renderer's times from GetRenderStats:
shadow and surface passes by GL timer queries (the device's clock, overlapping the above) and the CPU's
readback wait and copy.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

import spear

FRAME_DT = 1.0 / 60.0
WARMUP_FRAMES = 10
SIZE = 0.3  # box edge and sphere diameter, metres
FORCE = 4.0  # newtons
BASELINE = 0.3  # metres between the two views
PAPER_TABLE3 = {  # milliseconds per frame, supplement Table 3 (UE 5 on an RTX 4090 laptop)
    "UnrealCV+": {(4, 1): 279.4, (16, 1): 293.7, (64, 1): 288.8, (4, 2): 528.5, (16, 2): 521.4, (64, 2): 541.6},
    "SPEAR": {(4, 1): 19.2, (16, 1): 20.2, (64, 1): 30.9, (4, 2): 30.8, (16, 2): 31.7, (64, 2): 34.7},
}


@dataclass(frozen=True)
class Result:
    objects: int
    views: int
    width: int
    height: int
    frames: int
    transport: str
    physics: str
    ms_per_frame: float
    device: str
    forces: str = "each"  # one AddForce per object, or "batched": one add_forces call
    phases: dict[str, float] = field(default_factory=dict[str, float])  # --breakdown: milliseconds per frame by phase


def grid_position(i: int, n: int) -> tuple[float, float]:
    side = math.ceil(math.sqrt(n))
    return 0.8 * (i % side) - 0.4 * (side - 1), 0.8 * (i // side) - 0.4 * (side - 1)


def colour(i: int) -> spear.FLinearColor:
    return spear.FLinearColor(0.2 + 0.6 * ((i * 37) % 11) / 10, 0.2 + 0.6 * ((i * 17) % 7) / 6,
                              0.2 + 0.6 * ((i * 53) % 5) / 4, 1.0)


def force(i: int, n: int, frame: int) -> spear.FVector:
    angle = 1.5 * frame * FRAME_DT + 2.0 * math.pi * i / n
    return spear.FVector(FORCE * math.cos(angle), FORCE * math.sin(angle), 0.0)


def rig_pose(n: int, frame: int) -> tuple[spear.FVector, spear.FRotator, tuple[float, float, float]]:
    """The rig's location, its rotation, and its right vector at a frame."""
    radius = 0.4 * math.ceil(math.sqrt(n)) + 5.0
    angle = 0.3 * frame * FRAME_DT
    eye = (radius * math.cos(angle), radius * math.sin(angle), 2.5)
    forward = (0.0 - eye[0], 0.0 - eye[1], 0.2 - eye[2])
    length = math.sqrt(sum(c * c for c in forward))
    forward = (forward[0] / length, forward[1] / length, forward[2] / length)
    right_length = math.hypot(forward[0], forward[1])
    right = (forward[1] / right_length, -forward[0] / right_length, 0.0)  # forward x up
    rotation = spear.FRotator(Pitch=math.degrees(math.asin(forward[2])),
                              Yaw=math.degrees(math.atan2(forward[1], forward[0])), Roll=0.0)
    return spear.FVector(*eye), rotation, right


def add_lights(game: spear.UWorld, shadows: bool = True) -> None:
    """The sun, shining along (-0.5, -0.3, -1), with shadows unless told, and a uniform sky."""
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(
        Pitch=-math.degrees(math.atan2(1.0, math.hypot(0.5, 0.3))), Yaw=math.degrees(math.atan2(-0.3, -0.5))))
    sun.LightComponent.Intensity = 3.0
    sun.LightComponent.bCastShadows = shadows
    sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
    sky.SkyLightComponent.SkyColor = spear.FLinearColor(0.1, 0.12, 0.15, 1.0)
    sky.SkyLightComponent.Intensity = 1.0  # the peer's ambient term, (0.1, 0.12, 0.15)
    sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(0.3, 0.35, 0.45, 1.0)


def build_scene(game: spear.UWorld, n: int, shadows: bool = True) -> list[spear.UStaticMeshComponent]:
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    library.SetMaterial(Name="Ground", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(0.55, 0.55, 0.5, 1.0), Roughness=0.9))
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    ground.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Ground")
    ground.SetActorScale3D(NewScale3D=spear.FVector(40.0, 40.0, 1.0))
    bodies: list[spear.UStaticMeshComponent] = []
    for i in range(n):
        x, y = grid_position(i, n)
        library.SetMaterial(Name=f"Object{i}", Material=spear.FMaterialDesc(BaseColor=colour(i), Roughness=0.5))
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=f"Object{i}",
                                 location=spear.FVector(x, y, SIZE / 2 + 0.001))
        mesh = actor.StaticMeshComponent
        mesh.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube" if i % 2 == 0 else "/Engine/BasicShapes/Sphere")
        mesh.SetMaterial(ElementIndex=0, Material=f"Object{i}")
        mesh.SetRelativeScale3D(NewScale3D=spear.FVector(SIZE, SIZE, SIZE))
        mesh.Friction = 0.8
        mesh.SetMassOverrideInKg(MassInKg=1.0)
        mesh.SetSimulatePhysics(bSimulate=True)
        bodies.append(mesh)
    add_lights(game, shadows)
    return bodies


def mjcf(n: int) -> str:
    """The same workload as an MJCF model for --physics mujoco (and bench/mujoco_cosim_peer.cpp)."""
    bodies: list[str] = []
    for i in range(n):
        x, y = grid_position(i, n)
        c = colour(i)
        shape = 'type="box" size="0.15 0.15 0.15"' if i % 2 == 0 else 'type="sphere" size="0.15"'
        bodies.append(f'<body name="object_{i}" pos="{x!r} {y!r} {SIZE / 2 + 0.001!r}"><freejoint/>'
                      f'<geom {shape} mass="1" friction="0.8 0.005 0.0001" rgba="{c.R!r} {c.G!r} {c.B!r} 1"/></body>')
    return (f'<mujoco model="cosim"><option timestep="{FRAME_DT / 4!r}"/>'
            '<size nconmax="2000" njmax="8000"/><worldbody>'
            '<geom name="ground" type="plane" size="20 20 0.1" rgba="0.55 0.55 0.5 1" friction="0.8 0.005 0.0001"/>'
            + "".join(bodies) + "</worldbody></mujoco>")


def build_mujoco_scene(instance: spear.Instance, game: spear.UWorld, n: int, shadows: bool = True) -> Any:
    """MuJoCo owns the dynamics (the mujoco_interop plugin); spear renders the actors it moves."""
    build = Path(os.environ.get("SPEAR_PLUGIN_DIR", Path(__file__).resolve().parent.parent / "build" / "python"))
    if not (build / "mujoco_interop").is_dir():
        raise spear.NotFoundError(f"cosim_benchmark: --physics mujoco needs the mujoco_interop plugin in {build} "
                                  "(built with spear when Debian's libmujoco-dev is installed)")
    sys.path.insert(0, str(build))
    instance.load_plugin("mujoco_interop")
    # The plugin's classes are typed by its own stubs (examples/mujoco_interop); here they are used by name.
    scene: Any = game.spawn_actor(uclass="AMujocoScene", name="Mujoco")
    scene.LoadMjcfString(Xml=mjcf(n))
    add_lights(game, shadows)
    return scene


def forces(n: int, frame: int) -> NDArray[np.float64]:
    """MuJoCo's xfrc_applied rows (force only) for every body; row 0 is the world body."""
    rows = np.zeros((n + 1, 3))
    for i in range(n):
        f = force(i, n, frame)
        rows[i + 1] = (f.X, f.Y, f.Z)
    return rows


def configure(camera: spear.UCameraSensorComponent, width: int, height: int) -> None:
    camera.Width, camera.Height, camera.FOV = width, height, 60.0
    camera.ShadowResolution = 2048
    camera.Modalities = [spear.ECameraModality.FinalColor]
    camera.Latency = 0


def run(instance: spear.Instance, *, objects: int, views: int, width: int, height: int, frames: int,
        physics: str, png: Path | None, breakdown: bool = False, batched_forces: bool = False,
        shadows: bool = True,
        global_illumination: spear.EGlobalIlluminationQuality | None = None,
        anti_aliasing: spear.EAntiAliasingMethod = spear.EAntiAliasingMethod.AAM_FXAA,
        ambient_occlusion: float | None = None) -> Result:
    game = instance.get_game()
    rig: spear.AActor
    bodies: list[spear.UStaticMeshComponent] = []
    mujoco: Any = None
    with instance.begin_frame():
        if physics == "mujoco":
            mujoco = build_mujoco_scene(instance, game, objects, shadows)
        else:
            bodies = build_scene(game, objects, shadows)
        location, rotation, _ = rig_pose(objects, 0)
        if views == 1:
            single = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Rig", location=location, rotation=rotation)
            cameras = [single.CameraSensor]
            rig = single
        else:
            stereo = game.spawn_actor(uclass=spear.AStereoCameraRig, name="Rig", location=location, rotation=rotation)
            stereo.Baseline = BASELINE
            cameras = [stereo.LeftCamera, stereo.RightCamera]  # left = view 0 at the rig's path
            rig = stereo
        for camera in cameras:
            configure(camera, width, height)
            if global_illumination is not None:  # else the camera's default
                camera.GlobalIlluminationQuality = global_illumination
            camera.AntiAliasingMethod = anti_aliasing
            if ambient_occlusion is not None:  # else the camera's default
                camera.AmbientOcclusionIntensity = ambient_occlusion
        device = cameras[0].get_render_device_info()
    with instance.end_frame():
        pass

    images: list[NDArray[np.uint8]] = []
    started = 0.0
    report_every = max(1, frames // 10)
    phases = Phases() if breakdown else None
    for frame in range(WARMUP_FRAMES + frames):
        if frame == WARMUP_FRAMES:
            if phases is not None:
                phases.sums = dict.fromkeys(phases.sums, 0.0)  # the warm-up frames are not counted
            started = time.perf_counter()
        if phases is not None:
            phases.mark("begin")
        with instance.begin_frame():
            if mujoco is not None:  # one call sets the forces, one steps MuJoCo and moves every actor
                mujoco.send_async.SetForces(Forces=forces(objects, frame))
                mujoco.send_async.Step(NumSteps=4)
            if batched_forces and bodies:
                game.send_async.add_forces(components=bodies, forces=forces(objects, frame)[1:])
            else:
                for i, body in enumerate(bodies):
                    body.send_async.AddForce(Force=force(i, objects, frame))
            location, rotation, right = rig_pose(objects, frame)
            if views == 2:  # the rig's centre is half a baseline right of view 0
                half = BASELINE / 2
                location = spear.FVector(location.X + half * right[0], location.Y + half * right[1], location.Z)
            rig.send_async.K2_SetActorLocationAndRotation(NewLocation=location, NewRotation=rotation)
            if phases is not None:
                phases.mark("calls")
        if phases is not None:
            phases.mark("tick")
        with instance.end_frame():
            images = []
            for camera in cameras:
                pixels = camera.read_pixels()
                if "final_color" not in pixels:
                    raise spear.InvalidStateError("cosim_benchmark: a view rendered no final_color")
                images.append(pixels["final_color"])
            if phases is not None:
                phases.mark("read")
                if frame == WARMUP_FRAMES - 1:  # the totals before the timed frames
                    phases.before = cameras[0].GetRenderStats()
                    phases.world_before = game.get_frame_timings()
        if phases is not None:
            phases.mark("end")
        done = frame + 1 - WARMUP_FRAMES
        if done > 0 and (done % report_every == 0 or done == frames):
            elapsed = time.perf_counter() - started
            print(f"  N={objects} views={views}: {done}/{frames} frames, {1000 * elapsed / done:.1f} ms/frame",
                  file=sys.stderr, flush=True)
    elapsed = time.perf_counter() - started
    measured: dict[str, float] = {}
    if phases is not None:  # the totals after them, read before another frame renders
        with instance.begin_frame():
            measured = phases.finish(game.get_frame_timings(), cameras[0].GetRenderStats(), frames)
        with instance.end_frame():
            pass
    if png is not None and images:
        from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs
        png.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(images[0][:, :, :3]).save(png)
    return Result(objects, views, width, height, frames, instance.transport, physics,
                  1000.0 * elapsed / frames, f"{device.Kind}: {device.Renderer}",
                  forces="batched" if batched_forces and bodies else "each", phases=measured)


class Phases:
    """--breakdown: the wall-clock time between marks, summed per phase over the timed frames, and the world's
    stage times and the renderer's pass times over the same frames (get_frame_timings and GetRenderStats
    totals, taken before and after)."""

    def __init__(self) -> None:
        self.sums: dict[str, float] = {"calls": 0.0, "tick": 0.0, "read": 0.0, "end": 0.0}
        self.last = 0.0
        self.before = spear.FRenderStats()
        self.world_before = spear.FFrameTimings()

    def mark(self, phase: str) -> None:
        now = time.perf_counter()
        if phase in self.sums and self.last:
            self.sums[phase] += now - self.last
        self.last = now

    def finish(self, world: spear.FFrameTimings, after: spear.FRenderStats, frames: int) -> dict[str, float]:
        result = {phase: 1000.0 * total / frames for phase, total in self.sums.items()}
        result["physics"] = (world.PhysicsMs - self.world_before.PhysicsMs) / frames
        result["rendering"] = (world.RenderingMs - self.world_before.RenderingMs) / frames
        result["gpu shadow"] = (after.ShadowMs - self.before.ShadowMs) / frames
        result["gpu surface"] = (after.SurfaceMs - self.before.SurfaceMs) / frames
        result["readback"] = (after.ReadbackMs - self.before.ReadbackMs) / frames
        return result


def table(results: list[Result]) -> str:
    """Table 3's shape: rows are simulators, columns N = 4/16/64 for 1 view, then for 2 views."""
    columns = sorted({(r.views, r.objects) for r in results})
    head = " | ".join(f"N={n}, {v} view{'s' if v > 1 else ''}" for v, n in columns)
    lines = [f"| simulator | {head} |", "|---|" + "---:|" * len(columns)]
    first = results[0]
    ours = {(r.objects, r.views): r.ms_per_frame for r in results}
    batched = ", batched forces" if first.forces == "batched" else ""
    label = f"spear ({first.transport}, {first.physics}{batched}, {first.width}x{first.height})"
    lines.append(f"| {label} | " + " | ".join(f"{ours[(n, v)]:.1f}" for v, n in columns) + " |")
    for name, cells in PAPER_TABLE3.items():
        lines.append(f"| {name} (paper, RTX 4090 laptop) | "
                     + " | ".join(f"{cells[(n, v)]:.1f}" if (n, v) in cells else "-" for v, n in columns) + " |")
    return "\n".join(lines)


def breakdown_table(results: list[Result]) -> str:
    """--breakdown: one row per cell, milliseconds per frame by phase."""
    names = list(results[0].phases)
    lines = ["| cell | frame | " + " | ".join(names) + " |", "|---|---:|" + "---:|" * len(names)]
    for r in results:
        lines.append(f"| N={r.objects}, {r.views} view{'s' if r.views > 1 else ''} | {r.ms_per_frame:.2f} | "
                     + " | ".join(f"{r.phases[name]:.2f}" for name in names) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--objects", type=int, nargs="+", default=[4, 16, 64], help="dynamic objects (N)")
    parser.add_argument("--views", type=int, nargs="+", default=[1, 2], choices=[1, 2], help="rendered views")
    parser.add_argument("--width", type=int, default=1920)
    parser.add_argument("--height", type=int, default=1080)
    parser.add_argument("--frames", type=int, default=1000, help="timed frames per cell (after 10 warm-up)")
    parser.add_argument("--server", default=None, help='None: in-process; "launch", "unix:PATH" or "tcp:HOST:PORT"')
    parser.add_argument("--physics", choices=["bullet", "mujoco"], default="bullet")
    parser.add_argument("--json", type=Path, default=None, help="also write the results as JSON")
    parser.add_argument("--png", type=Path, default=None, help="write view 0 of the last frame of each cell here")
    parser.add_argument("--breakdown", action="store_true", help="also print where a frame's time went, by phase")
    parser.add_argument("--forces", choices=["each", "batched"], default="each",
                        help="one AddForce per object (the paper's way), or one add_forces call for all")
    parser.add_argument("--no-shadows", action="store_true", help="the sun casts no shadows")
    parser.add_argument("--global-illumination", default=None,
                        choices=[q.name for q in spear.EGlobalIlluminationQuality],
                        help="the cameras' GlobalIlluminationQuality (default: the camera's, Medium)")
    parser.add_argument("--anti-aliasing", default="AAM_FXAA", choices=[m.name for m in spear.EAntiAliasingMethod],
                        help="the cameras' AntiAliasingMethod (AAM_FXAA: the camera's default)")
    parser.add_argument("--ambient-occlusion", type=float, default=None,
                        help="the cameras' AmbientOcclusionIntensity in [0, 1], 0 off (default: the camera's)")
    args = parser.parse_args(argv)

    results: list[Result] = []
    for views in args.views:
        for objects in args.objects:
            if objects < 1:
                parser.error(f"--objects must be >= 1, got {objects}")
            instance = spear.Instance(server=args.server, fixed_delta_seconds=FRAME_DT)
            try:
                png = None if args.png is None else args.png / f"cosim_n{objects}_v{views}.png"
                results.append(run(instance, objects=objects, views=views, width=args.width, height=args.height,
                                   frames=args.frames, physics=args.physics, png=png, breakdown=args.breakdown,
                                   batched_forces=args.forces == "batched", shadows=not args.no_shadows,
                                   global_illumination=(None if args.global_illumination is None else
                                                        spear.EGlobalIlluminationQuality[args.global_illumination]),
                                   anti_aliasing=spear.EAntiAliasingMethod[args.anti_aliasing],
                                   ambient_occlusion=args.ambient_occlusion))
            finally:
                instance.close()
            print(f"N={objects}, {views} view(s): {results[-1].ms_per_frame:.1f} ms/frame", file=sys.stderr)
    print(f"device: {results[0].device}")
    print(table(results))
    if args.breakdown:
        print(breakdown_table(results))
    if args.json is not None:
        args.json.write_text(json.dumps([asdict(r) for r in results], indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
