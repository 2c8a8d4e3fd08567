"""Negative typing case: a blueprint's functions, typed from its asset (assets/blueprints/BP_Crate.json).
Every marked line must be rejected by mypy --strict (`# E:`) and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    crate = game.spawn_actor(uclass=spear.BP_Crate)
    crate.Launch(Speed="fast")  # E: Argument "Speed" to "Launch" of "BP_Crate" has incompatible type "str"; expected "float"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['fast']" cannot be assigned to parameter "Speed" of type "float" in function "Launch" / "Literal['fast']" is not assignable to "float"
    crate.Nudge()  # E: Missing named argument "Velocity" for "Nudge" of "BP_Crate"  [call-arg]  # P: reportCallIssue: Argument missing for parameter "Velocity"
    crate.call_async.Launch(Speed="fast")  # E: Argument "Speed" to "Launch" of "BP_CrateAsync" has incompatible type "str"; expected "float"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['fast']" cannot be assigned to parameter "Speed" of type "float" in function "Launch" / "Literal['fast']" is not assignable to "float"
    crate.send_async.Nudge()  # E: Missing named argument "Velocity" for "Nudge" of "BP_CrateSend"  [call-arg]  # P: reportCallIssue: Argument missing for parameter "Velocity"
    crate.Lunch()  # E: "BP_Crate" has no attribute "Lunch"; maybe "Launch"?  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "Lunch" for class "BP_Crate" / Attribute "Lunch" is unknown
    plain = game.spawn_actor(uclass=spear.AStaticMeshActor)
    plain.Launch()  # E: "AStaticMeshActor" has no attribute "Launch"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "Launch" for class "AStaticMeshActor" / Attribute "Launch" is unknown
