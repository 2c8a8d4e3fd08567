"""Negative typing case: misuse of lanes. Every marked line must be rejected by mypy --strict (`# E:`) and by
pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(game: spear.UWorld) -> None:
    lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
    lanes.FindNearestLaneLocationByName(Location=(1.0, 2.0, 0.0), TagName="Driving")  # E: Argument "Location" to "FindNearestLaneLocationByName" of "UZoneGraphSubsystem" has incompatible type "Tuple[float, float, float]"; expected "FVector"  [arg-type]  # P: reportArgumentType: Argument of type "tuple[float, float, float]" cannot be assigned to parameter "Location" of type "FVector" in function "FindNearestLaneLocationByName" / "tuple[float, float, float]" is not assignable to "FVector"
    lanes.GetLinkedLanes(LaneIndex=3, Type="Outgoing")  # E: Argument "Type" to "GetLinkedLanes" of "UZoneGraphSubsystem" has incompatible type "str"; expected "EZoneLaneLinkType"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['Outgoing']" cannot be assigned to parameter "Type" of type "EZoneLaneLinkType" in function "GetLinkedLanes" / "Literal['Outgoing']" is not assignable to "EZoneLaneLinkType"
    lanes.GetZoneGraphData().LaneProfile = [("Driving", 3.5)]  # E: List item 0 has incompatible type "Tuple[str, float]"; expected "FZoneLaneDesc"  [list-item]  # P: reportAttributeAccessIssue: Cannot assign to attribute "LaneProfile" for class "AZoneGraphData" / "tuple[str, float]" is not assignable to "FZoneLaneDesc"
    lanes.FindNearestLane(Location=spear.FVector(), MaxDistance=5.0, Tag="Driving").OutLaneLocation.Lane  # E: "FZoneGraphLaneLocation" has no attribute "Lane"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "Lane" for class "FZoneGraphLaneLocation" / Attribute "Lane" is unknown


def traffic_misuse(game: spear.UWorld) -> None:
    driver = game.spawn_actor(uclass=spear.ALaneFollowingController, name="Driver")
    driver.TargetSpeed = "fast"  # E: Incompatible types in assignment (expression has type "str", variable has type "float")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "TargetSpeed" for class "ALaneFollowingController" / "Literal['fast']" is not assignable to "float"
    driver.Speed = 9.0  # E: "ALaneFollowingController" has no attribute "Speed"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot assign to attribute "Speed" for class "ALaneFollowingController" / Attribute "Speed" is unknown
    driver.GetRoute().append("lane")  # E: Argument 1 to "append" of "list" has incompatible type "str"; expected "int"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['lane']" cannot be assigned to parameter "object" of type "int" in function "append" / "Literal['lane']" is not assignable to "int"
