"""Navigation on both transports: a navigation mesh built from the world's static geometry (a floor and a
wall with a gap), paths through the gap with the taut-string length, unreachable and off-mesh ends, tiles
rebuilt when geometry appears, uniform random points, agent profiles, an AI walking the path, and the nav
data's settings saved with the scene."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import spear

Result = spear.ENavigationQueryResult


def box(game: spear.UWorld, name: str, center: tuple[float, float, float], size: tuple[float, float, float]) -> spear.AStaticMeshActor:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*center))
    actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    actor.SetActorScale3D(NewScale3D=spear.FVector(*size))
    return actor


def wall_with_gap(game: spear.UWorld) -> None:
    """A 20 x 10 m floor (top at z = 0) split at x = 0 by a 2 m wall with a gap for y in [2, 3]."""
    box(game, "Floor", (0.0, 0.0, -0.5), (20.0, 10.0, 1.0))
    box(game, "WallSouth", (0.0, -1.5, 1.0), (0.2, 7.0, 2.0))
    box(game, "WallNorth", (0.0, 4.0, 1.0), (0.2, 2.0, 2.0))


def nav_data(game: spear.UWorld, radius: float = 0.3) -> spear.ARecastNavMesh:
    system = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game)
    nav = system.GetDefaultNavDataInstance()
    nav.AgentRadius = radius
    nav.TileSize = 6.4
    return nav


def taut_string_length(r: float) -> float:
    """From (-4, 0) to (4, 0) around the wall's end at y = 2, keeping r from it (see nav_mesh_test.cpp)."""
    corner, start = (-0.1, 2.0), (-4.0, 0.0)
    d = math.dist(corner, start)
    tangent = math.atan2(start[1] - corner[1], start[0] - corner[0]) + 2 * math.pi - math.acos(r / d)
    return 2.0 * (math.sqrt(d * d - r * r) + r * (tangent - math.pi / 2)) + 0.2


def test_paths_go_through_the_gap_with_the_shortest_length(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall_with_gap(game)
        nav = nav_data(game)
        found = nav.FindPath(Start=spear.FVector(-4.0, 0.0, 0.0), End=spear.FVector(4.0, 0.0, 0.0))
        assert found.ReturnValue == Result.Success
        points = found.PathPoints
        assert points.dtype == np.float64 and points.ndim == 2 and points.shape[1] == 3 and len(points) >= 3
        assert found.PathLength == pytest.approx(taut_string_length(0.3), abs=0.25)
        assert found.PathLength == pytest.approx(float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum()))
        # The corners that turn the wall's end are in the gap's side, never in the wall.
        assert any(abs(x) <= 0.5 and 2.0 < y < 3.0 for x, y, _ in points)
        assert not any(abs(x) < 0.1 and (y < 2.0 or y > 3.0) for x, y, _ in points)

        # UE's static forms on the default navigation data agree.
        same = spear.UNavigationSystemV1.FindPathToLocationSynchronously(
            WorldContextObject=game, PathStart=spear.FVector(-4.0, 0.0, 0.0), PathEnd=spear.FVector(4.0, 0.0, 0.0)
        )
        assert same.ReturnValue == Result.Success and np.array_equal(same.PathPoints, points)
        length = spear.UNavigationSystemV1.GetPathLength(
            WorldContextObject=game, PathStart=spear.FVector(-4.0, 0.0, 0.0), PathEnd=spear.FVector(4.0, 0.0, 0.0)
        )
        assert length.ReturnValue == Result.Success and length.PathLength == found.PathLength
        assert nav.GetGeodesicDistance(Start=spear.FVector(-4.0, 0.0, 0.0), End=spear.FVector(4.0, 0.0, 0.0)) == found.PathLength

        batch = nav.FindPaths(
            StartPoints=np.array([[-4.0, 0.0, 0.0], [-4.0, 0.0, 0.0]]), EndPoints=np.array([[4.0, 0.0, 0.0], [40.0, 0.0, 0.0]])
        )
        assert batch.PathStarts.tolist() == [0, len(points), len(points)]
        assert np.array_equal(batch.PathPoints, points)
        assert batch.Results.tolist() == [Result.Success, Result.Invalid]
        assert batch.Lengths[0] == found.PathLength
    with instance.end_frame():
        pass


