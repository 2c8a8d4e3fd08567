"""City traffic (the paper's control_city_sample): a street grid whose road splines become lanes (UE's ZoneGraph
names), a procedural city around them, cars placed on lanes with FindNearestLaneLocationByName and driven by
ALaneFollowingController through their own throttle, steering and brake. Player 0 possesses one car and drives
it with input, keeping to its lane by the lane queries, stops before the next junction and hands the car to an
autopilot. A chase camera follows the player's car; a map from above shows every lane and where each car went.

    PYTHONPATH=python /usr/bin/python3 examples/control_city_sample.py [--server launch] [--cars 16] [--frames 900] [--out out/control_city_sample]
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

BLOCK = 60.0              # metres between the streets' centre lines
COLUMNS, ROWS = 4, 3      # blocks
CHASE = (480, 270)        # the chase camera's image
MAP_PIXELS_PER_METRE = 2.0
MARGIN = 12.0             # metres of map round the streets
PAINTS = [(0.6, 0.05, 0.04), (0.05, 0.2, 0.55), (0.85, 0.85, 0.8), (0.1, 0.1, 0.1), (0.8, 0.55, 0.05), (0.15, 0.4, 0.2)]


def build_city(game: spear.UWorld, seed: int) -> spear.UZoneGraphSubsystem:
    """Grass, the sun and sky, a grid of streets (one road spline between each two crossings) and the
    buildings of a procedural city kept off them."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    for name, rgb in (("Grass", (0.2, 0.26, 0.12)), ("Concrete", (0.6, 0.6, 0.58)), ("Brick", (0.55, 0.3, 0.22)),
                      ("Glass", (0.25, 0.35, 0.45)), ("Tyre", (0.03, 0.03, 0.03)), ("Window", (0.05, 0.07, 0.1))):
        library.SetMaterial(Name=name, Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(*rgb, 1.0), Roughness=0.7))
    for i, rgb in enumerate(PAINTS):
        library.SetMaterial(Name=f"Paint{i}", Material=spear.FMaterialDesc(
            BaseColor=spear.FLinearColor(*rgb, 1.0), Roughness=0.3, Metallic=0.4))
    width, height = COLUMNS * BLOCK, ROWS * BLOCK
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground",
                              location=spear.FVector(width / 2, height / 2, -0.5))
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    ground.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Grass")
    ground.SetActorScale3D(NewScale3D=spear.FVector(width + 200.0, height + 200.0, 1.0))
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-55.0, Yaw=-40.0))
    sun.LightComponent.Intensity = 3.0
    game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Sky")

    def street(name: str, a: tuple[float, float], b: tuple[float, float]) -> None:
        road = game.spawn_actor(uclass=spear.ASplineActor, name=name, tags=["Road"])
        road.SplineComponent.SetSplinePoints(Points=[spear.FVector(a[0], a[1], 0.0), spear.FVector(b[0], b[1], 0.0)],
                                             CoordinateSpace=spear.ESplineCoordinateSpace.World)

    for row in range(ROWS + 1):
        for column in range(COLUMNS):
            street(f"Street_{row}_{column}", (column * BLOCK, row * BLOCK), ((column + 1) * BLOCK, row * BLOCK))
    for column in range(COLUMNS + 1):
        for row in range(ROWS):
            street(f"Avenue_{column}_{row}", (column * BLOCK, row * BLOCK), (column * BLOCK, (row + 1) * BLOCK))

    city = game.spawn_actor(uclass=spear.APCGVolume, name="City", location=spear.FVector(width / 2, height / 2, 20.0))
    city.BoxComponent.SetBoxExtent(InBoxExtent=spear.FVector(width / 2 - 10.0, height / 2 - 10.0, 25.0))
    pcg = city.PCGComponent
    pcg.GenerationMode = spear.EPCGGenerationMode.CityBlocks
    pcg.Seed = seed
    pcg.BlockSize, pcg.StreetWidth, pcg.LotsPerSide = 20.0, 2.0, 2
    pcg.MinHeight, pcg.MaxHeight, pcg.RoadWidth = 6.0, 30.0, 15.0  # buildings keep off the 11 m roads
    pcg.Materials = ["Concrete", "Brick", "Glass"]
    pcg.Generate()
    print(f"city: {len(pcg.GetGeneratedActors())} buildings", flush=True)
    lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
    print(f"lanes: {lanes.GetNumLanes()} lanes ({', '.join(lanes.GetLaneTags())}), {lanes.GetNumJunctions()} junctions",
          flush=True)
    return lanes


