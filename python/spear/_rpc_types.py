"""Typed decoding of RPC results: wire values become the same Python types the in-process API returns
(dataclasses, IntEnums, typed proxies), guided by the type spelling the generator recorded
("FVector", "list[AActor]", "AActor | None", "dict[str, float]")."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

from spear._rpc_proxy import ObjectProxy, proxy_class, RpcClient
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


def _api_lookup(name: str) -> Any:
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


def convert(value: Any, type_string: str, client: RpcClient) -> Any:
    t = type_string.strip()
    if t.endswith("| None"):
        t = t[: -len("| None")].strip()
    if value is None:
        return None
    if isinstance(value, ObjectRef):
        return _proxy(value, client, t if t.isidentifier() else "")
    if isinstance(value, ClassRef):
        found = _api_lookup(value.name)
        if found is None and value.native:
            from spear._blueprint import blueprint_class

            return blueprint_class(value.name, value.native)
        return found or value.name
    if t.startswith("list[") and isinstance(value, list):
        inner = t[5:-1]
        return [convert(item, inner, client) for item in value]
    if t.startswith("dict[str, ") and isinstance(value, dict):
        inner = t[10:-1]
        return {key: convert(item, inner, client) for key, item in value.items()}
    if isinstance(value, dict):
        cls = _api_lookup(t)
        if cls is not None and dataclasses.is_dataclass(cls):
            hints = {f.name: f.type for f in dataclasses.fields(cls)}
            return cls(**{k: convert(v, str(hints.get(k, "")), client) for k, v in value.items()})
        return {key: convert(item, "", client) for key, item in value.items()}
    if isinstance(value, int) and not isinstance(value, bool):
        cls = _api_lookup(t)
        if cls is not None and isinstance(cls, type) and issubclass(cls, int) and cls is not int:
            return cls(value)
    if isinstance(value, list):
        return [convert(item, "", client) for item in value]
    return value


def convert_result_tuple(value: dict[str, Any], result_tuple: Callable[..., Any], client: RpcClient) -> Any:
    # The generator's spellings; NamedTuple keeps them as ForwardRefs.
    hints = {k: getattr(t, "__forward_arg__", t) for k, t in result_tuple.__annotations__.items()}
    return result_tuple(**{k: convert(v, str(hints.get(k, "")), client) for k, v in value.items()})
