"""Positive typing case: a wheeled vehicle, its settings and its wheel states."""

from __future__ import annotations

from typing import assert_type

import spear


def drive(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, location=spear.FVector(Z=0.9))
        assert_type(car, spear.AWheeledVehiclePawn)
        car.MaxSteerAngle = 30.0
        car.Mesh.SetMaterial(ElementIndex=0, Material="CarPaint")
        assert_type(car.WheelRearLeft, spear.UStaticMeshComponent)
        game.inject_input_for_actor(actor=car, input_action_name="Throttle", value=spear.FVector(X=1.0))
    with instance.end_frame():
        wheel = car.GetWheelState(WheelIndex=0)
        assert_type(wheel, spear.FWheelState)
        assert_type(wheel.bInContact, bool)
        assert_type(car.GetForwardSpeed(), float)
        assert_type(car.GetNumWheels(), int)
