"""Blueprints: classes defined by asset files, loaded with load_class and spawned like native classes."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

import spear

ROOT = Path(__file__).resolve().parents[2]
AXES = str(ROOT / "assets" / "blueprints" / "BP_Axes.json")
CRATE = str(ROOT / "assets" / "blueprints" / "BP_Crate.json")


def write(path: Path, document: dict[str, Any]) -> str:
    path.write_text(json.dumps(document))
    return str(path)


def blueprint(parent: str = "AActor", **fields: Any) -> dict[str, Any]:
    return {"format": "spear.blueprint", "version": 1, "parent": parent, **fields}


def test_load_class_returns_a_class_named_after_the_asset(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        axes = game.load_class(uclass=spear.AActor, name=AXES)
        assert axes.__name__ == "BP_Axes" and axes.__sp_class__ == "BP_Axes"
        assert issubclass(axes, spear.AActor)
        assert game.load_class(uclass=spear.AActor, name=AXES) is axes  # loaded once, same class
        crate = game.load_class(uclass=spear.AStaticMeshActor, name=CRATE)
        assert issubclass(crate, spear.AStaticMeshActor)
        assert game.load_class(uclass=spear.UObject, name="BP_Crate") is crate  # by name once loaded
        native = game.load_class(uclass=spear.AActor, name="AStaticMeshActor")  # a registered class by name
        assert issubclass(native, spear.AStaticMeshActor) and native.__sp_class__ == "AStaticMeshActor"


def test_spawned_blueprint_has_the_assets_properties_and_components(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        axes_class = game.load_class(uclass=spear.AActor, name=AXES)
        axes = game.spawn_actor(uclass=axes_class, location=spear.FVector(1.0, 2.0, 3.0), tags=["extra"])
        assert isinstance(axes, spear.AActor)
        assert axes.GetClassName() == "BP_Axes" and axes.GetName() == "BP_Axes_0"
        assert axes.Tags == ["axes", "extra"]  # the blueprint's default, then the spawn's
        components = {c.GetName(): c for c in axes.K2_GetComponents()}
        assert list(components) == ["Root", "XAxis", "YAxis", "ZAxis"]
        assert axes.RootComponent == components["Root"]
        x = game.get_component_by_name(actor=axes, component_name="XAxis")
        assert isinstance(x, spear.UStaticMeshComponent)
        assert x.GetAttachParent() == components["Root"]
        assert x.StaticMesh == "/Engine/BasicShapes/Cube" and x.Materials == ["/Engine/Materials/Red"]
        assert x.RelativeScale3D == spear.FVector(1.0, 0.02, 0.02)
        assert x.GetComponentLocation() == spear.FVector(1.5, 2.0, 3.0)
        z = components["ZAxis"]
        assert isinstance(z, spear.UStaticMeshComponent) and z.Materials == ["/Engine/Materials/Blue"]

        crate_class = game.load_class(uclass=spear.AStaticMeshActor, name=CRATE)
        crate = game.spawn_actor(uclass=crate_class, name="Crate")
        assert isinstance(crate, spear.AStaticMeshActor) and crate.GetClassName() == "BP_Crate"
        mesh = crate.StaticMeshComponent
        assert mesh.bSimulatePhysics and mesh.MassInKg == 12.0 and mesh.Materials == ["/Engine/Materials/Wood"]
        assert mesh.Mobility == spear.EComponentMobility.Movable
        by_name = game.spawn_actor(uclass="BP_Crate", name="Crate2")
        assert by_name.GetClassName() == "BP_Crate"


def test_class_queries_see_blueprints_in_the_hierarchy(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        axes_class = game.load_class(uclass=spear.AActor, name=AXES)
        crate_class = game.load_class(uclass=spear.AActor, name=CRATE)
        plain = game.spawn_actor(uclass=spear.AActor, name="Plain")
        mesh = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Mesh")
        axes = game.spawn_actor(uclass=axes_class, name="Axes")
        crate = game.spawn_actor(uclass=crate_class, name="Crate")
        assert game.find_actors_by_class(uclass=axes_class) == [axes]
        assert game.find_actors_by_class(uclass="BP_Crate") == [crate]
        assert game.find_actor_by_class(uclass=crate_class) == crate
        assert game.find_actors_by_class(uclass=spear.AActor) == [plain, mesh, axes, crate]
        assert game.find_actors_by_class(uclass=spear.AStaticMeshActor) == [mesh, crate]
        assert game.find_actors_by_class_as_dict(uclass=axes_class) == {"Axes": axes}
        default = game.get_default_object(uclass=crate_class)
        assert default.GetClassName() == "BP_Crate" and default.GetName() == "Default__BP_Crate"


def test_blueprint_actors_round_trip_through_scene_files(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    path = str(tmp_path / "scene.json")
    with instance.begin_frame():
        game.spawn_actor(uclass=game.load_class(uclass=spear.AActor, name=AXES), name="Axes")
        game.save_scene(path=path)
        game.load_scene(path=path)
        axes = game.find_actor_by_name(name="Axes")
        assert axes is not None and axes.GetClassName() == "BP_Axes"
        assert [c.GetName() for c in axes.K2_GetComponents()] == ["Root", "XAxis", "YAxis", "ZAxis"]
    scene = json.loads(Path(path).read_text())
    assert scene["actors"][0]["class"] == "BP_Axes"


def test_load_class_errors_name_the_file_and_the_field(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()

    def fails(error: type[spear.SpearError], message: str, name: str, uclass: type[spear.UObject] = spear.AActor) -> None:
        with pytest.raises(error, match=re.escape(message)):
            game.load_class(uclass=uclass, name=name)

    missing = str(tmp_path / "BP_Missing.json")
    bad_json = tmp_path / "BP_BadJson.json"
    bad_json.write_text("{ not json")
    with instance.begin_frame():
        fails(spear.NotFoundError, f"UWorld.load_class(): blueprint '{missing}' not found", missing)
        fails(spear.InvalidArgumentError, f"UWorld.load_class(): blueprint '{bad_json}' is not valid JSON", str(bad_json))
        path = write(tmp_path / "BP_BadParent.json", blueprint("AFoo"))
        fails(spear.InvalidArgumentError,
              f"UWorld.load_class(): blueprint '{path}': 'parent': class 'AFoo' is not registered", path)
        path = write(tmp_path / "BP_BadProperty.json", blueprint(properties={"Colour": 1}))
        fails(spear.InvalidArgumentError,
              f"UWorld.load_class(): blueprint '{path}': AActor has no property 'Colour'", path)
        path = write(tmp_path / "BP_BadValue.json", blueprint(properties={"Tags": 3}))
        fails(spear.InvalidArgumentError,
              f"UWorld.load_class(): blueprint '{path}': property 'Tags': expected a list (list[str]), got number 3",
              path)
        path = write(tmp_path / "BP_BadComponent.json",
                     blueprint(components=[{"name": "Thing", "class": "UFooComponent"}]))
        fails(spear.InvalidArgumentError,
              f"UWorld.load_class(): blueprint '{path}': component 'Thing': class 'UFooComponent' is not registered",
              path)
        path = write(tmp_path / "BP_NoClass.json", blueprint(components=[{"name": "Thing"}]))
        fails(spear.InvalidArgumentError,
              f"UWorld.load_class(): blueprint '{path}': component 'Thing': missing 'class' "
              "(AActor creates no component 'Thing')", path)
        path = write(tmp_path / "BP_BadComponentProperty.json", blueprint(
            "AStaticMeshActor", components=[{"name": "StaticMeshComponent", "properties": {"Mass": 1.0}}]))
        fails(spear.InvalidArgumentError,
              f"UWorld.load_class(): blueprint '{path}': component 'StaticMeshComponent': "
              "UStaticMeshComponent has no property 'Mass'", path)
        fails(spear.InvalidArgumentError,
              "UWorld.load_class(): class 'BP_Axes' (from '" + AXES + "') does not derive from AStaticMeshActor",
              AXES, spear.AStaticMeshActor)
        with pytest.raises(spear.NotFoundError, match=re.escape("class 'BP_Never' is not registered")):
            game.spawn_actor(uclass="BP_Never")
        assert game.get_actor_count() == 0  # nothing half-made was left in the world


def test_generated_blueprint_classes_work_without_load_class(instance: spear.Instance) -> None:
    # The generator typed every asset under assets/blueprints as its parent class; using one as uclass=
    # loads it on first use, on either transport.
    game = instance.get_game()
    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.BP_Crate, location=spear.FVector(Z=2.0))
        assert isinstance(crate, spear.AStaticMeshActor)
        assert crate.GetClassName() == "BP_Crate"
        assert game.find_actors_by_class(uclass=spear.BP_Crate) == [crate]
        assert game.load_class(uclass=spear.AStaticMeshActor, name="BP_Crate") is spear.BP_Crate
        axes = game.spawn_actor(uclass=spear.BP_Axes)
        assert axes.GetClassName() == "BP_Axes" and len(axes.K2_GetComponents()) == 4
    with instance.end_frame():
        pass
    assert spear.BP_Crate.__doc__ and "crate" in spear.BP_Crate.__doc__


def test_a_scene_with_blueprint_actors_loads_its_blueprints(
        make_instance: Any, tmp_path: Path) -> None:
    scene = tmp_path / "crates.json"
    first = make_instance()
    game = first.get_game()
    with first.begin_frame():
        game.spawn_actor(uclass=spear.BP_Crate, name="Crate")
        game.save_scene(path=str(scene))
    with first.end_frame():
        pass
    first.close()
    saved = json.loads(scene.read_text())["actors"][0]
    assert saved["class"] == "BP_Crate" and saved["blueprint"].endswith("assets/blueprints/BP_Crate.json")
    # A new engine (over RPC: a new server process, which has never loaded the blueprint).
    second = make_instance(scene=scene)
    with second.begin_frame():
        crate = second.get_game().find_actor_by_name(name="Crate")
        assert crate is not None and crate.GetClassName() == "BP_Crate"
        second.get_game().save_scene(path=str(tmp_path / "again.json"))
    with second.end_frame():
        pass
    assert (tmp_path / "again.json").read_text() == scene.read_text()  # load then save: the same bytes


def test_blueprint_functions_are_typed_methods_of_its_objects(instance: spear.Instance) -> None:
    # BP_Crate declares Launch and Nudge (assets/blueprints/BP_Crate.json): composed of reflected calls, run by
    # the engine, called by attribute on the crate (typed in the stubs) or by name through call_function.
    game = instance.get_game()
    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.BP_Crate, location=spear.FVector(Z=1.0))
        plain = game.spawn_actor(uclass=spear.AStaticMeshActor)
    with instance.end_frame():
        pass
    with instance.begin_frame():
        thrown_from = crate.Launch(Speed=4.0)
        assert isinstance(thrown_from, spear.FVector)
        assert thrown_from == crate.GetActorLocation()
        assert instance.call_function(uobject=crate, function="Launch", args={}) == crate.GetActorLocation()
        crate.Nudge(Velocity=spear.FVector(X=2.0))
        assert hasattr(crate, "Nudge") and not hasattr(plain, "Nudge")
        with pytest.raises(spear.InvalidArgumentError, match=r"^BP_Crate\.Launch\(\): argument 'Speed' must be float"):
            crate.Launch(Speed="fast")  # type: ignore[arg-type]  # what mypy refuses, the engine refuses too
        # A call that does not fit the signature is Python's TypeError, in the words a C++ function's gives.
        with pytest.raises(TypeError, match=r"^BP_Crate\.Nudge\(\) missing 1 required keyword-only argument: 'Velocity'$"):
            crate.Nudge()  # type: ignore[call-arg]
        with pytest.raises(TypeError, match=r"^BP_Crate\.Launch\(\) got an unexpected keyword argument 'Sped'$"):
            crate.Launch(Sped=1.0)  # type: ignore[call-arg]
        with pytest.raises(TypeError, match=r"^BP_Crate\.Launch\(\) takes 1 positional argument but 2 were given$"):
            crate.Launch(1.0)  # type: ignore[misc]
        with pytest.raises(TypeError, match=r"^AActor\.SetActorLocation\(\) takes 1 positional argument but 2 were given$"):
            crate.SetActorLocation(spear.FVector())  # type: ignore[misc]  # the same words as a C++ function's
        with pytest.raises(spear.NotFoundError, match=r"class 'AStaticMeshActor' has no function 'Launch'"):
            instance.call_function(uobject=plain, function="Launch", args={})
    with instance.end_frame():
        velocity = crate.StaticMeshComponent.GetPhysicsLinearVelocity()
    # Launch set 5 m/s up (its default), Nudge added 2 m/s along X; one physics frame of gravity since.
    assert velocity.X == pytest.approx(2.0, abs=1e-6)
    assert 4.5 < velocity.Z < 5.0
    with pytest.raises(AttributeError, match=r"its blueprint's functions cannot be looked up now: .*outside a frame"):
        crate.Launch()


def crate_in_play(instance: spear.Instance) -> spear.BP_Crate:
    """A BP_Crate spawned 2 m up, one frame into play."""
    with instance.begin_frame():
        crate = instance.get_game().spawn_actor(uclass=spear.BP_Crate, location=spear.FVector(Z=2.0))
    with instance.end_frame():
        pass
    return crate


def test_blueprint_functions_queue_with_call_async(instance: spear.Instance) -> None:
    # Over RPC the call goes through the proxy's typed call, so call_async queues it and returns a Future.
    crate = crate_in_play(instance)
    with instance.begin_frame():
        future = crate.call_async.Launch(Speed=1.0)
        assert future.get() == crate.GetActorLocation()
    with instance.end_frame():
        pass


def test_blueprint_functions_are_sent_with_send_async(instance: spear.Instance) -> None:
    # Typed in BP_CrateSend; nobody waits for the result, and the call still runs in the frame.
    crate = crate_in_play(instance)
    with instance.begin_frame():
        crate.send_async.Nudge(Velocity=spear.FVector(X=3.0))
    with instance.end_frame():
        velocity = crate.StaticMeshComponent.GetPhysicsLinearVelocity()
    assert velocity.X == pytest.approx(3.0, abs=1e-6)


def test_blueprint_functions_are_checked_when_the_asset_loads(instance: spear.Instance, tmp_path: Path) -> None:
    path = write(tmp_path / "BP_BadCall.json", blueprint(
        "AStaticMeshActor", functions=[{"name": "Go", "body": [{"call": "StaticMeshComponent.Fly"}]}]))
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError, match=re.escape(
                f"blueprint '{path}': functions[0]: function 'Go': body[0]: 'StaticMeshComponent.Fly': class "
                "'UStaticMeshComponent' has no function 'Fly'")):
            instance.get_game().load_class(uclass=spear.AActor, name=path)
    with instance.end_frame():
        pass