def spawn_car(game: spear.UWorld, name: str, at: spear.FZoneGraphLaneLocation, paint: int) -> spear.AWheeledVehiclePawn:
    """A car on a lane location, facing the way the lane runs."""
    yaw = math.degrees(math.atan2(at.Direction.Y, at.Direction.X))
    car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name=name,
                           location=spear.FVector(at.Position.X, at.Position.Y, 0.9), rotation=spear.FRotator(Yaw=yaw))
    car.Mesh.SetMaterial(ElementIndex=0, Material=f"Paint{paint % len(PAINTS)}")
    car.Cabin.SetMaterial(ElementIndex=0, Material="Window")
    for wheel in (car.WheelFrontLeft, car.WheelFrontRight, car.WheelRearLeft, car.WheelRearRight):
        wheel.SetMaterial(ElementIndex=0, Material="Tyre")
    return car


def place_traffic(game: spear.UWorld, lanes: spear.UZoneGraphSubsystem, count: int, rng: np.random.Generator,
                  keep_clear: spear.FVector) -> tuple[list[spear.AWheeledVehiclePawn], list[spear.ALaneFollowingController]]:
    """Cars at random points of the city moved onto the nearest driving lane (the paper's call), at least 15 m
    apart and from `keep_clear`, each with a driver of its own speed."""
    cars: list[spear.AWheeledVehiclePawn] = []
    drivers: list[spear.ALaneFollowingController] = []
    taken: list[spear.FVector] = [keep_clear]
    while len(cars) < count:
        x, y = rng.uniform(0.0, COLUMNS * BLOCK), rng.uniform(0.0, ROWS * BLOCK)
        at = lanes.FindNearestLaneLocationByName(Location=spear.FVector(x, y, 0.0), TagName="Driving", MaxDistance=30.0)
        if at.LaneIndex < 0 or lanes.GetLaneRoad(LaneIndex=at.LaneIndex) is None:
            continue  # nothing near, or inside a junction
        if any(math.hypot(at.Position.X - p.X, at.Position.Y - p.Y) < 15.0 for p in taken):
            continue
        car = spawn_car(game, f"Car{len(cars)}", at, len(cars))
        driver = game.spawn_actor(uclass=spear.ALaneFollowingController, name=f"Driver{len(cars)}")
        driver.TargetSpeed = float(rng.uniform(7.0, 11.0))
        driver.Possess(InPawn=car)
        cars.append(car)
        drivers.append(driver)
        taken.append(at.Position)
    return cars, drivers


def player_input(lanes: spear.UZoneGraphSubsystem, car: spear.AWheeledVehiclePawn) -> dict[str, float]:
    """What the player does: keep to the lane under the car (steer toward its point 8 m ahead), hold 8 m/s,
    and brake to a stop before the lane's end (the junction)."""
    location, yaw = car.GetActorLocation(), math.radians(car.GetActorRotation().Yaw)
    at = lanes.FindNearestLaneLocationByName(Location=location, TagName="Driving", MaxDistance=10.0)
    if at.LaneIndex < 0:
        return {"Brake": 1.0}
    ahead = lanes.AdvanceLaneLocation(InLaneLocation=at, AdvanceDistance=8.0)
    dx, dy = ahead.Position.X - location.X, ahead.Position.Y - location.Y
    bearing = math.atan2(dy, dx) - yaw
    steer = max(-1.0, min(1.0, math.atan2(math.sin(bearing), math.cos(bearing)) / math.radians(car.MaxSteerAngle)))
    remaining = lanes.GetLaneLength(LaneIndex=at.LaneIndex) - at.DistanceAlongLane
    speed = car.GetForwardSpeed()
    wanted = min(8.0, max(0.0, math.sqrt(max(remaining - 6.0, 0.0) * 2.0 * 2.5)))  # braking at 2.5 m/s²
    if wanted < 0.5 and speed < 1.0:  # at the stop: hold it
        return {"Steer": steer, "Brake": 1.0}
    if speed > wanted + 0.3:
        return {"Steer": steer, "Brake": min(1.0, (speed - wanted) * 0.3)}
    return {"Steer": steer, "Throttle": max(0.0, min(1.0, (wanted - speed) * 0.5))}


