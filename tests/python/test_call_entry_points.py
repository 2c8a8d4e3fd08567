"""How a typed call reaches the engine: keywords matched whatever string object names them, what does not fit
refused with Python's own TypeError, and (in-process, where functions and properties are CPython descriptors
over the pybind11 classes, core/pybind/fast_call.h) objects that are not what a descriptor expects refused
without touching memory."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest

import spear
from spear import _inprocess


@pytest.fixture
def actor(make_instance: Callable[..., spear.Instance]) -> Iterator[tuple[spear.Instance, spear.AStaticMeshActor]]:
    instance = make_instance()
    with instance.begin_frame():
        made = instance.get_game().spawn_actor(uclass=spear.AStaticMeshActor)
        made.Tags = ["probe"]
    with instance.end_frame():
        pass
    with instance.begin_frame():
        yield instance, made
    with instance.end_frame():
        pass


def test_keywords_spelt_by_any_string_object(actor: tuple[spear.Instance, spear.AStaticMeshActor]) -> None:
    _, probe = actor
    # A keyword built at run time is a new string object, not the interned one a call site names.
    name = "".join(["T", "a", "g"])
    assert probe.ActorHasTag(**{name: "probe"}) is True
    assert probe.ActorHasTag(**{name: "other"}) is False
    location = spear.FVector(X=1.0, Y=2.0, Z=3.0)
    probe.SetActorLocation(**{"".join(["New", "Location"]): location})
    assert probe.GetActorLocation() == location


def test_calls_that_do_not_fit_raise_pythons_type_error(actor: tuple[spear.Instance, spear.AStaticMeshActor]) -> None:
    _, probe = actor
    with pytest.raises(TypeError, match=r"ActorHasTag\(\) takes 1 positional argument but 2 were given"):
        probe.ActorHasTag("probe")  # type: ignore[misc]
    with pytest.raises(TypeError, match=r"ActorHasTag\(\) got an unexpected keyword argument 'Tga'"):
        probe.ActorHasTag(Tag="probe", Tga="x")  # type: ignore[call-arg]
    with pytest.raises(TypeError, match=r"ActorHasTag\(\) missing 1 required keyword-only argument: 'Tag'"):
        probe.ActorHasTag()  # type: ignore[call-arg]
    with pytest.raises(TypeError, match=r"GetName\(\) takes 1 positional argument but 2 were given"):
        probe.GetName(1)  # type: ignore[call-arg]
    # The object keeps working after each refusal.
    assert probe.ActorHasTag(Tag="probe") is True


def test_static_functions_take_keywords_and_refuse_the_rest(
        actor: tuple[spear.Instance, spear.AStaticMeshActor]) -> None:
    instance, _ = actor
    game = instance.get_game()
    controller = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
    assert controller is None or isinstance(controller, spear.APlayerController)
    with pytest.raises(TypeError, match=r"GetPlayerController\(\) takes 0 positional arguments but 1 positional "
                                        r"argument \(and 1 keyword-only argument\) were given"):
        spear.UGameplayStatics.GetPlayerController(game, PlayerIndex=0)  # type: ignore[misc]
    with pytest.raises(TypeError, match=r"GetPlayerController\(\) got an unexpected keyword argument 'Index'"):
        spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, Index=0)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match=r"GetPlayerController\(\) missing 1 required keyword-only argument: "
                                        r"'PlayerIndex'"):
        spear.UGameplayStatics.GetPlayerController(WorldContextObject=game)  # type: ignore[call-arg]
    if isinstance(game, spear.UObject) and not hasattr(game, "_sp_client"):
        # In-process the routing above ends in the module's own static function, which checks the same way.
        native = _inprocess.native_class("UGameplayStatics")
        with pytest.raises(TypeError, match=r"GetPlayerController\(\) takes 0 positional arguments but 1 "
                                            r"positional argument \(and 1 keyword-only argument\) were given"):
            native.GetPlayerController(game, PlayerIndex=0)
        assert native.GetPlayerController(WorldContextObject=game, PlayerIndex=0) == controller


def test_descriptors_refuse_objects_of_other_classes() -> None:
    """In-process only: a descriptor reached through the class can be handed anything."""
    instance = spear.Instance()
    try:
        with instance.begin_frame():
            probe = instance.get_game().spawn_actor(uclass=spear.AStaticMeshActor)
            native = type(probe)
            with pytest.raises(TypeError):
                native.GetName(5)
            root = vars(_inprocess.module().AActor)["RootComponent"]
            with pytest.raises(TypeError, match="doesn't apply to a 'int' object"):
                root.fget(5)
            tags = vars(_inprocess.module().AActor)["Tags"]
            with pytest.raises(TypeError, match="doesn't apply to a 'str' object"):
                tags.fset("not an actor", ["x"])
            assert probe.GetName()  # still alive and answering
        with instance.end_frame():
            pass
    finally:
        instance.close()


def test_an_instance_never_initialised_is_refused() -> None:
    """In-process only: a Python subclass whose object never got its C++ value (no handle) raises, not crashes."""
    instance = spear.Instance()
    try:
        native = _inprocess.module().AActor
        Sub = type("Sub", (native,), {})
        empty = Sub.__new__(Sub)
        with instance.begin_frame():
            with pytest.raises(TypeError, match="never initialised"):
                empty.GetName()
            with pytest.raises(TypeError, match="never initialised"):
                empty.Tags
        with instance.end_frame():
            pass
    finally:
        instance.close()
