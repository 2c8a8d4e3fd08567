"""Lanes (UZoneGraphSubsystem, AZoneGraphData): road splines tagged "Road" become lanes with junctions where roads
end on roads; nearest-lane queries one by one and batched, locations along lanes, links, the road a lane runs
along; a changed road rebuilds the lanes, crossing roads are refused leaving the lanes as they were, and scenes
save the roads and settings that rebuild the same lanes. Both transports."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import spear

LINK = spear.EZoneLaneLinkType


def _road(game: spear.UWorld, name: str, *points: tuple[float, float]) -> spear.ASplineActor:
    road = game.spawn_actor(uclass=spear.ASplineActor, name=name, tags=["Road"])
    road.SplineComponent.SetSplinePoints(Points=[spear.FVector(x, y, 0.0) for x, y in points],
                                         CoordinateSpace=spear.ESplineCoordinateSpace.World)
    return road


def _t_junction(game: spear.UWorld) -> spear.UZoneGraphSubsystem:
    """Main along +X from -50 to 50 m; Side from Main at x = 0 north to y = 40 m."""
    _road(game, "Main", (-50.0, 0.0), (50.0, 0.0))
    _road(game, "Side", (0.0, 0.0), (0.0, 40.0))
    return spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)


def test_road_splines_become_lanes_with_a_junction(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lanes = _t_junction(game)
        data = lanes.GetZoneGraphData()
        assert data.GetName() == "ZoneGraphData-Default"
        assert [(d.Tag, d.Width, d.Direction) for d in data.LaneProfile] == [
            ("Sidewalk", 2.0, spear.EZoneLaneDirection.Forward), ("Driving", 3.5, spear.EZoneLaneDirection.Forward),
            ("Driving", 3.5, spear.EZoneLaneDirection.Backward), ("Sidewalk", 2.0, spear.EZoneLaneDirection.Backward)]
        assert lanes.GetNumJunctions() == 1
        assert lanes.GetLaneTags() == ["Sidewalk", "Driving"]
        # Three road pieces (Main either side of the junction, Side) of four lanes, then the connectors.
        count = lanes.GetNumLanes()
        assert count > 12
        # Driving east on Main's west piece: the lane 1.75 m right of the centre line (-Y), ending short of the
        # junction (half the road's 11 m width and a 3 m corner radius), leading straight on or left into Side.
        found, location, distance = lanes.FindNearestLane(Location=spear.FVector(-20.0, -2.0, 0.3), MaxDistance=5.0,
                                                          Tag="Driving")
        assert found and location.LaneIndex == 1
        assert (location.Position.X, location.Position.Y) == pytest.approx((-20.0, -1.75))
        assert distance == pytest.approx(math.hypot(0.25, 0.3))
        assert (location.Direction.X, location.Direction.Y) == pytest.approx((1.0, 0.0))
        assert location.DistanceAlongLane == pytest.approx(30.0)
        road = lanes.GetLaneRoad(LaneIndex=1)
        assert road is not None and road.GetName() == "Main"
        assert lanes.GetLaneTag(LaneIndex=1) == "Driving" and lanes.GetLaneWidth(LaneIndex=1) == 3.5
        assert lanes.GetLaneLength(LaneIndex=1) == pytest.approx(50.0 - 8.5)
        leads = lanes.GetLinkedLanes(LaneIndex=1, Type=LINK.Outgoing)
        assert len(leads) == 2
        reached = set()
        for connector in leads:
            assert lanes.GetLaneRoad(LaneIndex=connector) is None  # a connector through the junction
            assert lanes.GetLinkedLanes(LaneIndex=connector, Type=LINK.Incoming) == [1]
            (after,) = lanes.GetLinkedLanes(LaneIndex=connector, Type=LINK.Outgoing)
            after_road = lanes.GetLaneRoad(LaneIndex=after)
            assert after_road is not None
            reached.add(after_road.GetName())
        assert reached == {"Main", "Side"}
        assert lanes.GetLinkedLanes(LaneIndex=1, Type=LINK.AdjacentRight) == [0]  # the sidewalk
        assert lanes.GetLinkedLanes(LaneIndex=1, Type=LINK.AdjacentLeft) == []
        points = lanes.GetLanePoints(LaneIndex=1)
        assert points.shape[1] == 3 and points[0] == pytest.approx([-50.0, -1.75, 0.0])
        all_points, starts = lanes.GetAllLanePoints()
        assert starts.shape == (count + 1,) and starts[-1] == len(all_points)
        assert np.array_equal(all_points[starts[1]:starts[2]], points)
    with instance.end_frame():
        pass


def test_nearest_lanes_one_by_one_and_batched_agree(instance: spear.Instance) -> None:
    game = instance.get_game()
    rng = np.random.default_rng(5)
    points = np.column_stack([rng.uniform(-60, 60, 200), rng.uniform(-20, 50, 200), rng.uniform(-1, 1, 200)])
    with instance.begin_frame():
        lanes = _t_junction(game)
        indices, positions, along = lanes.FindNearestLanes(Locations=points, MaxDistance=6.0, Tag="Sidewalk")
        assert indices.dtype == np.int64 and positions.shape == (200, 3) and along.shape == (200,)
        for i in range(0, 200, 7):
            one = lanes.FindNearestLaneLocationByName(Location=spear.FVector(*map(float, points[i])),
                                                      TagName="Sidewalk", MaxDistance=6.0)
            assert one.LaneIndex == indices[i]
            if one.LaneIndex >= 0:
                assert [one.Position.X, one.Position.Y, one.Position.Z] == pytest.approx(positions[i])
                assert one.DistanceAlongLane == pytest.approx(along[i])
                assert lanes.GetLaneTag(LaneIndex=one.LaneIndex) == "Sidewalk"
            else:
                assert np.isnan(positions[i]).all()
        assert (indices >= 0).sum() > 20 and (indices < 0).sum() > 20
        # Far from every lane: a location with no lane, not an error.
        nowhere = lanes.FindNearestLaneLocationByName(Location=spear.FVector(500.0, 500.0, 0.0), TagName="Driving")
        assert nowhere.LaneIndex == -1
        assert not lanes.FindNearestLane(Location=spear.FVector(500.0, 0.0, 0.0), MaxDistance=10.0, Tag="").ReturnValue
    with instance.end_frame():
        pass


def test_locations_move_along_their_lane(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lanes = _t_junction(game)
        start = lanes.CalculateLocationAlongLane(LaneIndex=1, Distance=10.0)
        assert (start.Position.X, start.DistanceAlongLane) == pytest.approx((-40.0, 10.0))
        moved = lanes.AdvanceLaneLocation(InLaneLocation=start, AdvanceDistance=12.5)
        assert (moved.Position.X, moved.Position.Y, moved.DistanceAlongLane) == pytest.approx((-27.5, -1.75, 22.5))
        end = lanes.AdvanceLaneLocation(InLaneLocation=start, AdvanceDistance=1000.0)
        assert end.DistanceAlongLane == pytest.approx(lanes.GetLaneLength(LaneIndex=1))  # stops at the lane's end
        back = lanes.AdvanceLaneLocation(InLaneLocation=start, AdvanceDistance=-20.0)
        assert back.DistanceAlongLane == 0.0
    with instance.end_frame():
        pass


def test_changed_roads_rebuild_and_bad_input_is_refused(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lanes = _t_junction(game)
        before = lanes.GetNumLanes()
        side = game.find_actor_by_name(name="Side")
        assert isinstance(side, spear.ASplineActor)
        # Side moved 10 m east: its lanes move with it (driving south, 1.75 m west of its centre line).
        side.SetActorLocation(NewLocation=spear.FVector(10.0, 0.0, 0.0))
        found, location, _ = lanes.FindNearestLane(Location=spear.FVector(8.0, 20.0, 0.0), MaxDistance=3.0, Tag="Driving")
        assert found and location.Position.X == pytest.approx(10.0 - 1.75)
        assert location.Direction.Y == pytest.approx(-1.0)
        # Attached to an actor that moves, Side moves with it although its own transform stays as it was.
        carrier = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Carrier")
        side.SplineComponent.AttachToComponent(Parent=carrier.StaticMeshComponent, bKeepWorldTransform=True)
        carrier.SetActorLocation(NewLocation=spear.FVector(-4.0, 0.0, 0.0))
        found, location, _ = lanes.FindNearestLane(Location=spear.FVector(4.0, 20.0, 0.0), MaxDistance=3.0, Tag="Driving")
        assert found and location.Position.X == pytest.approx(6.0 - 1.75)
        side.SplineComponent.DetachFromComponent()
        carrier.SetActorLocation(NewLocation=spear.FVector(0.0, 0.0, 0.0))
        side.SetActorLocation(NewLocation=spear.FVector(10.0, 0.0, 0.0))
        # A road across Main with no junction: refused naming both roads; the lanes stay as they were.
        _road(game, "Cross", (30.0, -20.0), (30.0, 20.0))
        with pytest.raises(spear.InvalidArgumentError) as raised:
            lanes.GetNumLanes()
        assert str(raised.value) == ("UZoneGraphSubsystem.GetNumLanes(): road 'Main' crosses road 'Cross' at "
                                     "(30, 0, 0) without a junction: end one of them there, or split it there into two roads")
        cross = game.find_actor_by_name(name="Cross")
        assert cross is not None
        game.destroy_actor(actor=cross)
        assert lanes.GetNumLanes() == before
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"FindNearestLane\(\): no lane has tag 'Bike' \(the lanes' tags: Sidewalk, Driving\)"):
            lanes.FindNearestLane(Location=spear.FVector(), MaxDistance=1.0, Tag="Bike")
        with pytest.raises(spear.InvalidArgumentError, match=r"GetLaneLength\(\): LaneIndex 9999 is not a lane"):
            lanes.GetLaneLength(LaneIndex=9999)
        with pytest.raises(spear.InvalidArgumentError, match=r"FindNearestLanes\(\): Locations\[1, 0\] = nan"):
            lanes.FindNearestLanes(Locations=np.array([[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]]), MaxDistance=1.0, Tag="")
        with pytest.raises(spear.InvalidArgumentError, match=r"MaxDistance -1(\.0)? must be >= 0"):
            lanes.FindNearestLaneLocationByName(Location=spear.FVector(), TagName="Driving", MaxDistance=-1.0)
        data = lanes.GetZoneGraphData()
        with pytest.raises(spear.InvalidArgumentError, match=r"Profile\[0\]\.Width must be > 0, got 0"):
            data.SetLaneProfile(Profile=[spear.FZoneLaneDesc(Tag="Driving", Width=0.0)])
        assert len(data.LaneProfile) == 4
        # One driving lane each way and nothing else: fewer lanes, one tag.
        data.LaneProfile = [spear.FZoneLaneDesc(Tag="Driving", Width=3.0),
                            spear.FZoneLaneDesc(Tag="Driving", Width=3.0, Direction=spear.EZoneLaneDirection.Backward)]
        assert lanes.GetLaneTags() == ["Driving"] and lanes.GetNumLanes() < before
    with instance.end_frame():
        pass


def test_scenes_save_the_roads_and_settings_that_rebuild_the_same_lanes(instance: spear.Instance,
                                                                        tmp_path: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lanes = _t_junction(game)
        lanes.GetZoneGraphData().JunctionTolerance = 2.0
        points, starts = lanes.GetAllLanePoints()
        game.save_scene(path=str(tmp_path / "roads.json"))
        game.load_scene(path=str(tmp_path / "roads.json"))
        loaded = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
        assert loaded.GetZoneGraphData().JunctionTolerance == 2.0
        again, again_starts = loaded.GetAllLanePoints()
        assert np.array_equal(again_starts, starts) and np.allclose(again, points, atol=1e-9)
    with instance.end_frame():
        pass


def test_cameras_see_the_roads_with_their_own_ids(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lanes = _t_junction(game)
        data = lanes.GetZoneGraphData()
        # Straight down onto Main between its west end and the junction: 37.3 m across at 40 m up, half a pixel
        # (7.3 cm) to the side, so that the lines (12 cm: 0.8 pixels) lie over pixel centres, not between them.
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Above", location=spear.FVector(-25.0, 0.073, 40.0),
                                  rotation=spear.FRotator(Pitch=-90.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 256, 256, 50.0  # a 12 cm line is 0.8 pixels wide
        camera.Modalities = [spear.ECameraModality.ObjectIds]
    with instance.end_frame():
        ids = camera.read_pixels()["object_ids"]
    slots: dict[str, int] = {}
    with instance.begin_frame():
        for object_id in np.unique(ids[ids != 0]):
            found, actor, component, slot, material = camera.GetObjectIdInfo(ObjectId=int(object_id))
            assert found and actor is not None and actor.GetName() == "ZoneGraphData-Default" and component is None
            slots[f"{slot}:{material}"] = int((ids == object_id).sum())
        data.RoadMaterial = "Red"
    with instance.end_frame():
        pass
    # 11 m of road across 37.3 m of view (0.295): asphalt (7 m), the two sidewalks (4 m), the lines on them.
    assert set(slots) == {"0:Asphalt", "1:Concrete", "2:LaneMarking"}, slots
    assert slots["0:Asphalt"] > slots["1:Concrete"] > slots["2:LaneMarking"] > 0
    assert 0.27 < sum(slots.values()) / ids.size < 0.32
    with instance.begin_frame():
        pass
    with instance.end_frame():
        ids = camera.read_pixels()["object_ids"]
    with instance.begin_frame():
        found, _, _, slot, material = camera.GetObjectIdInfo(ObjectId=int(ids[128, 117]))  # 1.5 m off the centre line
        assert found and (slot, material) == (0, "Red")  # the road's material, renamed
        data.bDrawRoads = False
    with instance.end_frame():
        pass
    with instance.begin_frame():
        pass
    with instance.end_frame():
        assert not camera.read_pixels()["object_ids"].any()  # nothing drawn, nothing else in view


def test_roads_that_make_no_lanes_leave_the_drawn_roads_as_they_were(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lanes = _t_junction(game)
        lanes.GetZoneGraphData()  # a world draws its roads once it has zone graph data
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Above", location=spear.FVector(-20.0, 0.0, 40.0),
                                  rotation=spear.FRotator(Pitch=-90.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 64, 64, 60.0
        camera.Modalities = [spear.ECameraModality.ObjectIds]
    with instance.end_frame():
        before = camera.read_pixels()["object_ids"]
    with instance.begin_frame():
        _road(game, "Cross", (-20.0, -20.0), (-20.0, 20.0))  # across Main with no junction
    with instance.end_frame():  # the frame renders: the roads as they were drawn
        after = camera.read_pixels()["object_ids"]
    assert before.any() and np.array_equal(before, after)
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError, match="crosses road 'Cross'"):
            lanes.GetNumLanes()  # the queries say why
    with instance.end_frame():
        pass