def chase(car: spear.AWheeledVehiclePawn, camera: spear.ACameraSensorActor) -> None:
    """The camera 9 m behind and 3.5 m above the car, looking along its heading and a little down."""
    location, yaw = car.GetActorLocation(), car.GetActorRotation().Yaw
    heading = (math.cos(math.radians(yaw)), math.sin(math.radians(yaw)))
    camera.K2_SetActorLocationAndRotation(
        NewLocation=spear.FVector(location.X - 9.0 * heading[0], location.Y - 9.0 * heading[1], location.Z + 3.5),
        NewRotation=spear.FRotator(Pitch=-12.0, Yaw=yaw))


def to_map(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """World (x, y) in metres to map pixels (column, row), north up."""
    column = (points[..., 0] + MARGIN) * MAP_PIXELS_PER_METRE
    row = (ROWS * BLOCK + MARGIN - points[..., 1]) * MAP_PIXELS_PER_METRE
    return np.stack([column, row], axis=-1)


def draw_polyline(image: NDArray[np.uint8], points: NDArray[np.float64], colour: tuple[int, int, int],
                  width: int = 0) -> None:
    pixels = to_map(points)
    for p, q in zip(pixels[:-1], pixels[1:]):
        for t in np.linspace(0.0, 1.0, max(2, int(np.hypot(*(q - p)) * 2))):
            c, r = (p + t * (q - p)).astype(int)
            if 0 <= r < image.shape[0] and 0 <= c < image.shape[1]:
                image[max(r - width, 0):r + width + 1, max(c - width, 0):c + width + 1] = colour


def draw_map(lanes: spear.UZoneGraphSubsystem, trails: list[list[tuple[float, float]]], player: int) -> NDArray[np.uint8]:
    """Every lane (driving dark, sidewalks light) and each car's trail, the player's in red, ending in a dot.
    Called inside a frame (it asks for the lanes)."""
    size = to_map(np.array([COLUMNS * BLOCK + MARGIN, -MARGIN])).astype(int)
    image = np.full((size[1], size[0], 3), 245, dtype=np.uint8)
    points, starts = lanes.GetAllLanePoints()  # every lane at once: one call, not one per lane
    for lane in range(len(starts) - 1):
        driving = lanes.GetLaneTag(LaneIndex=lane) == "Driving"
        draw_polyline(image, points[starts[lane]:starts[lane + 1], :2], (120, 120, 130) if driving else (205, 205, 205))
    for i, trail in enumerate(trails):
        colour = (220, 30, 30) if i == player else (40, 90, 200)
        path = np.array(trail, dtype=np.float64)
        draw_polyline(image, path, colour, width=1 if i == player else 0)
        draw_polyline(image, path[-1:].repeat(2, axis=0), colour, width=3)
    return image


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--cars", type=int, default=16, help="cars driving by themselves")
    parser.add_argument("--frames", type=int, default=900, help="frames to run (60 per simulated second)")
    parser.add_argument("--handover", type=int, default=420, help="the frame the player hands the car to an autopilot")
    parser.add_argument("--every", type=int, default=30, help="save the chase camera's view every N frames")
    parser.add_argument("--seed", type=int, default=7, help="the city's and the traffic's seed")
    parser.add_argument("--out", default="out/control_city_sample", help="folder for the views, the map and the strip")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(args.seed)

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        lanes = build_city(game, args.seed)
        # The player's car: on the southern street, heading east, possessed by player 0.
        start = lanes.FindNearestLaneLocationByName(Location=spear.FVector(0.5 * BLOCK, 0.0, 0.0), TagName="Driving")
        if start.Direction.X < 0.0:  # the other way's lane: the one running east lies on the road's other side
            start = lanes.FindNearestLaneLocationByName(Location=spear.FVector(0.5 * BLOCK, -3.0, 0.0), TagName="Driving")
        cars, drivers = place_traffic(game, lanes, args.cars, rng, keep_clear=start.Position)
        hero = spawn_car(game, "PlayerCar", start, 0)
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        player.Possess(InPawn=hero)
        pawn = player.K2_GetPawn()
        assert pawn is not None
        print(f"player 0 drives {pawn.GetName()} from lane {start.LaneIndex} at "
              f"({start.Position.X:.1f}, {start.Position.Y:.1f})", flush=True)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="ChaseCamera")
        camera.CameraSensor.Width, camera.CameraSensor.Height = CHASE
        camera.CameraSensor.FOV = 75.0
        chase(hero, camera)
    with instance.end_frame():
        pass

    everyone = [*cars, hero]
    trails: list[list[tuple[float, float]]] = [[] for _ in everyone]
    views: list[NDArray[np.uint8]] = []
    worst = 0.0
    for frame in range(args.frames):
        with instance.begin_frame():
            if frame == args.handover:
                at = lanes.FindNearestLaneLocationByName(Location=hero.GetActorLocation(), TagName="Driving")
                print(f"frame {frame}: the player's car stands at {hero.GetForwardSpeed():.2f} m/s, "
                      f"{lanes.GetLaneLength(LaneIndex=at.LaneIndex) - at.DistanceAlongLane:.1f} m before the junction",
                      flush=True)
                autopilot = game.spawn_actor(uclass=spear.ALaneFollowingController, name="Autopilot")
                autopilot.Possess(InPawn=hero)  # takes the car from the player
                print(f"frame {frame}: the player hands {hero.GetName()} to the autopilot", flush=True)
            if frame < args.handover:
                for action, value in player_input(lanes, hero).items():
                    game.inject_input_for_actor(actor=player, input_action_name=action, value=spear.FVector(X=value))
            chase(hero, camera)
        with instance.end_frame():
            if frame % 10 == 0:
                for trail, car in zip(trails, everyone):
                    p = car.GetActorLocation()
                    trail.append((p.X, p.Y))
                if frame >= 60:  # under way: how far from its lane's centre line has any driver let its car go?
                    worst = max(worst, *(abs(driver.GetLateralOffset()) for driver in drivers))
            if frame % args.every == 0:
                pixels = camera.CameraSensor.read_pixels()
                if "final_color" not in pixels:
                    raise spear.InvalidStateError("control_city_sample: the chase camera rendered no final_color")
                view = pixels["final_color"][:, :, :3].copy()
                Image.fromarray(view).save(out / f"chase_{frame:04d}.png")
                views.append(view)
            if frame % 150 == 0 or frame == args.frames - 1:
                speeds = [car.GetForwardSpeed() for car in everyone]
                print(f"frame {frame + 1}/{args.frames}: player's car at {hero.GetForwardSpeed():.1f} m/s, traffic "
                      f"mean {np.mean(speeds[:-1]):.1f} m/s", flush=True)

    travelled = [sum(math.dist(a, b) for a, b in zip(t[:-1], t[1:])) for t in trails]
    print(f"traffic travelled {np.mean(travelled[:-1]):.0f} m on average, the player's car {travelled[-1]:.0f} m; "
          f"no car was more than {worst:.2f} m off its lane's centre line", flush=True)
    with instance.begin_frame():
        game_map = draw_map(lanes, trails, player=len(everyone) - 1)
    with instance.end_frame():
        pass
    Image.fromarray(game_map).save(out / "map.png")
    # The strip: four chase views across the run, two by two, beside the map scaled to their height.
    picks: list[NDArray[np.uint8]] = [views[int(i)] for i in np.linspace(0, len(views) - 1, 4)]
    grid: NDArray[np.uint8] = np.concatenate([np.concatenate(picks[:2], axis=1), np.concatenate(picks[2:], axis=1)], axis=0)
    scale = grid.shape[0] / game_map.shape[0]
    scaled: NDArray[np.uint8] = np.asarray(
        Image.fromarray(game_map).resize((int(game_map.shape[1] * scale), grid.shape[0])), dtype=np.uint8)
    Image.fromarray(np.concatenate([grid, scaled], axis=1)).save(out.with_suffix(".png"))
    print(f"wrote {len(views)} views and the map to {out}/, the strip to {out.with_suffix('.png')}", flush=True)
    instance.close()


if __name__ == "__main__":
    main()
