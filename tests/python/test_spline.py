"""USplineComponent on both transports: points in local or world space, lengths and locations by distance
on a straight road, rotations along it, many evaluations as one (N, 3) array, closed loops, saved with
scenes, and clear errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import spear
from spear.errors import InvalidArgumentError

LOCAL = spear.ESplineCoordinateSpace.Local
WORLD = spear.ESplineCoordinateSpace.World


def test_a_road_along_a_turned_actor(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        road = game.spawn_actor(uclass=spear.ASplineActor, name="Road", location=spear.FVector(10.0, 0.0, 0.5),
                                rotation=spear.FRotator(Yaw=90.0))
        spline = road.SplineComponent
        for x in (0.0, 5.0, 10.0, 15.0):  # a straight line along the actor's X: the world's +Y
            spline.AddSplinePoint(Position=spear.FVector(X=x), CoordinateSpace=LOCAL)
        assert spline.GetNumberOfSplinePoints() == 4 and spline.GetSplineLength() == pytest.approx(15.0)
        at = spline.GetLocationAtDistanceAlongSpline(Distance=7.5, CoordinateSpace=WORLD)
        assert (at.X, at.Y, at.Z) == pytest.approx((10.0, 7.5, 0.5), abs=1e-9)
        assert spline.GetLocationAtDistanceAlongSpline(Distance=7.5, CoordinateSpace=LOCAL).X == pytest.approx(7.5)
        assert spline.GetRotationAtDistanceAlongSpline(Distance=3.0, CoordinateSpace=WORLD).Yaw == pytest.approx(90.0)
        direction = spline.GetDirectionAtDistanceAlongSpline(Distance=3.0, CoordinateSpace=LOCAL)
        assert (direction.X, direction.Y, direction.Z) == pytest.approx((1.0, 0.0, 0.0))
        assert spline.GetDistanceAlongSplineAtSplinePoint(PointIndex=2) == pytest.approx(10.0)
        # A point given in world space lands where it was asked for.
        spline.AddSplinePoint(Position=spear.FVector(10.0, 20.0, 0.5), CoordinateSpace=WORLD)
        assert spline.SplinePoints[-1].X == pytest.approx(20.0) and spline.GetSplineLength() == pytest.approx(20.0)
        distances = np.linspace(0.0, 20.0, 9)
        points = spline.GetLocationsAtDistances(Distances=distances, CoordinateSpace=WORLD)
        assert points.dtype == np.float64 and points.shape == (9, 3)
        assert np.allclose(points, np.stack([np.full(9, 10.0), distances, np.full(9, 0.5)], axis=1), atol=1e-9)
    with instance.end_frame():
        pass


def test_a_closed_loop_and_own_tangents(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        ring = game.spawn_actor(uclass=spear.ASplineActor, name="Ring").SplineComponent
        ring.SetSplinePoints(Points=[spear.FVector(3 * math.cos(a), 3 * math.sin(a), 0.0)
                                     for a in np.linspace(0.0, 2 * math.pi, 16, endpoint=False)],
                             CoordinateSpace=LOCAL)
        open_length = ring.GetSplineLength()
        ring.SetClosedLoop(bInClosedLoop=True)
        assert ring.IsClosedLoop() and ring.GetSplineLength() == pytest.approx(2 * math.pi * 3, rel=2e-3)
        assert ring.GetSplineLength() > open_length
        end = ring.GetLocationAtSplineInputKey(InKey=16.0, CoordinateSpace=LOCAL)
        assert (end.X, end.Y) == pytest.approx((3.0, 0.0), abs=1e-9)  # the loop closes on its first point
        ring.SetTangentAtSplinePoint(PointIndex=0, InTangent=spear.FVector(Z=4.0), CoordinateSpace=LOCAL)
        assert ring.GetTangentAtSplinePoint(PointIndex=0, CoordinateSpace=LOCAL) == spear.FVector(Z=4.0)
        lifted = ring.GetLocationAtSplineInputKey(InKey=0.5, CoordinateSpace=LOCAL)
        assert lifted.Z == pytest.approx((0.125 - 0.5 + 0.5) * 4.0)  # h10(0.5) * 4: the tangent's own lift
        with pytest.raises(InvalidArgumentError, match=r"PointIndex 16 is out of range \[0, 16\)"):
            ring.GetLocationAtSplinePoint(PointIndex=16, CoordinateSpace=LOCAL)
        # Found by the RPC fuzzer: a NaN distance reached the curve's segment index.
        with pytest.raises(InvalidArgumentError,
                           match=r"GetLocationsAtDistances\(\): Distances\[1\] = nan is not finite"):
            ring.GetLocationsAtDistances(Distances=np.array([0.0, np.nan]), CoordinateSpace=LOCAL)
        with pytest.raises(InvalidArgumentError,
                           match=r"GetLocationAtDistanceAlongSpline\(\): Distance inf is not finite"):
            ring.GetLocationAtDistanceAlongSpline(Distance=math.inf, CoordinateSpace=LOCAL)
        with pytest.raises(InvalidArgumentError, match=r"GetRotationAtDistanceAlongSpline\(\): Distance nan"):
            ring.GetRotationAtDistanceAlongSpline(Distance=math.nan, CoordinateSpace=LOCAL)
        with pytest.raises(InvalidArgumentError, match="Distances must be a 1-D array"):
            ring.GetLocationsAtDistances(Distances=np.zeros((2, 2)), CoordinateSpace=LOCAL)
        game.save_scene(path=str(tmp_path / "ring.json"))
        game.load_scene(path=str(tmp_path / "ring.json"))
        ring_actor = game.find_actor_by_name(name="Ring")
        assert isinstance(ring_actor, spear.ASplineActor)
        loaded = ring_actor.SplineComponent
        assert loaded.GetNumberOfSplinePoints() == 16 and loaded.IsClosedLoop()  # points and loop are saved
        assert loaded.GetSplineLength() == pytest.approx(2 * math.pi * 3, rel=2e-3)
    with instance.end_frame():
        pass


def test_a_spline_draws_as_a_debug_line_when_asked(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor", location=spear.FVector(Z=-0.5))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.SetActorScale3D(NewScale3D=spear.FVector(20.0, 20.0, 1.0))
        path = game.spawn_actor(uclass=spear.ASplineActor, name="Path")
        spline = path.SplineComponent
        spline.SetSplinePoints(Points=[spear.FVector(-3.0, -2.0, 0.05), spear.FVector(0.0, 1.0, 0.05), spear.FVector(3.0, -1.0, 0.05)],
                               CoordinateSpace=spear.ESplineCoordinateSpace.World)
        spline.bDrawDebug = True
        spline.SetDebugLineThickness(Thickness=0.2)
        spline.DebugLineColor = spear.FLinearColor(0.0, 1.0, 0.0, 1.0)
        with pytest.raises(spear.InvalidArgumentError, match=r"USplineComponent.DebugLineThickness must be > 0, got -1"):
            spline.SetDebugLineThickness(Thickness=-1.0)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Above", location=spear.FVector(Z=8.0),
                                  rotation=spear.FRotator(Pitch=-90.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 96, 96, 70.0
        camera.SetModalityNames(Names=["final_color", "object_ids"])
    with instance.end_frame():
        pixels = camera.read_pixels()
    assert "final_color" in pixels and "object_ids" in pixels
    colour, ids = pixels["final_color"], pixels["object_ids"]
    green = (colour[:, :, 1] > 150) & (colour[:, :, 0] < 80) & (colour[:, :, 2] < 80)  # it glows green
    assert green.sum() > 50
    line_ids = set(np.unique(ids[green]).tolist())
    assert len(line_ids) == 1
    with instance.begin_frame():
        info = camera.GetObjectIdInfo(ObjectId=line_ids.pop())
        assert info.ReturnValue and info.Actor == path and info.Component is None and info.MaterialName == "DebugLine"
        spline.bDrawDebug = False
    with instance.end_frame():
        hidden = camera.read_pixels()
    assert "final_color" in hidden
    assert ((hidden["final_color"][:, :, 1] > 150) & (hidden["final_color"][:, :, 0] < 80)).sum() == 0