def test_geometry_that_appears_rebuilds_only_its_tiles(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall_with_gap(game)
        nav = nav_data(game)
        start, end = spear.FVector(-4.0, 0.0, 0.0), spear.FVector(4.0, 0.0, 0.0)
        assert nav.FindPath(Start=start, End=end).ReturnValue == Result.Success
        all_tiles = nav.GetLastBuildTileCount()
        assert all_tiles == 4 * 2  # 20 x 10 m in 6.4 m tiles
        area = nav.GetNavigableArea()
        box(game, "Plug", (0.0, 2.5, 1.0), (0.2, 1.0, 2.0))  # closes the gap
        blocked = nav.FindPath(Start=start, End=end)
        assert 0 < nav.GetLastBuildTileCount() < all_tiles
        assert blocked.ReturnValue == Result.Fail  # partial: as close as it gets, on its own side
        assert -0.7 < blocked.PathPoints[-1][0] < -0.1
        assert math.isinf(nav.GetGeodesicDistance(Start=start, End=end))
        assert nav.GetNavigableArea() < area
        off = nav.FindPath(Start=start, End=spear.FVector(40.0, 0.0, 0.0))
        assert off.ReturnValue == Result.Invalid and off.PathPoints.shape == (0, 3)
        game.destroy_actor(actor=game.find_actor_by_name(name="Plug"))
        assert nav.FindPath(Start=start, End=end).ReturnValue == Result.Success
        assert nav.GetNavigableArea() == pytest.approx(area)
    with instance.end_frame():
        pass


def test_random_points_are_navigable_and_repeat_for_a_seed(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall_with_gap(game)
        nav = nav_data(game)
        nav.SetRandomSeed(Seed=5)
        points = nav.GetRandomPoints(NumPoints=500)
        assert points.shape == (500, 3)
        assert all(nav.IsNavigable(Point=spear.FVector(*p)) for p in points[:50])
        assert (points[:, 0] < 0).sum() == pytest.approx(250, abs=60)  # the two halves have equal area
        nav.SetRandomSeed(Seed=5)
        assert np.array_equal(nav.GetRandomPoints(NumPoints=500), points)

        origins = np.array([[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 9.0]])
        near = nav.GetRandomReachablePointsInRadius(Origins=origins, Radius=2.0)
        assert near[0][0] < 0 and near[1][0] > 0  # the wall: each stays on its origin's side
        assert np.hypot(*(near[0][:2] - origins[0][:2])) <= 2.0 and np.hypot(*(near[1][:2] - origins[1][:2])) <= 2.0
        assert np.isnan(near[2]).all()  # 9 m up: off the mesh

        drawn = spear.UNavigationSystemV1.K2_GetRandomReachablePointInRadius(
            WorldContextObject=game, Origin=spear.FVector(-1.0, 0.0, 0.0), Radius=2.0
        )
        assert drawn.ReturnValue and drawn.RandomLocation.X < 0
        projected = spear.UNavigationSystemV1.K2_ProjectPointToNavigation(
            WorldContextObject=game, Point=spear.FVector(-3.0, 1.0, 0.6)
        )
        assert projected.ReturnValue and projected.ProjectedLocation.Z == pytest.approx(0.0, abs=0.06)
        assert not nav.ProjectPointToNavigation(Point=spear.FVector(-3.0, 1.0, 9.0)).ReturnValue
        triangles = nav.GetNavMeshTriangles()
        assert triangles.ndim == 3 and triangles.shape[1:] == (3, 3)
    with instance.end_frame():
        pass


def test_agent_profiles_and_errors(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall_with_gap(game)
        system = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game)
        assert system.GetNavDataForAgentName(AgentName="Default") is None  # none yet
        small = nav_data(game)
        big = game.spawn_actor(uclass=spear.ARecastNavMesh, name="BigNav")
        big.AgentName = "Big"
        big.AgentRadius = 0.6  # does not fit through the 1 m gap
        assert system.GetNavDataForAgentName(AgentName="Big") == big
        assert system.GetNavDataForAgentName(AgentName="Default") == small
        assert big.GetNavigableArea() < small.GetNavigableArea()
        start, end = spear.FVector(-4.0, 0.0, 0.0), spear.FVector(4.0, 0.0, 0.0)
        assert big.FindPath(Start=start, End=end).ReturnValue == Result.Fail
        assert small.FindPath(Start=start, End=end).ReturnValue == Result.Success

        # A bad setting is refused as it is set, and undone: the mesh stays as it was.
        with pytest.raises(spear.InvalidArgumentError, match=r"^ARecastNavMesh.AgentMaxSlope: AgentMaxSlope = 95 must be in \(0, 90\) degrees"):
            big.AgentMaxSlope = 95.0
        with pytest.raises(spear.InvalidArgumentError, match=r"^ARecastNavMesh.CellSize: CellSize = nan must be a finite number > 0"):
            big.CellSize = math.nan
        with pytest.raises(spear.InvalidArgumentError, match=r"^ARecastNavMesh.TileSize: TileSize = 1e-09 must be at least 8 cells \(0.8 m at CellSize 0.1\)"):
            big.TileSize = 1e-9
        assert (big.AgentMaxSlope, big.CellSize, big.TileSize) == (45.0, 0.1, 12.8)
        assert big.FindPath(Start=start, End=end).ReturnValue == Result.Fail
        with pytest.raises(spear.InvalidArgumentError, match=r"FindPaths\(\): StartPoints has 1 rows and EndPoints 2"):
            small.FindPaths(StartPoints=np.zeros((1, 3)), EndPoints=np.zeros((2, 3)))
        with pytest.raises(spear.InvalidArgumentError, match=r"GetRandomReachablePointsInRadius\(\): Origins\[0, 2\] = nan is not finite"):
            small.GetRandomReachablePointsInRadius(Origins=np.array([[0.0, 0.0, math.nan]]), Radius=1.0)
        with pytest.raises(spear.InvalidArgumentError, match=r"GetRandomPoints\(\): NumPoints -1 must be in \[0, 10000000\]"):
            small.GetRandomPoints(NumPoints=-1)
        with pytest.raises(spear.InvalidArgumentError, match=r"NumPoints 2000000000 must be in"):
            small.GetRandomPoints(NumPoints=2_000_000_000)  # refused, not a 48 GB allocation
    with instance.end_frame():
        pass


def test_an_empty_world_has_no_navigation(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        nav = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game).GetDefaultNavDataInstance()
        assert nav.GetName() == "RecastNavMesh-Default"
        assert nav.GetNumPolygons() == 0
        result = nav.FindPath(Start=spear.FVector(), End=spear.FVector(X=1.0))
        assert result.ReturnValue == Result.Error and result.PathPoints.shape == (0, 3)
        with pytest.raises(spear.InvalidStateError, match=r"GetRandomPoints\(\): .*RecastNavMesh-Default.* has no navigable area"):
            nav.GetRandomPoints(NumPoints=1)
    with instance.end_frame():
        pass


def test_an_ai_walks_the_path_through_the_gap(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall_with_gap(game)
        game.spawn_actor(uclass=spear.ANavMeshBoundsVolume).SetActorScale3D(NewScale3D=spear.FVector(1.0, 0.5, 1.0))
        walker = game.spawn_actor(uclass=spear.ACharacter, location=spear.FVector(-4.0, 0.0, 0.95))
        walker.CharacterMovement.MaxWalkSpeed = 4.0
        ai = game.spawn_actor(uclass=spear.AAIController)
        ai.Possess(InPawn=walker)
        assert ai.MoveToLocation(Dest=spear.FVector(4.0, 0.0, 0.0)) == spear.EPathFollowingRequestResult.RequestSuccessful
        first = ai.GetImmediateMoveDestination()
        assert 1.5 < first.Y < 3.0  # heading for the gap, not straight at the goal
    with instance.end_frame():
        pass
    max_x_before_gap = -math.inf
    for _ in range(300):  # about 9 m at 4 m/s
        with instance.begin_frame():
            at = walker.GetActorLocation()
            if at.Y < 1.5:
                max_x_before_gap = max(max_x_before_gap, at.X) if at.X < 0 else max_x_before_gap
            moving = ai.GetMoveStatus() == spear.EPathFollowingStatus.Moving
        with instance.end_frame():
            pass
        if not moving:
            break
    with instance.begin_frame():
        at = walker.GetActorLocation()
        assert ai.GetMoveStatus() == spear.EPathFollowingStatus.Idle
        assert math.hypot(at.X - 4.0, at.Y) <= 0.1 + 0.35 + 1e-6  # arrived, on the far side of the wall
        assert max_x_before_gap < -0.3  # it never walked into the wall below the gap
    with instance.end_frame():
        pass


def test_nav_settings_are_saved_with_the_scene(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    path = tmp_path / "nav.json"
    with instance.begin_frame():
        wall_with_gap(game)
        nav = nav_data(game, radius=0.45)
        before = nav.FindPath(Start=spear.FVector(-4.0, 0.0, 0.0), End=spear.FVector(4.0, 0.0, 0.0))
        game.save_scene(path=str(path))
        game.load_scene(path=str(path))
        loaded = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game).GetNavDataForAgentName(AgentName="Default")
        assert loaded is not None and loaded.AgentRadius == 0.45 and loaded.TileSize == 6.4
        after = loaded.FindPath(Start=spear.FVector(-4.0, 0.0, 0.0), End=spear.FVector(4.0, 0.0, 0.0))
        assert np.array_equal(after.PathPoints, before.PathPoints)  # the build is deterministic
    with instance.end_frame():
        pass


def test_a_move_survives_its_navigation_going_away_and_refused_requests(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall_with_gap(game)
        nav = nav_data(game)
        walker = game.spawn_actor(uclass=spear.ACharacter, location=spear.FVector(-4.0, 0.0, 0.95))
        goal = game.spawn_actor(uclass=spear.APlayerStart, name="Goal", location=spear.FVector(4.0, 0.0, 0.0))
        ai = game.spawn_actor(uclass=spear.AAIController)
        ai.Possess(InPawn=walker)
        assert ai.MoveToActor(Goal=goal) == spear.EPathFollowingRequestResult.RequestSuccessful
        corner = ai.GetImmediateMoveDestination()
        with pytest.raises(spear.InvalidArgumentError, match=r"MoveToLocation\(\): AcceptanceRadius nan must be >= 0"):
            ai.MoveToLocation(Dest=spear.FVector(), AcceptanceRadius=math.nan)
        assert ai.GetImmediateMoveDestination() == corner  # the refused request changed nothing
        game.destroy_actor(actor=nav)  # the navigation goes away...
        goal.SetActorLocation(NewLocation=spear.FVector(4.0, -3.0, 0.0))  # ...and the goal moves: a re-plan
    with instance.end_frame():
        pass
    instance.step(num_frames=3)
    with instance.begin_frame():
        assert ai.GetMoveStatus() == spear.EPathFollowingStatus.Idle  # the move ended; the engine runs on
    with instance.end_frame():
        pass
