"""Procedural city (the paper's control_city_generator): road splines spell "SPEAR", a UPCGComponent fills an
APCGVolume with city blocks of buildings of random heights that keep off the roads, and a camera renders it
from above into a PNG. Then the roads change (the letters move apart) and Generate() rebuilds the city;
calling it again with nothing changed does nothing (the generation is cached until FlushCache()).

    PYTHONPATH=python /usr/bin/python3 examples/control_city_generator.py [--server launch] [--seed 3] [--out out/city.png]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false

from __future__ import annotations

import argparse
from pathlib import Path

from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

# Each letter's strokes in a 1 x 1.6 box (bottom left at the origin); a stroke of two points is straight,
# more points make a smooth curve through them.
LETTERS: dict[str, list[list[tuple[float, float]]]] = {
    "S": [[(1.0, 1.45), (0.5, 1.6), (0.05, 1.3), (0.3, 0.9), (0.75, 0.7), (0.95, 0.3), (0.5, 0.0), (0.0, 0.15)]],
    "P": [[(0.0, 0.0), (0.0, 1.6)], [(0.0, 1.6), (0.7, 1.55), (0.95, 1.2), (0.7, 0.85), (0.0, 0.8)]],
    "E": [[(0.0, 0.0), (0.0, 1.6)], [(0.0, 1.6), (1.0, 1.6)], [(0.0, 0.8), (0.8, 0.8)], [(0.0, 0.0), (1.0, 0.0)]],
    "A": [[(0.0, 0.0), (0.5, 1.6)], [(0.5, 1.6), (1.0, 0.0)], [(0.25, 0.7), (0.75, 0.7)]],
    "R": [[(0.0, 0.0), (0.0, 1.6)], [(0.0, 1.6), (0.7, 1.55), (0.95, 1.2), (0.7, 0.85), (0.0, 0.8)], [(0.3, 0.8), (1.0, 0.0)]],
}
SCALE = 24.0  # metres per letter unit
WIDTH, HEIGHT = 1280, 720


def lay_roads(game: spear.UWorld, word: str, pitch: float) -> list[spear.ASplineActor]:
    """One spline actor per stroke, tagged "Road", the letters `pitch` metres apart."""
    roads = []
    for i, letter in enumerate(word):
        for j, stroke in enumerate(LETTERS[letter]):
            road = game.spawn_actor(uclass=spear.ASplineActor, name=f"Road_{letter}{i}_{j}", tags=["Road"])
            road.SplineComponent.SetSplinePoints(
                Points=[spear.FVector(i * pitch + x * SCALE, y * SCALE, 0.0) for x, y in stroke],
                CoordinateSpace=spear.ESplineCoordinateSpace.World)
            roads.append(road)
    return roads


def render(camera: spear.ACameraSensorActor, instance: spear.Instance, out: Path) -> None:
    with instance.begin_frame():
        pass
    with instance.end_frame():
        pixels = camera.CameraSensor.read_pixels()
    if "final_color" not in pixels:
        raise spear.InvalidStateError("control_city_generator: the camera rendered no final_color")
    Image.fromarray(pixels["final_color"][:, :, :3].copy()).save(out)
    print(f"wrote {out}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--seed", type=int, default=3, help="the generator's seed")
    parser.add_argument("--out", default="out/city.png", help="the rendered view from above; a second view goes beside it")
    args = parser.parse_args()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
        for name, rgb in (("Ground", (0.2, 0.26, 0.12)), ("Concrete", (0.6, 0.6, 0.58)),
                          ("Brick", (0.55, 0.3, 0.22)), ("Glass", (0.25, 0.35, 0.45))):
            library.SetMaterial(Name=name, Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(*rgb, 1.0), Roughness=0.7))
        ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(80.0, 19.2, -0.5))
        ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        ground.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Ground")
        ground.SetActorScale3D(NewScale3D=spear.FVector(260.0, 140.0, 1.0))
        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-70.0, Yaw=-60.0))
        sun.LightComponent.Intensity = 3.0
        # A clear sky for the sun: the background, and the light on the sides the sun does not reach.
        game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Sky")

        lay_roads(game, "SPEAR", pitch=34.0)
        # The roads' lanes (UE's ZoneGraph), drawn as asphalt, sidewalks and lane markings: a lane each way and a
        # sidewalk each side, as wide as the city keeps its buildings from the road (RoadWidth).
        lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
        lanes.GetZoneGraphData().LaneProfile = [
            spear.FZoneLaneDesc(Tag="Sidewalk", Width=0.5), spear.FZoneLaneDesc(Tag="Driving", Width=1.5),
            spear.FZoneLaneDesc(Tag="Driving", Width=1.5, Direction=spear.EZoneLaneDirection.Backward),
            spear.FZoneLaneDesc(Tag="Sidewalk", Width=0.5, Direction=spear.EZoneLaneDirection.Backward)]
        print(f"lanes: {lanes.GetNumLanes()} lanes, {lanes.GetNumJunctions()} junctions", flush=True)
        city = game.spawn_actor(uclass=spear.APCGVolume, name="City", location=spear.FVector(80.0, 19.2, 10.0))
        city.BoxComponent.SetBoxExtent(InBoxExtent=spear.FVector(88.0, 28.0, 12.0))
        pcg = city.PCGComponent
        pcg.GenerationMode = spear.EPCGGenerationMode.CityBlocks
        pcg.Seed = args.seed
        pcg.BlockSize, pcg.StreetWidth, pcg.LotsPerSide = 2.0, 0.8, 1
        pcg.MinHeight, pcg.MaxHeight, pcg.RoadWidth = 1.5, 8.0, 4.0
        pcg.Materials = ["Concrete", "Brick", "Glass"]
        pcg.Generate()
        print(f"generated {len(pcg.GetGeneratedActors())} buildings in {pcg.GetLastGenerationSeconds() * 1000:.0f} ms "
              f"around {len(game.find_actors_by_tag(tag='Road'))} road splines", flush=True)

        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Above",
                                  location=spear.FVector(80.0, 19.2, 175.0), rotation=spear.FRotator(Pitch=-90.0, Yaw=90.0))
        camera.CameraSensor.Width, camera.CameraSensor.Height, camera.CameraSensor.FOV = WIDTH, HEIGHT, 60.0
    with instance.end_frame():
        pass
    render(camera, instance, out)

    # The roads change: the letters move apart, and the city is generated again around them.
    with instance.begin_frame():
        for road in game.find_actors_by_tag(tag="Road"):
            game.destroy_actor(actor=road)
        lay_roads(game, "SPEAR", pitch=36.0)
        print(f"lanes rebuilt: {lanes.GetNumLanes()} lanes, {lanes.GetNumJunctions()} junctions", flush=True)
        pcg.Generate()
        moved = pcg.GetGeneratedActors()
        print(f"roads moved: {len(moved)} buildings in {pcg.GetLastGenerationSeconds() * 1000:.0f} ms", flush=True)
        pcg.Generate()  # nothing changed since: cached, nothing rebuilt
        print(f"generate again with nothing changed: the same actors: {pcg.GetGeneratedActors() == moved}", flush=True)
    with instance.end_frame():
        pass
    render(camera, instance, out.with_name(out.stem + "_wide" + out.suffix))
    instance.close()


if __name__ == "__main__":
    main()
