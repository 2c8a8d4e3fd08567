"""Negative typing case: misuse of navigation. Every marked line must be rejected by mypy --strict (`# E:`)
and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    nav = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game).GetDefaultNavDataInstance()
    nav.FindPath(Start=(0.0, 0.0, 0.0), End=spear.FVector())  # E: Argument "Start" to "FindPath" of "ARecastNavMesh" has incompatible type "Tuple[float, float, float]"; expected "FVector"  [arg-type]  # P: reportArgumentType: Argument of type "tuple[float, float, float]" cannot be assigned to parameter "Start" of type "FVector" in function "FindPath" / "tuple[float, float, float]" is not assignable to "FVector"
    nav.AgentRadiuss = 0.5  # E: "ARecastNavMesh" has no attribute "AgentRadiuss"; maybe "AgentRadius"?  [attr-defined]  # P: reportAttributeAccessIssue: Cannot assign to attribute "AgentRadiuss" for class "ARecastNavMesh" / Attribute "AgentRadiuss" is unknown
    nav.FindPath(Start=spear.FVector(), End=spear.FVector()).PathLength.shape  # E: "float" has no attribute "shape"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "shape" for class "float" / Attribute "shape" is unknown
    spear.UNavigationSystemV1.GetPathLength(WorldContextObject=game, PathStart=spear.FVector(), PathEnd=spear.FVector(), NavData=game)  # E: Argument "NavData" to "GetPathLength" of "UNavigationSystemV1" has incompatible type "UWorld"; expected "Optional[ARecastNavMesh]"  [arg-type]  # P: reportArgumentType: Argument of type "UWorld" cannot be assigned to parameter "NavData" of type "ARecastNavMesh | None" in function "GetPathLength" / Type "UWorld" is not assignable to type "ARecastNavMesh | None" / "UWorld" is not assignable to "ARecastNavMesh" / "UWorld" is not assignable to "None"
