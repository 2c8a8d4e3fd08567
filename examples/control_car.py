"""Drive a physically simulated car: AWheeledVehiclePawn (Bullet's raycast vehicle) possessed by player 0,
driven by input injected for the player controller, with a chase camera. The car accelerates past a crate,
turns left, pushes a second crate out of its way and brakes; every few frames the chase camera's view is saved
as an image sequence, and a strip of four views is written beside it.

    PYTHONPATH=python /usr/bin/python3 examples/control_car.py [--server launch] [--frames 240] [--out out/control_car]
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


def build_track(game: spear.UWorld) -> tuple[spear.AStaticMeshActor, spear.AStaticMeshActor]:
    """A large ground, the sun and sky, and two crates: one beside the road, one in the car's way."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    library.SetMaterial(Name="Asphalt", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(0.18, 0.18, 0.2, 1.0), Roughness=0.85))
    library.SetMaterial(Name="Crate", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(0.7, 0.45, 0.2, 1.0), Roughness=0.6))
    library.SetMaterial(Name="CarPaint", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(0.6, 0.05, 0.04, 1.0), Roughness=0.3, Metallic=0.4))
    library.SetMaterial(Name="Glass", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(0.05, 0.07, 0.1, 1.0), Roughness=0.1))
    library.SetMaterial(Name="Tyre", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(0.03, 0.03, 0.03, 1.0), Roughness=0.9))
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    ground.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Asphalt")
    ground.SetActorScale3D(NewScale3D=spear.FVector(200.0, 200.0, 1.0))
    crates = []
    for name, x, y in (("Pillar", 7.0, -4.0), ("Crate", 15.5, 9.5)):
        crate = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(x, y, 0.6))
        mesh = crate.StaticMeshComponent
        mesh.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        mesh.SetMaterial(ElementIndex=0, Material="Crate")
        mesh.SetRelativeScale3D(NewScale3D=spear.FVector(1.2, 1.2, 1.2))
        mesh.SetMassOverrideInKg(MassInKg=60.0)
        mesh.SetSimulatePhysics(bSimulate=True)
        crates.append(crate)
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=-30.0))
    sun.LightComponent.Intensity = 3.0
    # A clear sky for the sun: the background, and the light on the sides the sun does not reach.
    game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Sky")
    return crates[0], crates[1]


def paint(car: spear.AWheeledVehiclePawn) -> None:
    car.Mesh.SetMaterial(ElementIndex=0, Material="CarPaint")
    car.Cabin.SetMaterial(ElementIndex=0, Material="Glass")
    for wheel in (car.WheelFrontLeft, car.WheelFrontRight, car.WheelRearLeft, car.WheelRearRight):
        wheel.SetMaterial(ElementIndex=0, Material="Tyre")


def chase(car: spear.AWheeledVehiclePawn, camera: spear.ACameraSensorActor) -> None:
    """Puts the camera 7 m behind and 2.8 m above the car, looking along its heading and a little down."""
    location, yaw = car.GetActorLocation(), car.GetActorRotation().Yaw
    heading = (math.cos(math.radians(yaw)), math.sin(math.radians(yaw)))
    camera.K2_SetActorLocationAndRotation(
        NewLocation=spear.FVector(location.X - 7.0 * heading[0], location.Y - 7.0 * heading[1], location.Z + 2.8),
        NewRotation=spear.FRotator(Pitch=-13.0, Yaw=yaw))


def controls(frame: int) -> dict[str, float]:
    """The scripted drive: accelerate past the pillar, curve left, straighten into the crate, brake."""
    if frame < 30:
        return {}  # settle on the springs
    if frame < 110:
        return {"Throttle": 1.0}
    if frame < 170:
        return {"Throttle": 0.6, "Steer": 0.55}
    if frame < 215:
        return {"Throttle": 0.8}
    return {"Brake": 1.0}


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--frames", type=int, default=240, help="frames to drive (60 per simulated second)")
    parser.add_argument("--every", type=int, default=10, help="save the chase camera's view every N frames")
    parser.add_argument("--out", default="out/control_car", help="folder for the image sequence")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        pillar, crate = build_track(game)
        car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name="Car", location=spear.FVector(Z=0.9))
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        paint(car)
        player.Possess(InPawn=car)  # the player's input now drives the car
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="ChaseCamera")
        camera.CameraSensor.Width, camera.CameraSensor.Height, camera.CameraSensor.FOV = WIDTH, HEIGHT, 75.0
        chase(car, camera)
    with instance.end_frame():
        pass

    views: list[NDArray[np.uint8]] = []
    for frame in range(args.frames):
        with instance.begin_frame():
            for action, value in controls(frame).items():
                game.inject_input_for_actor(actor=player, input_action_name=action, value=spear.FVector(X=value))
            chase(car, camera)
        with instance.end_frame():
            if frame % args.every == 0 or frame == args.frames - 1:
                pixels = camera.CameraSensor.read_pixels()
                if "final_color" not in pixels:
                    raise spear.InvalidStateError("control_car: the chase camera rendered no final_color")
                image = pixels["final_color"][:, :, :3].copy()
                Image.fromarray(image).save(out / f"frame_{frame:04d}.png")
                views.append(image)
                location = car.GetActorLocation()
                print(f"frame {frame + 1}/{args.frames}: car at ({location.X:.1f}, {location.Y:.1f}), "
                      f"yaw {car.GetActorRotation().Yaw:.0f} deg, {car.GetForwardSpeed():.1f} m/s", flush=True)

    with instance.begin_frame():
        moved = crate.GetActorLocation()
        print(f"pillar at ({pillar.GetActorLocation().X:.1f}, {pillar.GetActorLocation().Y:.1f}); "
              f"crate pushed from (15.5, 9.5) to ({moved.X:.1f}, {moved.Y:.1f})")
    with instance.end_frame():
        pass
    instance.close()

    strip = np.concatenate([views[i * (len(views) - 1) // 3] for i in range(4)], axis=1)
    Image.fromarray(strip).save(out.with_suffix(".png"))
    print(f"wrote {len(views)} frames to {out}/ and a strip of four to {out.with_suffix('.png')}")


if __name__ == "__main__":
    main()
