"""Asynchronous calls: typed futures resolved by end_frame; over RPC, one message per frame."""

from __future__ import annotations

import pytest

import spear


def test_call_async_returns_futures_resolved_by_end_frame(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=1.0))
        before = [actor.call_async.GetActorLocation() for _ in range(50)]
        moved = actor.call_async.SetActorLocation(NewLocation=spear.FVector(Z=2.0))
        after = actor.call_async.GetActorLocation()
        actor.send_async.SetActorScale3D(NewScale3D=spear.FVector(X=2.0, Y=2.0, Z=2.0))
        bad = actor.call_async.SetActorLocation(NewLocation="nowhere")  # type: ignore[arg-type]
        spawned = game.call_async.spawn_actor(uclass=spear.AStaticMeshActor, name="Async")
        bounds = actor.call_async.GetActorBounds(bOnlyCollidingComponents=False)
        doomed = game.spawn_actor(uclass=spear.AActor)
        destroyed = game.call_async.destroy_actor(actor=doomed)  # a function without a result
        refused = game.call_async.destroy_actor(actor=None)  # type: ignore[arg-type]
    with instance.end_frame():
        assert destroyed.get() is None and not doomed.is_valid()
        with pytest.raises(spear.InvalidArgumentError):  # its error, not lost with the future
            refused.get()
        assert all(f.get() == spear.FVector(Z=1.0) for f in before)
        assert moved.get() is True
        assert after.get() == spear.FVector(Z=2.0)
        with pytest.raises(TypeError):
            bad.get()
        assert isinstance(spawned.get(), spear.AStaticMeshActor) and spawned.get().GetName() == "Async"
        assert actor.GetActorScale3D() == spear.FVector(X=2.0, Y=2.0, Z=2.0)
        assert isinstance(bounds.get(), spear.AActor.GetActorBoundsResult)
        assert bounds.get().Origin == spear.FVector(Z=2.0)


def test_calls_queued_in_a_frame_travel_in_one_message() -> None:
    with spear.Instance(server="launch") as instance:
        connection = instance._backend.connection  # type: ignore[attr-defined]
        game = instance.get_game()
        with instance.begin_frame():
            actor = game.spawn_actor(uclass=spear.AActor)
            sent = connection.messages_sent
            futures = [actor.call_async.ActorHasTag(Tag=str(i)) for i in range(10_000)]
            assert connection.messages_sent == sent  # nothing sent yet
        # Leaving the block sent the queue and the frame's execution in one message.
        assert connection.messages_sent == sent + 1
        with instance.end_frame():
            assert not any(f.get() for f in futures)


def test_synchronous_calls_see_the_effects_of_earlier_queued_ones(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AActor)
        actor.send_async.SetActorLocation(NewLocation=spear.FVector(X=5.0))
        # A plain call sends the queue first, so order is kept.
        assert actor.GetActorLocation() == spear.FVector()  # an AActor has no root component to move
        game.send_async.destroy_actor(actor=actor)
        assert game.get_actor_count() == 0
    with instance.end_frame():
        pass


def test_a_failed_send_async_call_is_a_warning_and_the_rest_still_run(instance: spear.Instance) -> None:
    # Nobody waits for a send_async call, so its error is not lost silently either: both transports warn
    # with the engine's message, and the calls around it run.
    game = instance.get_game()
    with pytest.warns(RuntimeWarning) as warned:
        with instance.begin_frame():
            actor = game.spawn_actor(uclass=spear.AActor)
            game.send_async.destroy_actor(actor=None)  # type: ignore[arg-type]
            game.send_async.destroy_actor(actor=actor)
        with instance.end_frame():
            destroyed = not actor.is_valid()
    assert destroyed
    messages = [str(w.message) for w in warned if str(w.message).startswith("send_async call failed:")]
    assert messages == ["send_async call failed: UWorld.destroy_actor(): argument 'actor' must not be None"]


def test_queued_calls_take_their_arguments_as_they_were_at_the_call(instance: spear.Instance) -> None:
    # In-process a queued call runs at once; over RPC its arguments are encoded when it is queued. Either way a
    # struct the caller reuses and changes afterwards does not change the calls already made.
    game = instance.get_game()
    with instance.begin_frame():
        actors = [game.spawn_actor(uclass=spear.AStaticMeshActor) for _ in range(3)]
        where = spear.FVector()
        moved = []
        for i, actor in enumerate(actors):
            where.X = float(i + 1)
            moved.append(actor.call_async.SetActorLocation(NewLocation=where))
        where.X = 100.0
    with instance.end_frame():
        assert all(future.get() is True for future in moved)
        assert [actor.GetActorLocation().X for actor in actors] == [1.0, 2.0, 3.0]


def test_an_argument_that_cannot_be_sent_fails_its_call_alone(instance: spear.Instance) -> None:
    game = instance.get_game()
    with pytest.warns(RuntimeWarning) as warned:
        with instance.begin_frame():
            actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
            actor.send_async.SetActorLocation(NewLocation=object())  # type: ignore[arg-type]
            refused = actor.call_async.SetActorLocation(NewLocation=object())  # type: ignore[arg-type]
            actor.send_async.SetActorLocation(NewLocation=spear.FVector(X=4.0))
        with instance.end_frame():
            with pytest.raises(TypeError, match="SetActorLocation"):
                refused.get()
            location = actor.GetActorLocation()
    assert location == spear.FVector(X=4.0)
    failed = [str(w.message) for w in warned if str(w.message).startswith("send_async call failed:")]
    assert len(failed) == 1 and "SetActorLocation" in failed[0]


def test_a_struct_with_an_emptied_field_fails_its_call_alone_with_the_same_error(instance: spear.Instance) -> None:
    # The struct's own AttributeError, on both transports and for every way of calling; the frame the call was
    # the first of, and the calls after it, go on (over RPC the value is read while the frame's first message is
    # built, which once lost the frame's begin with it).
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Emptied")
    with instance.end_frame():
        pass
    emptied = spear.FVector(X=1.0, Y=2.0, Z=3.0)
    del emptied.Z
    with pytest.warns(RuntimeWarning, match="send_async call failed: 'FVector' object has no attribute 'Z'"):
        with instance.begin_frame():
            with pytest.raises(AttributeError, match="'FVector' object has no attribute 'Z'"):
                actor.SetActorLocation(NewLocation=emptied)
            actor.send_async.SetActorLocation(NewLocation=emptied)
            refused = actor.call_async.SetActorLocation(NewLocation=emptied)
            actor.send_async.SetActorLocation(NewLocation=spear.FVector(X=5.0))
        with instance.end_frame():
            with pytest.raises(AttributeError, match="'FVector' object has no attribute 'Z'"):
                refused.get()
            assert actor.GetActorLocation() == spear.FVector(X=5.0)
