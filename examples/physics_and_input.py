"""Physics and input: load the default apartment scene, drop a crate onto the table, trace a ray down to
find what it landed on, and drive a vehicle by injecting input actions into it alone.

    PYTHONPATH=python /usr/bin/python3 examples/physics_and_input.py [--server launch]
"""

from __future__ import annotations

import argparse

import spear

APARTMENT = "/Game/scenes/apartment"  # assets/scenes/apartment.json, found wherever spear is installed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    instance = spear.Instance(scene=APARTMENT, server=parser.parse_args().server)
    game = instance.get_game()

    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate", location=spear.FVector(1.5, 1.2, 2.0))
        mesh = crate.StaticMeshComponent
        mesh.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        mesh.SetRelativeScale3D(NewScale3D=spear.FVector(0.3, 0.3, 0.3))
        mesh.SetMassOverrideInKg(MassInKg=2.0)
        mesh.SetSimulatePhysics(bSimulate=True)
        car = game.spawn_actor(uclass=spear.AKinematicVehicle, name="Car", location=spear.FVector(-1.0, 0.0, 0.2))
        other = game.spawn_actor(uclass=spear.AKinematicVehicle, name="Other", location=spear.FVector(-1.0, -1.0, 0.2))
    with instance.end_frame():
        pass

    for _ in range(120):  # 2 s: the crate falls onto the table, the car drives a left-hand curve
        with instance.begin_frame():
            game.inject_input_for_actor(actor=car, input_action_name="Throttle", value=spear.FVector(X=0.5))
            game.inject_input_for_actor(actor=car, input_action_name="Steer", value=spear.FVector(X=0.3))
        with instance.end_frame():
            pass

    with instance.begin_frame():
        location = crate.GetActorLocation()
        print(f"crate rests at z = {location.Z:.3f} m (table top at 0.75 m, half size 0.15 m)")
        result = game.line_trace_single(start=location, end=spear.FVector(location.X, location.Y, -1.0))
        below = result.actor.GetName() if result.actor is not None else "nothing"
        print(f"below the crate's centre: {below} at {result.hit.Distance:.3f} m")
        print(f"car at {car.GetActorLocation()}, yaw {car.GetActorRotation().Yaw:.1f} deg")
        print(f"the other vehicle did not move: {other.GetActorLocation()}")
    with instance.end_frame():
        pass
    instance.close()


if __name__ == "__main__":
    main()
