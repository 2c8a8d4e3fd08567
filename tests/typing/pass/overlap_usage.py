"""Positive typing case: trigger volumes and overlap queries, typed by the class filter."""

from __future__ import annotations

from typing import assert_type

import spear


def overlaps(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        trigger = game.spawn_actor(uclass=spear.ATriggerBox)
        trigger.CollisionComponent.BoxExtent = spear.FVector(2.0, 2.0, 1.0)
        assert_type(trigger.CollisionComponent, spear.UBoxComponent)
        assert_type(trigger.GetOverlappingActors(ClassFilter=spear.AStaticMeshActor), list[spear.AStaticMeshActor])
        component = trigger.CollisionComponent
        assert_type(component.GetOverlappingActors(ClassFilter=spear.APawn), list[spear.APawn])
        assert_type(component.GetBeginOverlaps(), list[spear.UPrimitiveComponent])
        assert_type(component.IsOverlappingActor(Other=trigger), bool)
        sphere = game.spawn_actor(uclass=spear.ATriggerSphere)
        sphere.CollisionComponent.SphereRadius = 3.0
    with instance.end_frame():
        pass
