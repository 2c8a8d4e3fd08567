"""Blueprints: classes defined by asset files. Load one with load_class (SPEAR's call), spawn it like a
native class, find its instances by class, and call the functions its asset declares.

    PYTHONPATH=python /usr/bin/python3 examples/blueprints.py [--server launch]
"""

from __future__ import annotations

import argparse

import spear

# By asset name, so the example runs from anywhere (a checkout or the installed package).
BLUEPRINTS = "/Game/blueprints"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    instance = spear.Instance(server=parser.parse_args().server)
    game = instance.get_game()

    with instance.begin_frame():
        # load_class(uclass=C, name=path) is typed as type[C]: the blueprint's class, a subclass of C.
        axes_class = game.load_class(uclass=spear.AActor, name=f"{BLUEPRINTS}/BP_Axes")
        crate_class = game.load_class(uclass=spear.AStaticMeshActor, name=f"{BLUEPRINTS}/BP_Crate")
        print(f"loaded {axes_class.__name__} (a {axes_class.__mro__[1].__name__}) and {crate_class.__name__}")

        axes = game.spawn_actor(uclass=axes_class, name="Axes")
        print(f"{axes.GetName()} is a {axes.GetClassName()} with components "
              f"{[c.GetName() for c in axes.K2_GetComponents()]}")

        # spawn_actor(uclass=crate_class) is typed AStaticMeshActor: the blueprint's native members are there.
        crate = game.spawn_actor(uclass=crate_class, location=spear.FVector(X=1.0, Z=2.0), name="Crate")
        mesh = crate.StaticMeshComponent
        print(f"{crate.GetName()}: {mesh.MassInKg} kg of {mesh.Materials[0]}, simulating: {mesh.bSimulatePhysics}")
        # After load_class, the blueprint's name works as uclass= too.
        game.spawn_actor(uclass="BP_Crate", location=spear.FVector(X=-1.0, Z=2.0), name="Crate2")
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=-0.05), name="Floor")
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.StaticMeshComponent.RelativeScale3D = spear.FVector(X=10.0, Y=10.0, Z=0.1)
        floor.StaticMeshComponent.Mobility = spear.EComponentMobility.Static

    with instance.end_frame():
        pass
    instance.step(num_frames=120)  # the crates fall onto the floor

    with instance.begin_frame():
        crates = game.find_actors_by_class(uclass=crate_class)
        meshes = game.find_actors_by_class(uclass=spear.AStaticMeshActor)
        print(f"crates: {[c.GetName() for c in crates]}; mesh actors: {[m.GetName() for m in meshes]}")
        for crate in crates:
            print(f"{crate.GetName()} came to rest at Z = {crate.GetActorLocation().Z:.3f}")
        # spear.BP_Crate, generated from the asset, types the functions it declares (Launch, Nudge): they are
        # reflected calls composed in the asset, run by the engine, called like any method.
        thrown = game.spawn_actor(uclass=spear.BP_Crate, location=spear.FVector(Z=0.5), name="Thrown")
    with instance.end_frame():
        pass
    with instance.begin_frame():
        start = thrown.Launch(Speed=6.0)  # typed FVector: where it was thrown from
        thrown.Nudge(Velocity=spear.FVector(X=1.0))
        print(f"{thrown.GetName()} launched from Z = {start.Z:.2f} with a nudge along X")
    with instance.end_frame():
        pass
    instance.step(num_frames=30)
    with instance.begin_frame():
        where = thrown.GetActorLocation()
        print(f"half a second later it is at X = {where.X:.2f}, Z = {where.Z:.2f}")
        # A character class: BP_Walker is an ASkeletalMeshActor showing the built-in humanoid, walking from the
        # start of play; its function Run (composed in the asset) switches it to the run clip.
        walker = game.spawn_actor(uclass=spear.BP_Walker, location=spear.FVector(X=2.0), name="Walker")
        body = walker.SkeletalMeshComponent
        print(f"{walker.GetName()} is a {walker.GetClassName()}: {body.GetNumBones()} bones, playing "
              f"'{body.AnimToPlay}'")
    with instance.end_frame():
        pass
    with instance.begin_frame():
        length = walker.Run(PlayRate=1.5)  # typed float: the run clip's length
        print(f"{walker.GetName()} runs now ('{body.AnimToPlay}', {length:.2f} s a cycle, at {body.PlayRate}x)")
    with instance.end_frame():
        pass

    instance.close()


if __name__ == "__main__":
    main()
