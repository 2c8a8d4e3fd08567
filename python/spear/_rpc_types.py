"""Typed decoding of RPC results: wire values become the same Python types the in-process API returns
(dataclasses, IntEnums, typed proxies), guided by the declared type the generator recorded as data
(spear._type_code.TypeCode)."""

from __future__ import annotations

import dataclasses
import sys
from typing import Any

from spear._partial import PartialDict
from spear._rpc_proxy import ObjectProxy, proxy_class, RpcClient
from spear._type_code import TypeCode
from spear._wire import ClassRef, ObjectRef

_api_modules: list[Any] = []


def _searched_modules() -> list[Any]:
    """The API modules results are looked up in: the engine's first, then loaded plugins' (add_api_module)."""
    if not _api_modules:
        from spear._engine import api

        _api_modules.append(api)
    return _api_modules


def add_api_module(module: Any) -> None:
    """Lets results name the classes, structs and enums of a loaded plugin's API."""
    if module not in _searched_modules():
        _api_modules.append(module)


def api_lookup(name: str) -> Any:
    """The class, struct or enum called `name` in the engine's API or a loaded plugin's, or None: what a class
    reference names on either transport (core/pybind/bridge.cpp's pythonClassFor() asks here too)."""
    for module in _searched_modules():
        found = getattr(module, name, None)
        if found is not None:
            return found
    return None


def _proxy(ref: ObjectRef, client: RpcClient, fallback: str) -> ObjectProxy:
    cls: type[ObjectProxy]
    try:
        cls = proxy_class(ref.class_name)
    except KeyError:  # a class this client has no proxy for (e.g. from a plugin): use the declared one
        if not fallback:
            raise
        cls = proxy_class(fallback)
    return cls(client, (ref.index, ref.generation))


def _field_types(cls: type) -> dict[str, TypeCode]:
    """The declared field types of a generated struct or result tuple (its API module's type_codes)."""
    table: dict[str, dict[str, TypeCode]] = getattr(sys.modules[cls.__module__], "_FIELD_TYPES", {})
    return table.get(cls.__qualname__, {})


def convert(value: Any, type: TypeCode | None, client: RpcClient) -> Any:
    """`value` as its declared `type` says (None: not recorded, the value alone decides)."""
    if value is None:
        return None
    if isinstance(value, ObjectRef):
        return _proxy(value, client, type.name if type is not None and type.kind == "object" else "")
    if isinstance(value, ClassRef):
        found = api_lookup(value.name)
        if found is None and value.native:
            from spear._blueprint import blueprint_class

            return blueprint_class(value.name, value.native)
        return found or value.name
    element = type.element if type is not None else None
    if isinstance(value, list):
        return [convert(item, element, client) for item in value]
    if isinstance(value, dict):
        cls = api_lookup(type.name) if type is not None and type.kind == "struct" else None
        if cls is not None:  # a dataclass, or a TypedDict (a dict with typed values)
            fields = _field_types(cls)
            items = {k: convert(v, fields.get(k), client) for k, v in value.items()}
            if dataclasses.is_dataclass(cls):
                return cls(**items)
            if getattr(cls, "__total__", True):
                return items
            return PartialDict(cls, items)  # a partial TypedDict: missing keys say why
        return {key: convert(item, element, client) for key, item in value.items()}
    if type is not None and type.kind == "enum" and isinstance(value, int) and not isinstance(value, bool):
        cls = api_lookup(type.name)
        if cls is not None:
            return cls(value)
    return value


def convert_result_tuple(value: dict[str, Any], result_tuple: type, client: RpcClient) -> Any:
    fields = _field_types(result_tuple)
    return result_tuple(**{k: convert(v, fields.get(k), client) for k, v in value.items()})
