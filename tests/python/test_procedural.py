"""Procedural generation on both transports: UPCGComponent in an APCGVolume scatters actors at a spacing
onto the ground, follows a spline, and lays out city blocks that keep off road splines; the same seed gives
the same actors and another seed others; Generate is cached until something it reads changes; generated
actors are ordinary (physical, saved with the scene, found again after a load); bad rules are refused."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import spear

Mode = spear.EPCGGenerationMode


def ground(game: spear.UWorld) -> None:
    floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(Z=-0.5))
    floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    floor.SetActorScale3D(NewScale3D=spear.FVector(60.0, 60.0, 1.0))


def volume(game: spear.UWorld, name: str = "Forest", extent: tuple[float, float, float] = (10.0, 8.0, 5.0)) -> spear.APCGVolume:
    v = game.spawn_actor(uclass=spear.APCGVolume, name=name, location=spear.FVector(Z=2.0))
    v.BoxComponent.SetBoxExtent(InBoxExtent=spear.FVector(*extent))
    return v


def locations(actors: list[spear.AActor]) -> list[tuple[float, float, float]]:
    return [(a.GetActorLocation().X, a.GetActorLocation().Y, a.GetActorLocation().Z) for a in actors]


def test_scatter_is_spaced_grounded_and_repeatable(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        ground(game)
        pcg = volume(game).PCGComponent
        pcg.Spacing, pcg.MaxCount, pcg.Seed = 2.0, 30, 7
        pcg.MinScale, pcg.MaxScale = 0.5, 1.0
        pcg.Materials = ["Red", "Green"]
        pcg.Generate()
        actors = pcg.GetGeneratedActors()
        assert len(actors) == 30 and pcg.IsGenerated()
        assert all(isinstance(a, spear.AStaticMeshActor) and a.ActorHasTag(Tag="PCG:Forest") for a in actors)
        assert actors[0].GetName() == "Forest_0"
        points = locations(actors)
        for i, p in enumerate(points):
            assert -10.0 <= p[0] <= 10.0 and -8.0 <= p[1] <= 8.0
            assert all(math.dist(p[:2], q[:2]) >= 2.0 for q in points[:i])
        # Standing on the ground: each cube's bottom at z = 0.
        for a in actors:
            origin, extent = a.GetActorBounds(bOnlyCollidingComponents=False)
            assert origin.Z - extent.Z == pytest.approx(0.0, abs=1e-9)
        assert {a.StaticMeshComponent.Materials[0] for a in actors} == {"Red", "Green"}

        pcg.Generate()  # nothing changed: the same actors, not new ones
        assert [a.GetName() for a in pcg.GetGeneratedActors()] == [a.GetName() for a in actors]
        assert all(game.find_actor_by_name(name=a.GetName()) is not None for a in actors)
        pcg.Seed = 8
        pcg.Generate()
        assert locations(pcg.GetGeneratedActors()) != points
        pcg.Seed = 7
        pcg.Generate()
        assert locations(pcg.GetGeneratedActors()) == points  # the same seed, the same forest
        pcg.Cleanup()
        assert pcg.GetGeneratedActors() == [] and not pcg.IsGenerated()
    with instance.end_frame():
        pass


def test_scatter_keeps_out_of_exclusions_and_off_empty_ground(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(X=-5.0, Z=-0.5))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.SetActorScale3D(NewScale3D=spear.FVector(10.0, 16.0, 1.0))  # only under the western half
        pond = game.spawn_actor(uclass=spear.ATriggerBox, name="Pond", location=spear.FVector(X=-5.0), tags=["NoTrees"])
        pond.CollisionComponent.SetBoxExtent(InBoxExtent=spear.FVector(2.0, 2.0, 1.0))
        pcg = volume(game).PCGComponent
        pcg.Spacing, pcg.MaxCount, pcg.ExclusionTag = 1.0, 200, "NoTrees"
        pcg.Generate()
        points = locations(pcg.GetGeneratedActors())
        assert len(points) > 20
        assert all(p[0] <= 0.0 for p in points)  # nothing where there is no ground to stand on
        assert not any(abs(p[0] + 5.0) < 2.0 and abs(p[1]) < 2.0 for p in points)
    with instance.end_frame():
        pass


def test_along_a_spline_and_city_blocks_off_the_roads(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        ground(game)
        spline = game.spawn_actor(uclass=spear.ASplineActor, name="Avenue", tags=["Road"])
        spline.SplineComponent.SetSplinePoints(
            Points=[spear.FVector(-10.0, 0.0, 0.0), spear.FVector(10.0, 0.0, 0.0)], CoordinateSpace=spear.ESplineCoordinateSpace.World)
        trees = volume(game, "Trees", extent=(12.0, 8.0, 5.0)).PCGComponent
        spline.Tags = ["Road", "Trees"]
        trees.GenerationMode, trees.SplineTag, trees.Spacing = Mode.AlongSpline, "Trees", 4.0
        trees.SplineOffset, trees.bBothSides = 3.0, True
        trees.Generate()
        rows = locations(trees.GetGeneratedActors())
        assert len(rows) == 2 * 6  # 0, 4, ..., 20 m on both sides
        assert sorted({round(p[1], 6) for p in rows}) == [-3.0, 3.0]

        city = volume(game, "City", extent=(28.0, 28.0, 20.0)).PCGComponent
        city.GenerationMode = Mode.CityBlocks
        city.BlockSize, city.StreetWidth, city.LotsPerSide = 12.0, 4.0, 2
        city.MinHeight, city.MaxHeight, city.RoadWidth = 4.0, 16.0, 6.0
        city.Generate()
        buildings = city.GetGeneratedActors()
        heights = []
        for b in buildings:
            origin, extent = b.GetActorBounds(bOnlyCollidingComponents=False)
            heights.append(2 * extent.Z)
            assert origin.Z - extent.Z == pytest.approx(0.0, abs=1e-9)  # on the ground
            # Off the avenue (y = 0 for x in [-10, 10]) by half the road width.
            assert abs(origin.Y) - extent.Y >= 3.0 - 1e-9 or abs(origin.X) - extent.X >= 10.0 + 3.0 - 1e-9
        assert all(4.0 <= h <= 16.0 for h in heights) and len(set(heights)) > 5
    with instance.end_frame():
        pass


def test_generated_actors_are_ordinary_and_saved_with_the_scene(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    path = tmp_path / "forest.json"
    with instance.begin_frame():
        ground(game)
        pcg = volume(game).PCGComponent
        pcg.Spacing, pcg.MaxCount = 3.0, 12
        pcg.Generate()
        before = locations(pcg.GetGeneratedActors())
        # Physical: a trace straight down onto the first one hits it, not the ground.
        x, y, _ = before[0]
        hit = game.line_trace_single(start=spear.FVector(x, y, 10.0), end=spear.FVector(x, y, -1.0))
        assert hit.ReturnValue and hit.actor is not None and hit.actor.GetName() == "Forest_0"
        assert len(game.find_actors_by_tag(tag="PCG:Forest")) == 12
        game.save_scene(path=str(path))
        game.load_scene(path=str(path))
        loaded = game.find_actor_by_name(name="Forest")
        assert isinstance(loaded, spear.APCGVolume)
        again = loaded.PCGComponent
        assert locations(again.GetGeneratedActors()) == before  # found by their tag after the load
        assert again.Spacing == 3.0 and again.MaxCount == 12
        again.FlushCache()
        again.Generate()  # afresh: the same seed gives the same forest
        assert locations(again.GetGeneratedActors()) == before
    with instance.end_frame():
        pass


def test_bad_rules_are_refused_and_leave_nothing_behind(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        ground(game)
        pcg = volume(game).PCGComponent
        pcg.Spacing = -1.0
        with pytest.raises(spear.InvalidArgumentError, match=r"UPCGComponent.Generate\(\): Spacing = -1 must be a finite number > 0"):
            pcg.Generate()
        pcg.Spacing = 2.0
        pcg.GenerationMode = Mode.AlongSpline
        with pytest.raises(spear.InvalidArgumentError, match=r"no ASplineActor has SplineTag 'PCGSpline'"):
            pcg.Generate()
        pcg.GenerationMode = Mode.Scatter
        count = pcg.MaxCount
        pcg.Spacing, pcg.MaxCount = 1e-4, 10  # 2.8e5 x 2.3e5 cells, but only the 10 filled are stored
        pcg.Generate()
        assert len(pcg.GetGeneratedActors()) == 10
        pcg.Spacing = 1e-12
        with pytest.raises(spear.InvalidArgumentError, match=r"Spacing = 1e-12 over a 20 x 16 m box makes more than 2\^31 cells along a side"):
            pcg.Generate()  # refused: past the cells' 64-bit keys
        pcg.Spacing, pcg.MaxCount = 2.0, 2_000_000
        with pytest.raises(spear.InvalidArgumentError, match=r"MaxCount = 2000000 asks for more than 1e\+06 placements"):
            pcg.Generate()
        pcg.MaxCount = count
        pcg.GenerationMode = Mode.CityBlocks
        pcg.BlockSize, pcg.StreetWidth = 1e-9, 0.0
        with pytest.raises(spear.InvalidArgumentError, match=r"lots, more than 1e\+06"):
            pcg.Generate()
        pcg.BlockSize, pcg.StreetWidth = 24.0, 8.0
        pcg.GenerationMode = Mode.Scatter
        pcg.StaticMesh = "/Engine/BasicShapes/Teapot"
        with pytest.raises(spear.NotFoundError, match=r"StaticMesh '/Engine/BasicShapes/Teapot' could not be loaded"):
            pcg.Generate()
        assert pcg.GetGeneratedActors() == []
        pcg.StaticMesh = "/Engine/BasicShapes/Sphere"
        pcg.Generate()
        assert pcg.IsGenerated() and pcg.GetLastGenerationSeconds() > 0.0
    with instance.end_frame():
        pass
