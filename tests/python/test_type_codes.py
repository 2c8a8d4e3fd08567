"""Declared types travel as data: the code the registry holds for a member (C++, built by the generator's C++
spelling) is the code the generated type_codes.py holds for it (its Python spelling), under the name the
generator gives that code, for every property of the objects of a small scene; and results decode by them to
the same typed values on both transports."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

import spear
from codegen import typecodes
from spear._engine import type_codes
from spear._type_code import Kind, TypeCode


def _generator_code(code: TypeCode) -> typecodes.TypeCode:
    element = _generator_code(code.element) if code.element is not None else None
    return typecodes.TypeCode(code.kind, code.name, code.optional, element)


def _properties(obj: object) -> list[str]:
    """The reflected properties: those of the generated proxies."""
    return sorted({name for cls in type(obj).__mro__ if cls.__module__ == "spear._engine.rpc"
                   for name, member in vars(cls).items() if isinstance(member, property)})


@pytest.fixture(scope="module")
def server() -> Iterator[spear.Instance]:
    instance = spear.Instance(server="launch")
    yield instance
    instance.close()


def _scene_objects(instance: spear.Instance) -> list[Any]:
    game = instance.get_game()
    with instance.begin_frame():
        cube = game.spawn_actor(uclass=spear.AStaticMeshActor)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor)
        light = game.spawn_actor(uclass=spear.ASpotLight)
        objects = [cube, cube.StaticMeshComponent, camera, camera.CameraSensor, light, game]
    with instance.end_frame():
        pass
    return objects


def test_registry_and_type_codes_module_hold_the_same_codes(server: spear.Instance) -> None:
    connection = server._rpc_connection()
    checked = 0
    objects = _scene_objects(server)
    with server.begin_frame():
        for obj in objects:
            for name in _properties(obj):
                wire = connection.request("get_typed", object=obj, property=name)["type"]
                code = TypeCode.from_wire(wire)
                constant = typecodes.py_name(_generator_code(code))
                assert getattr(type_codes, constant, None) == code, f"{type(obj).__name__}.{name}: {constant}"
                checked += 1
    with server.end_frame():
        pass
    assert checked > 50


@pytest.mark.parametrize("owner, declared_by, function, args, result_type", [
    (0, "AActor", "GetActorBounds", {"bOnlyCollidingComponents": False}, "void"),
    # Object out-parameters may come back as None (nothing hit), as the result tuple says.
    (-1, "UWorld", "line_trace_single", {"start": spear.FVector(0, 0, 5), "end": spear.FVector(0, 0, 4)}, "bool"),
])
def test_out_parameter_types_match_the_result_tuple_fields(server: spear.Instance, owner: int, declared_by: str,
                                                           function: str, args: dict[str, Any],
                                                           result_type: Kind) -> None:
    target = _scene_objects(server)[owner]
    with server.begin_frame():
        reply = server._rpc_connection().request("call_typed", object=target, function=function, args=args)
    with server.end_frame():
        pass
    sent = {name: TypeCode.from_wire(wire) for name, wire in reply["out_types"].items()}
    assert sent == type_codes.FIELD_TYPES[f"{declared_by}.{function}Result"]
    assert TypeCode.from_wire(reply["type"]) == TypeCode(result_type)


def test_dynamic_results_are_typed_by_their_codes(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube")
        mesh = cube.StaticMeshComponent
        # A struct, an enum, a list of objects and a nullable object, read by name.
        assert isinstance(instance.get_property(uobject=mesh, path="RelativeLocation"), spear.FVector)
        assert instance.get_property(uobject=mesh, path="Mobility") is spear.EComponentMobility.Movable
        actors = instance.call_function(uobject=game, function="find_actors", args={})
        assert actors and all(isinstance(a, spear.AActor) for a in actors)
        bounds = instance.call_function(uobject=cube, function="GetActorBounds",
                                                  args={"bOnlyCollidingComponents": False})
        assert isinstance(bounds["Origin"], spear.FVector) and isinstance(bounds["BoxExtent"], spear.FVector)
    with instance.end_frame():
        pass
