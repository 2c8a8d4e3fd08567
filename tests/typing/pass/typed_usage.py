"""Positive typing case: what mypy --strict must infer for ordinary use of the typed API."""

from __future__ import annotations

from typing import assert_type

import numpy as np

import spear
from spear._engine import rpc
from spear._rpc_proxy import RpcClient
from spear.futures import Future


def world_services(instance: spear.Instance) -> None:
    game = instance.get_game()
    assert_type(game, spear.UWorld)
    with instance.begin_frame():
        mesh = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=1.0))
        assert_type(mesh, spear.AStaticMeshActor)
        by_name = game.spawn_actor(uclass="AStaticMeshActor")
        assert_type(by_name, spear.AActor)
        assert_type(game.find_actors_by_class(uclass=spear.AStaticMeshActor), list[spear.AStaticMeshActor])
        assert_type(game.find_actor_by_class(uclass=spear.AStaticMeshActor), spear.AStaticMeshActor | None)
        assert_type(game.find_actors_by_class_as_dict(uclass=spear.AActor), dict[str, spear.AActor])
        assert_type(game.get_components_by_class(actor=mesh, uclass=spear.UStaticMeshComponent),
                    list[spear.UStaticMeshComponent])
        assert_type(game.find_actor_by_name(name="x"), spear.AActor | None)
        assert_type(mesh.StaticMeshComponent, spear.UStaticMeshComponent)
        assert_type(mesh.RootComponent, spear.USceneComponent | None)
        assert_type(mesh.GetActorLocation(), spear.FVector)
        assert_type(mesh.GetActorLocation().Z, float)
        assert_type(mesh.StaticMeshComponent.Mobility, spear.EComponentMobility)
        assert_type(mesh.Tags, list[str])
        bounds = mesh.GetActorBounds(bOnlyCollidingComponents=True)
        assert_type(bounds, spear.AActor.GetActorBoundsResult)
        assert_type(bounds.BoxExtent, spear.FVector)
        assert_type(mesh.SetActorLocation(NewLocation=spear.FVector()), bool)
        mesh.StaticMeshComponent.RelativeLocation = spear.FVector(Z=2.0)
        mesh.StaticMeshComponent.Mobility = spear.EComponentMobility.Static
        cdo = game.get_default_object(uclass=spear.AStaticMeshActor)
        assert_type(cdo, spear.AStaticMeshActor)


def either_transport(client: RpcClient, local: spear.AActor) -> None:
    # The RPC proxy and the in-process object satisfy one typed interface: either can stand for the other.
    remote: spear.AActor = rpc.AActor(client, (1, 0))
    for actor in (remote, local):
        assert_type(actor.GetActorLocation(), spear.FVector)
    world: spear.UWorld = rpc.UWorld(client, (1, 0))
    assert_type(world.spawn_actor(uclass=spear.AStaticMeshActor), spear.AStaticMeshActor)
    # A proxy held as its own class is as precisely typed as the in-process class.
    proxy = rpc.UWorld(client, (1, 0))
    assert_type(proxy.find_actors_by_class(uclass=spear.AStaticMeshActor), list[spear.AStaticMeshActor])
    assert_type(proxy.spawn_actor(uclass="AStaticMeshActor"), spear.AActor)


def asynchronous(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
        location = actor.call_async.GetActorLocation()
        assert_type(location, Future[spear.FVector])
        spawned = game.call_async.spawn_actor(uclass=spear.AStaticMeshActor)
        assert_type(spawned, Future[spear.AStaticMeshActor])
        assert_type(actor.send_async.SetActorLocation(NewLocation=spear.FVector()), None)
    with instance.end_frame():
        assert_type(location.get(), spear.FVector)
        assert_type(actor.call_async.GetActorBounds(bOnlyCollidingComponents=True).get().Origin, spear.FVector)


def blueprints(instance: spear.Instance) -> None:
    game = instance.get_game()
    # A blueprint without functions is typed as its parent's class; one with functions has a stub class.
    assert_type(spear.BP_Axes, type[spear.AActor])
    with instance.begin_frame():
        crate: spear.AStaticMeshActor = game.spawn_actor(uclass=spear.BP_Crate)
        assert_type(game.spawn_actor(uclass=spear.BP_Crate), spear.BP_Crate)
        assert_type(game.find_actors_by_class(uclass=spear.BP_Axes), list[spear.AActor])
        assert crate.ActorHasTag(Tag="crate")


def lists_of_derived_actors(instance: spear.Instance) -> None:
    """A list of a derived class is accepted where a list of actors is asked for (the parameter is a
    Sequence, covariant; a list parameter would refuse list[AStaticMeshActor]), and so is a tuple."""
    game = instance.get_game()
    with instance.begin_frame():
        cubes: list[spear.AStaticMeshActor] = [game.spawn_actor(uclass=spear.AStaticMeshActor) for _ in range(2)]
        game.set_actor_locations(actors=cubes, locations=np.zeros((2, 3)))
        game.set_actor_locations(actors=tuple(cubes), locations=np.zeros((2, 3)))
        cameras: list[spear.UCameraSensorComponent] = [
            game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor for _ in range(2)]
    with instance.end_frame():
        stacked = spear.UCameraSensorComponent.read_pixels_stacked(Cameras=cameras)
        assert_type(stacked, spear.FCameraPixels)


def blueprint_functions(instance: spear.Instance) -> None:
    """A blueprint's functions are methods of its stub class, typed from its asset."""
    game = instance.get_game()
    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.BP_Crate)
        assert_type(crate, spear.BP_Crate)
        assert_type(crate.Launch(Speed=3.0), spear.FVector)
        assert_type(crate.Launch(), spear.FVector)
        crate.Nudge(Velocity=spear.FVector(X=1.0))
        assert_type(crate.StaticMeshComponent, spear.UStaticMeshComponent)  # the parent's members stay
        assert_type(crate.call_async.Launch(Speed=1.0), Future[spear.FVector])  # and asynchronously
        assert_type(crate.call_async.GetActorLocation(), Future[spear.FVector])
        crate.send_async.Nudge(Velocity=spear.FVector(Z=1.0))
    with instance.end_frame():
        pass
