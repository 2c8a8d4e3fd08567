"""Overlaps and trigger volumes on both transports: overlap sets equal the analytic answer for boxes and
spheres, begin/end events fire on the frames a falling box enters and leaves a trigger, and triggers stop
neither bodies nor traces."""

from __future__ import annotations

import math

import pytest

import spear
from spear.errors import InvalidArgumentError

GRAVITY = 9.81


def shape(game: spear.UWorld, mesh: str, x: float, y: float, z: float, *, overlaps: bool = True,
          name: str | None = None) -> spear.AStaticMeshActor:
    """A unit cube or a unit-diameter sphere at (x, y, z) that generates overlap events."""
    where = spear.FVector(x, y, z)
    actor = (game.spawn_actor(uclass=spear.AStaticMeshActor, location=where) if name is None
             else game.spawn_actor(uclass=spear.AStaticMeshActor, location=where, name=name))
    actor.StaticMeshComponent.SetStaticMesh(NewMesh=f"/Engine/BasicShapes/{mesh}")
    actor.StaticMeshComponent.bGenerateOverlapEvents = overlaps
    return actor


def test_overlap_sets_match_the_geometry(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        box = game.spawn_actor(uclass=spear.ATriggerBox, name="TriggerBox")
        box.CollisionComponent.BoxExtent = spear.FVector(1.0, 1.0, 1.0)
        sphere = game.spawn_actor(uclass=spear.ATriggerSphere, name="TriggerSphere",
                                  location=spear.FVector(X=10.0))
        sphere.CollisionComponent.SphereRadius = 1.0
        # Around the 2 m trigger box: unit shapes reach it when their centre is within 1.5 of a face, and a
        # sphere at a corner when its centre is within 0.5 of the corner (x = y = 1 + 0.5 / sqrt(2) = 1.354).
        inside = [shape(game, "Cube", 1.4, 0.0, 0.0), shape(game, "Sphere", 0.0, -1.45, 0.0),
                  shape(game, "Sphere", 1.3, 1.3, 0.0), shape(game, "Cube", 0.0, 0.0, 0.0)]
        outside = [shape(game, "Cube", 1.6, 0.0, 0.0), shape(game, "Sphere", 1.4, 1.4, 0.0),
                   shape(game, "Sphere", 0.0, 0.0, 1.55)]
        quiet = shape(game, "Cube", 0.0, 0.5, 0.0, overlaps=False)  # overlaps only when both generate events
        # Around the trigger sphere (radius 1): a unit sphere within 1.5, a unit cube's face within 1.5, and a
        # cube at (a, a) reaches it with its vertical edge while sqrt(2) * (a - 0.5) < 1, i.e. a < 1.207
        # (a box's edges are rounded by Bullet's margin, about 2 cm here: the cases keep clear of it).
        near = [shape(game, "Sphere", 11.45, 0.0, 0.0), shape(game, "Cube", 10.0, 1.45, 0.0),
                shape(game, "Cube", 10.0 + 1.15, 1.15, 0.0)]
        far = [shape(game, "Sphere", 10.0, 0.0, -1.55), shape(game, "Cube", 10.0 + 1.3, 1.3, 0.0)]
        assert box.GetOverlappingActors(ClassFilter=spear.AStaticMeshActor) == inside
        assert sphere.CollisionComponent.GetOverlappingActors(ClassFilter=spear.AActor) == near
        for actor in outside + far + [quiet]:
            assert not box.IsOverlappingActor(Other=actor) and not sphere.IsOverlappingActor(Other=actor)
        assert inside[0].IsOverlappingActor(Other=box)  # symmetric
        assert box.CollisionComponent.IsOverlappingComponent(OtherComp=inside[3].StaticMeshComponent)
        assert box.GetOverlappingActors(ClassFilter=spear.ATriggerBox) == []  # filtered by class
        quiet.StaticMeshComponent.bGenerateOverlapEvents = True
        assert box.IsOverlappingActor(Other=quiet)
        outside[0].SetActorLocation(NewLocation=spear.FVector(1.45, 0.0, 0.0))  # seen at once, mid-frame
        assert box.IsOverlappingActor(Other=outside[0])
    with instance.end_frame():
        pass


def test_begin_and_end_events_fire_as_a_box_falls_through(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        floor = shape(game, "Plane", 0.0, 0.0, 0.0, overlaps=False, name="Floor")
        floor.SetActorScale3D(NewScale3D=spear.FVector(20.0, 20.0, 1.0))
        trigger = game.spawn_actor(uclass=spear.ATriggerBox, location=spear.FVector(Z=3.0))
        trigger.CollisionComponent.BoxExtent = spear.FVector(2.0, 2.0, 0.5)  # z in [2.5, 3.5]
        box = shape(game, "Cube", 0.0, 0.0, 6.0, name="Falling")
        box.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
    with instance.end_frame():
        pass
    # Frame k's tick is the k-th since the box was spawned (the spawn frame's tick is the first); a query
    # inside the next frame sees the events of that tick.
    began: list[int] = []
    ended: list[int] = []
    for tick in range(1, 121):
        with instance.begin_frame():
            component = trigger.CollisionComponent
            if component.GetBeginOverlaps():
                assert component.GetBeginOverlaps() == [box.StaticMeshComponent]
                began.append(tick)
            if component.GetEndOverlaps():
                assert component.GetEndOverlaps() == [box.StaticMeshComponent]
                ended.append(tick)
        with instance.end_frame():
            pass
    # The box's bottom (z - 0.5) reaches the trigger's top (3.5) after falling 2 m, and its top (z + 0.5)
    # leaves the trigger's bottom (2.5) after falling 4 m: t = sqrt(2 d / g), in ticks of four 1/240 s
    # substeps (the integrator may cross a substep early, hence the tolerance of one tick).
    def tick_of(distance: float) -> int:
        return math.ceil(math.sqrt(2 * distance / GRAVITY) * 240 / 4)

    assert len(began) == 1 and began[0] == pytest.approx(tick_of(2.0), abs=1)
    assert len(ended) == 1 and ended[0] == pytest.approx(tick_of(4.0), abs=1)
    with instance.begin_frame():
        resting = box.GetActorLocation()
        assert resting.Z == pytest.approx(0.5, abs=1e-3)  # fell through onto the floor
        hit = game.line_trace_single(start=spear.FVector(resting.X, resting.Y, 10.0),
                                     end=spear.FVector(resting.X, resting.Y, -1.0))
        assert hit.actor == box  # the trace went through the trigger
    with instance.end_frame():
        pass


def test_bad_shapes_are_refused_when_set(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        box = game.spawn_actor(uclass=spear.ATriggerBox)
        with pytest.raises(InvalidArgumentError, match=r"^UBoxComponent\.BoxExtent must be finite and > 0 along "
                                                       r"every axis, got \(1, 0, 1\)$"):
            box.CollisionComponent.BoxExtent = spear.FVector(1.0, 0.0, 1.0)
        sphere = game.spawn_actor(uclass=spear.ATriggerSphere)
        with pytest.raises(InvalidArgumentError, match=r"^USphereComponent\.SphereRadius must be > 0, got -1$"):
            sphere.CollisionComponent.SphereRadius = -1.0
        with pytest.raises(InvalidArgumentError, match="argument .ClassFilter. must not be None"):
            box.GetOverlappingActors(ClassFilter=None)  # type: ignore[call-overload]
    with instance.end_frame():
        pass
