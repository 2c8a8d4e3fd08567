"""Getting started: create an engine, spawn actors by class, read and write reflected properties,
call reflected functions and find actors by class (subclasses included).

    PYTHONPATH=python /usr/bin/python3 examples/getting_started.py [--server launch]
"""

from __future__ import annotations

import argparse

import spear


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    instance = spear.Instance(server=parser.parse_args().server)
    game = instance.get_game()

    with instance.begin_frame():
        # spawn_actor(uclass=C) is typed to return a C.
        cube = game.spawn_actor(
            uclass=spear.AStaticMeshActor, location=spear.FVector(X=1.0, Y=0.0, Z=0.5), name="Cube", tags=["props"]
        )
        cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        print(f"spawned {cube.GetName()} of class {cube.GetClassName()} at {cube.GetActorLocation()}")

        # A plain AActor, and another mesh actor spawned by class name (dynamic use).
        marker = game.spawn_actor(uclass=spear.AActor, name="Marker")
        sphere = game.spawn_actor(uclass="AStaticMeshActor", name="Sphere", location=spear.FVector(X=-1.0))
        print(f"spawned {marker.GetName()} and {sphere.GetName()}")

        # Reflected properties read and write like Python attributes, with their real types.
        root = cube.StaticMeshComponent
        root.RelativeScale3D = spear.FVector(X=2.0, Y=1.0, Z=1.0)
        root.Mobility = spear.EComponentMobility.Movable
        print(f"{root.GetName()}: scale {root.RelativeScale3D}, mobility {root.Mobility.name}")

        # Reflected functions take keyword arguments; out-parameters come back as a named tuple.
        cube.SetActorRotation(NewRotation=spear.FRotator(Yaw=90.0))
        bounds = cube.GetActorBounds(bOnlyCollidingComponents=False)
        print(f"bounds of {cube.GetName()}: origin {bounds.Origin}, extent {bounds.BoxExtent}")

    with instance.end_frame():
        # Class queries respect the hierarchy: AActor finds the mesh actors too.
        actors = game.find_actors_by_class(uclass=spear.AActor)
        meshes = game.find_actors_by_class(uclass=spear.AStaticMeshActor)
        print(f"{len(actors)} actors, {len(meshes)} of them static mesh actors: {[a.GetName() for a in meshes]}")
        tagged = game.find_actors_by_tag(tag="props")
        print(f"tagged 'props': {[a.GetName() for a in tagged]}")
        print(f"frame {game.get_frame_count()}, simulated time {game.get_time_seconds():.4f} s")

    with instance.begin_frame():
        game.destroy_actor(actor=marker)
    with instance.end_frame():
        print(f"after destroying Marker: {game.get_actor_count()} actors")
        try:
            marker.GetName()
        except spear.StaleObjectError as error:
            print(f"using the destroyed actor raises StaleObjectError: {error}")

    instance.close()


if __name__ == "__main__":
    main()
