"""Navigation: a navigation mesh built from a small walled yard, episode sampling the way embodied-AI work does it
(random start/goal pairs on the navigable area, shortest paths and geodesic distances in one batch call), and an
AI-controlled character walking the longest path while a camera follows it. Writes a top-down map (navigable
area, walls, every sampled path, the walked trajectory) and the follow camera's frames.

    PYTHONPATH=python /usr/bin/python3 examples/navigation.py [--server launch] [--episodes 8] [--out out/navigation]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

WIDTH, HEIGHT = 480, 270
MAP_PIXELS_PER_METRE = 24
Result = spear.ENavigationQueryResult

# Walls of the yard as (centre x, centre y, length x, length y), 2 m high: an outer fence, an inner wall with
# a door, and a few crates to walk around.
WALLS = [
    (0.0, -8.0, 24.0, 0.3), (0.0, 8.0, 24.0, 0.3), (-12.0, 0.0, 0.3, 16.0), (12.0, 0.0, 0.3, 16.0),
    (0.0, -4.5, 0.3, 7.0), (0.0, 5.0, 0.3, 6.0),
    (-6.0, 3.0, 1.5, 1.5), (-5.0, -3.5, 2.5, 1.0), (6.0, -2.0, 1.2, 4.0), (7.5, 5.0, 2.0, 2.0),
]


def build_yard(game: spear.UWorld) -> None:
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    library.SetMaterial(Name="Grass", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(0.25, 0.4, 0.18, 1.0), Roughness=0.9))
    library.SetMaterial(Name="Brick", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(0.55, 0.3, 0.22, 1.0), Roughness=0.8))
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(Z=-0.5))
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    ground.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Grass")
    ground.SetActorScale3D(NewScale3D=spear.FVector(26.0, 18.0, 1.0))
    for i, (x, y, sx, sy) in enumerate(WALLS):
        wall = game.spawn_actor(uclass=spear.AStaticMeshActor, name=f"Wall{i}", location=spear.FVector(x, y, 1.0))
        wall.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        wall.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Brick")
        wall.SetActorScale3D(NewScale3D=spear.FVector(sx, sy, 2.0))
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-55.0, Yaw=30.0))
    sun.LightComponent.Intensity = 3.0
    # A clear sky for that sun: the background, and the light on the sides the sun does not reach.
    game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Sky")
    # Navigation is built inside this volume: the yard within the fence.
    bounds = game.spawn_actor(uclass=spear.ANavMeshBoundsVolume, name="NavBounds", location=spear.FVector(Z=0.5))
    bounds.BoxComponent.SetBoxExtent(InBoxExtent=spear.FVector(12.5, 8.5, 2.0))


def to_map(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """World (x, y) in metres to map pixels (column, row), north up."""
    column = (points[..., 0] + 13.0) * MAP_PIXELS_PER_METRE
    row = (9.0 - points[..., 1]) * MAP_PIXELS_PER_METRE
    return np.stack([column, row], axis=-1)


def fill_triangles(image: NDArray[np.uint8], triangles: NDArray[np.float64], colour: tuple[int, int, int]) -> None:
    """Rasterises (T, 3, 3) world triangles onto the map (pixel centres inside each triangle)."""
    for corners in to_map(triangles):
        c0, r0 = (int(v) for v in np.floor(corners.min(axis=0)))
        c1, r1 = (int(v) for v in np.ceil(corners.max(axis=0)))
        cols, rows = np.meshgrid(np.arange(c0, c1 + 1) + 0.5, np.arange(r0, r1 + 1) + 0.5)
        a, b, c = corners
        def side(p: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.asarray((q[0] - p[0]) * (rows - p[1]) - (q[1] - p[1]) * (cols - p[0]), dtype=np.float64)
        s1, s2, s3 = side(a, b), side(b, c), side(c, a)
        inside = ((s1 >= 0) & (s2 >= 0) & (s3 >= 0)) | ((s1 <= 0) & (s2 <= 0) & (s3 <= 0))
        r, k = rows[inside].astype(int), cols[inside].astype(int)
        keep = (r >= 0) & (r < image.shape[0]) & (k >= 0) & (k < image.shape[1])
        image[r[keep], k[keep]] = colour


def draw_polyline(image: NDArray[np.uint8], points: NDArray[np.float64], colour: tuple[int, int, int], width: int = 1) -> None:
    pixels = to_map(points)
    for p, q in zip(pixels[:-1], pixels[1:]):
        steps = max(2, int(np.hypot(*(q - p)) * 2))
        for t in np.linspace(0.0, 1.0, steps):
            c, r = (p + t * (q - p)).astype(int)
            image[max(r - width, 0):r + width + 1, max(c - width, 0):c + width + 1] = colour


def follow(walker: spear.ACharacter, camera: spear.ACameraSensorActor) -> None:
    """Puts the camera 5 m behind and 4 m above the walker, looking where it faces."""
    location, yaw = walker.GetActorLocation(), walker.GetActorRotation().Yaw
    heading = (math.cos(math.radians(yaw)), math.sin(math.radians(yaw)))
    camera.K2_SetActorLocationAndRotation(
        NewLocation=spear.FVector(location.X - 5.0 * heading[0], location.Y - 5.0 * heading[1], location.Z + 4.0),
        NewRotation=spear.FRotator(Pitch=-35.0, Yaw=yaw))


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--episodes", type=int, default=8, help="random start/goal pairs to plan")
    parser.add_argument("--seed", type=int, default=1, help="seed of the navigation mesh's random points")
    parser.add_argument("--max-frames", type=int, default=900, help="longest walk, in frames (60 per second)")
    parser.add_argument("--every", type=int, default=30, help="save the follow camera's view every N frames")
    parser.add_argument("--out", default="out/navigation", help="folder for the frames; the map goes beside it")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        build_yard(game)
        system = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game)
        nav = system.GetDefaultNavDataInstance()
        nav.SetRandomSeed(Seed=args.seed)
        print(f"navigation mesh: {nav.GetNumTiles()} tiles, {nav.GetNumPolygons()} polygons, "
              f"{nav.GetNavigableArea():.1f} m^2 walkable, built in {nav.GetLastBuildSeconds() * 1000:.0f} ms", flush=True)
        starts = nav.GetRandomPoints(NumPoints=args.episodes)
        goals = nav.GetRandomPoints(NumPoints=args.episodes)
        paths = nav.FindPaths(StartPoints=starts, EndPoints=goals)
        triangles = nav.GetNavMeshTriangles()
    with instance.end_frame():
        pass

    episodes: list[NDArray[np.float64]] = []
    for i in range(args.episodes):
        points = paths.PathPoints[paths.PathStarts[i]:paths.PathStarts[i + 1]]
        straight = float(np.linalg.norm(goals[i] - starts[i]))
        status = Result(int(paths.Results[i])).name
        print(f"episode {i + 1}/{args.episodes}: {status}, geodesic {paths.Lengths[i]:.2f} m, "
              f"straight line {straight:.2f} m, {len(points)} corners", flush=True)
        episodes.append(points)
    longest = int(np.argmax(np.where(paths.Results == Result.Success, paths.Lengths, -1.0)))

    # Walk the longest path with an AI-controlled character, a camera following it.
    start, goal = starts[longest], goals[longest]
    with instance.begin_frame():
        walker = game.spawn_actor(uclass=spear.ACharacter, name="Walker", location=spear.FVector(start[0], start[1], start[2] + 0.95))
        walker.CharacterMovement.MaxWalkSpeed = 3.0
        ai = game.spawn_actor(uclass=spear.AAIController, name="Guide")
        ai.Possess(InPawn=walker)
        request = ai.MoveToLocation(Dest=spear.FVector(goal[0], goal[1], goal[2]), AcceptanceRadius=0.2)
        print(f"walking episode {longest + 1} ({paths.Lengths[longest]:.2f} m): {request.name}", flush=True)
        # The planned path as a debug line, so the follow camera's frames show where the walker is going.
        route = game.spawn_actor(uclass=spear.ASplineActor, name="Route").SplineComponent
        corners = episodes[longest]
        route.SetSplinePoints(Points=[spear.FVector(x, y, z + 0.05) for x, y, z in corners],
                              CoordinateSpace=spear.ESplineCoordinateSpace.World)
        route.bDrawDebug = True
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="FollowCamera")
        camera.CameraSensor.Width, camera.CameraSensor.Height, camera.CameraSensor.FOV = WIDTH, HEIGHT, 75.0
        follow(walker, camera)
    with instance.end_frame():
        pass
    trajectory: list[tuple[float, float, float]] = []
    saved = 0
    for frame in range(args.max_frames):
        with instance.begin_frame():
            location = walker.GetActorLocation()
            trajectory.append((location.X, location.Y, location.Z))
            moving = ai.GetMoveStatus() == spear.EPathFollowingStatus.Moving
            follow(walker, camera)
        with instance.end_frame():
            if frame % args.every == 0 or not moving:
                pixels = camera.CameraSensor.read_pixels()
                if "final_color" not in pixels:
                    raise spear.InvalidStateError("navigation: the follow camera rendered no final_color")
                Image.fromarray(pixels["final_color"][:, :, :3].copy()).save(out / f"frame_{frame:04d}.png")
                saved += 1
        if frame % 60 == 0 or not moving:
            left = math.dist((location.X, location.Y), (goal[0], goal[1]))
            print(f"frame {frame + 1}: walker at ({location.X:.1f}, {location.Y:.1f}), {left:.1f} m from the goal", flush=True)
        if not moving:
            break
    walked = float(np.linalg.norm(np.diff(np.array(trajectory)[:, :2], axis=0), axis=1).sum())
    print(f"walked {walked:.2f} m in {len(trajectory)} frames (the path is {paths.Lengths[longest]:.2f} m)")
    instance.close()

    # The map: navigable area, everything else dark, every sampled path, the walk in red.
    image = np.full((18 * MAP_PIXELS_PER_METRE, 26 * MAP_PIXELS_PER_METRE, 3), 40, dtype=np.uint8)
    fill_triangles(image, triangles, (200, 220, 190))
    for points in episodes:
        if len(points) > 1:
            draw_polyline(image, points, (60, 90, 200))
    draw_polyline(image, np.array(trajectory), (220, 40, 30), width=2)
    for point, colour in ((start, (30, 160, 30)), (goal, (230, 180, 20))):
        c, r = to_map(point).astype(int)
        image[r - 4:r + 5, c - 4:c + 5] = colour
    map_path = out.with_name(out.name + "_map.png")
    Image.fromarray(image).save(map_path)
    print(f"wrote {saved} frames to {out}/ and the map to {map_path}")


if __name__ == "__main__":
    main()
