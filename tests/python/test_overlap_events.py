"""Overlap events as callbacks (Instance.on_overlap) on both transports: delivered at the start of end_frame
for the frame that ticked, equal to the polled events, stopped by cancel() and by the component's end, and a
failing callback leaves the engine usable."""

from __future__ import annotations

import pytest

import spear
from spear.errors import InvalidArgumentError


def falling_box_and_trigger(instance: spear.Instance) -> tuple[spear.ATriggerBox, spear.UPrimitiveComponent,
                                                                 spear.UPrimitiveComponent]:
    """A trigger at z in [2.5, 3.5] and a unit box falling through it from z = 6, spawned in one frame: the
    trigger, its collision component and the box's mesh component."""
    game = instance.get_game()
    with instance.begin_frame():
        trigger = game.spawn_actor(uclass=spear.ATriggerBox, location=spear.FVector(Z=3.0))
        trigger.CollisionComponent.BoxExtent = spear.FVector(2.0, 2.0, 0.5)
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Falling", location=spear.FVector(Z=6.0))
        box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        box.StaticMeshComponent.bGenerateOverlapEvents = True
        box.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
        components = trigger.CollisionComponent, box.StaticMeshComponent
    with instance.end_frame():
        pass
    return trigger, *components


def test_callbacks_see_the_polled_events_of_each_frame(instance: spear.Instance) -> None:
    _, component, falling = falling_box_and_trigger(instance)
    events: list[tuple[str, int, spear.UPrimitiveComponent, spear.UPrimitiveComponent]] = []
    polled: list[tuple[str, int]] = []
    subscription = instance.on_overlap(
        component,
        begin=lambda me, other: events.append(("begin", instance.frame_count, me, other)),
        end=lambda me, other: events.append(("end", instance.frame_count, me, other)))
    for _ in range(120):
        with instance.begin_frame():
            pass
        with instance.end_frame():
            frame = instance.frame_count
            polled += [("begin", frame) for _ in component.GetBeginOverlaps()]
            polled += [("end", frame) for _ in component.GetEndOverlaps()]
    assert [(kind, frame) for kind, frame, _, _ in events] == polled
    assert [kind for kind, *_ in events] == ["begin", "end"]
    assert all(me == component and other == falling for _, _, me, other in events)
    assert subscription.active
    subscription.cancel()
    assert not subscription.active


def test_cancelled_and_destroyed_subscriptions_stop(instance: spear.Instance) -> None:
    trigger, component, _ = falling_box_and_trigger(instance)
    calls: list[str] = []
    cancelled = instance.on_overlap(component, begin=lambda *_: calls.append("cancelled"))
    cancelled.cancel()
    kept = instance.on_overlap(component, begin=lambda *_: calls.append("kept"))
    instance.step(num_frames=60)  # the box has entered
    assert calls == ["kept"]
    with instance.begin_frame():
        instance.get_game().destroy_actor(actor=trigger)
    with instance.end_frame():
        pass
    assert not kept.active  # its component went with the trigger


def test_a_failing_callback_raises_from_end_frame_and_the_frame_still_ends(instance: spear.Instance) -> None:
    trigger, component, _ = falling_box_and_trigger(instance)

    def fail(me: spear.UPrimitiveComponent, other: spear.UPrimitiveComponent) -> None:
        raise RuntimeError(f"callback saw {other.GetName()}")

    instance.on_overlap(component, begin=fail)
    with pytest.raises(RuntimeError, match="^callback saw StaticMeshComponent$"):
        for _ in range(60):
            with instance.begin_frame():
                pass
            with instance.end_frame():
                pass
    assert instance.frame_state == "idle"
    with pytest.raises(InvalidArgumentError, match=r"^on_overlap\(\): give begin=, end= or both$"):
        instance.on_overlap(component)
    with pytest.raises(InvalidArgumentError, match=r"^on_overlap\(\): component must be a UPrimitiveComponent, "
                                                   r"got ATriggerBox$"):
        instance.on_overlap(trigger, begin=fail)  # type: ignore[arg-type]


def test_every_event_is_delivered_before_a_callback_error_is_raised(instance: spear.Instance) -> None:
    trigger, component, falling = falling_box_and_trigger(instance)
    seen: list[str] = []

    def fail(me: spear.UPrimitiveComponent, other: spear.UPrimitiveComponent) -> None:
        seen.append("failed")
        raise RuntimeError("first")

    instance.on_overlap(component, begin=fail)
    instance.on_overlap(component, begin=lambda me, other: seen.append("second"))
    with pytest.raises(RuntimeError, match="^first$"):
        for _ in range(60):
            with instance.begin_frame():
                pass
            with instance.end_frame():
                pass
    assert seen == ["failed", "second"]  # the later subscription still saw the frame's begin event


def test_subscriptions_belong_to_their_instance(instance: spear.Instance) -> None:
    _, component, _ = falling_box_and_trigger(instance)
    # An engine of the other transport (two in-process engines share one object table and are not told apart).
    other = spear.Instance(server="launch") if instance.transport == "inprocess" else spear.Instance()
    try:
        with pytest.raises(InvalidArgumentError, match=r"^on_overlap\(\): \w+ belongs to another engine "
                                                       r"\(a different spear.Instance\)$"):
            other.on_overlap(component, begin=lambda me, it: None)
    finally:
        other.close()
    subscription = instance.on_overlap(component, begin=lambda me, it: None)
    instance.close()
    assert not subscription.active
    with pytest.raises(spear.InvalidStateError, match=r"^on_overlap\(\): the instance is closed$"):
        instance.on_overlap(component, begin=lambda me, it: None)


def test_over_rpc_the_subscriptions_read_their_events_in_one_message() -> None:
    with spear.Instance(server="launch") as instance:
        _, component, _ = falling_box_and_trigger(instance)
        for _ in range(3):
            instance.on_overlap(component, begin=lambda me, other: None, end=lambda me, other: None)
        connection = instance._backend.connection  # type: ignore[attr-defined]
        with instance.begin_frame():
            pass
        sent = connection.messages_sent
        with instance.end_frame():
            # The frame's begin_end and the six reads, in one message.
            assert connection.messages_sent == sent + 1
