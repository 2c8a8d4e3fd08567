"""Positive typing case: lanes (UZoneGraphSubsystem) queried as a driving script does."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

import spear


def drive_along(game: spear.UWorld) -> list[spear.FVector]:
    lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
    data: spear.AZoneGraphData = lanes.GetZoneGraphData()
    data.LaneProfile = [spear.FZoneLaneDesc(Tag="Driving", Width=3.5),
                        spear.FZoneLaneDesc(Tag="Driving", Width=3.5, Direction=spear.EZoneLaneDirection.Backward)]
    start: spear.FZoneGraphLaneLocation = lanes.FindNearestLaneLocationByName(
        Location=spear.FVector(10.0, 0.0, 0.0), TagName="Driving", MaxDistance=20.0)
    if start.LaneIndex < 0:
        return []
    found, location, distance = lanes.FindNearestLane(Location=start.Position, MaxDistance=1.0, Tag="")
    assert found and distance >= 0.0
    route: list[spear.FVector] = []
    while len(route) < 10:
        route.append(location.Position)
        location = lanes.AdvanceLaneLocation(InLaneLocation=location, AdvanceDistance=5.0)
        if location.DistanceAlongLane >= lanes.GetLaneLength(LaneIndex=location.LaneIndex):
            following: list[int] = lanes.GetLinkedLanes(LaneIndex=location.LaneIndex,
                                                        Type=spear.EZoneLaneLinkType.Outgoing)
            if not following:
                break
            location = lanes.CalculateLocationAlongLane(LaneIndex=following[0], Distance=0.0)
    road: spear.ASplineActor | None = lanes.GetLaneRoad(LaneIndex=start.LaneIndex)
    assert road is None or road.SplineComponent.GetSplineLength() > 0.0
    indices: NDArray[np.int64]
    positions: NDArray[np.float64]
    indices, positions, _ = lanes.FindNearestLanes(Locations=np.zeros((4, 3)), MaxDistance=5.0, Tag="Driving")
    assert indices.shape == (4,) and positions.shape == (4, 3)
    return route


def traffic(game: spear.UWorld, car: spear.AWheeledVehiclePawn) -> tuple[float, list[int]]:
    """An AI driver for a car, tuned and asked where it is."""
    driver = game.spawn_actor(uclass=spear.ALaneFollowingController, name="Driver")
    driver.TargetSpeed, driver.MinGap, driver.TimeGap = 9.0, 2.5, 1.5
    driver.LaneTag, driver.RandomSeed, driver.bDriving = "Driving", 42, True
    driver.Possess(InPawn=car)
    at: spear.FZoneGraphLaneLocation = driver.GetLaneLocation()
    waiting: bool = driver.IsWaitingAtJunction()
    gap: float = driver.GetGapAhead()
    route: list[int] = driver.GetRoute()
    assert at.LaneIndex >= -1 and (waiting or not waiting)
    return gap + driver.GetLateralOffset(), route
