"""Base of the generated RPC proxy classes (spear._engine.rpc).

A proxy holds a handle and the client that owns it; every reflected call becomes one request through
that client. The client (the transport) implements the RpcClient protocol below.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from spear import _spfunc
from spear._object import SpObject
from spear._type_code import TypeCode


class _Default:
    """Marks an argument left at its default: it is not sent, and the server applies the C++ default."""

    def __repr__(self) -> str:
        return "<default>"


DEFAULT: Any = _Default()


class RpcClient(Protocol):
    def call(self, handle: tuple[int, int], function: str, args: dict[str, Any], result_type: TypeCode,
             context: str = "", result_tuple: Any = None) -> Any: ...

    def call_static(self, class_name: str, function: str, args: dict[str, Any], result_type: TypeCode,
                    context: str = "", result_tuple: Any = None) -> Any: ...

    def get_property(self, handle: tuple[int, int], name: str, result_type: TypeCode, context: str = "") -> Any: ...

    def set_property(self, handle: tuple[int, int], name: str, value: Any, context: str = "") -> None: ...

    def is_valid(self, handle: tuple[int, int]) -> bool: ...

    def call_sp_func(self, handle: tuple[int, int], name: str, arrays: dict[str, Any], unreal_objs: dict[str, str],
                     info: str, finish: Callable[[Any], Any], context: str) -> Any: ...

    def sp_func_names(self, handle: tuple[int, int], context: str) -> list[str]: ...

    def same_engine(self, other: object) -> bool:
        """Whether `other` (a client) reaches the engine this one does: their handles mean the same objects."""
        ...

    def deferred(self, discard: bool) -> Any:
        """A context in which calls are queued and return Futures."""
        ...


_PROXIES: dict[str, type[ObjectProxy]] = {}


def register_proxy(cls: type[ObjectProxy]) -> None:
    """Records the proxy class for its engine class name, so that results can be wrapped by class."""
    _PROXIES[cls.__sp_class__] = cls


def proxy_class(class_name: str) -> type[ObjectProxy]:
    return _PROXIES[class_name]


class ObjectProxy(SpObject):
    """An engine object on the other side of an RPC connection."""

    __slots__ = ("_sp_client", "_sp_handle")

    def __init__(self, client: RpcClient, handle: tuple[int, int]) -> None:
        self._sp_client = client
        self._sp_handle = handle

    def __eq__(self, other: object) -> bool:
        # The same engine (several connections may reach one server), not necessarily the same connection.
        return (isinstance(other, ObjectProxy) and other._sp_handle == self._sp_handle
                and self._sp_client.same_engine(other._sp_client))

    def __hash__(self) -> int:
        return hash(self._sp_handle)

    def __repr__(self) -> str:
        state = "" if self.is_valid() else " (destroyed)"
        return f"<{type(self).__name__}{state} {self._sp_handle[0]}:{self._sp_handle[1]} (remote)>"

    def is_valid(self) -> bool:
        """True while the engine object exists; False once it was destroyed."""
        return self._sp_client.is_valid(self._sp_handle)

    @property
    def call_async(self) -> Any:
        """The same functions, queued: each returns a Future resolved when the queue is sent."""
        return _DeferredCaller(self, discard=False)

    @property
    def send_async(self) -> Any:
        """The same functions, queued, results discarded (fire and forget)."""
        return _DeferredCaller(self, discard=True)

    # `owner` is the class that declares the member: messages then read as in-process ("AActor.GetName()").

    def _sp_call(self, owner: str, function: str, args: dict[str, Any], result_type: TypeCode,
                 result_tuple: Any = None) -> Any:
        sent = {name: value for name, value in args.items() if value is not DEFAULT}
        return self._sp_client.call(self._sp_handle, function, sent, result_type, f"{owner}.{function}()", result_tuple)

    def _sp_get(self, owner: str, name: str, result_type: TypeCode) -> Any:
        return self._sp_client.get_property(self._sp_handle, name, result_type, f"{owner}.{name}")

    def _sp_set(self, owner: str, name: str, value: Any) -> None:
        self._sp_client.set_property(self._sp_handle, name, value, f"{owner}.{name}")

    # SpFuncs (spear._spfunc): the typed call, the names, and Fig. 8's attribute form.
    call_sp_func = _spfunc.call_sp_func
    get_sp_func_names = _spfunc.get_sp_func_names
    __getattr__ = _spfunc.sp_func_getattr

    def _sp_call_sp_func(self, name: str, arrays: dict[str, Any], unreal_objs: dict[str, str], info: str,
                         finish: Callable[[Any], Any], context: str) -> Any:
        return self._sp_client.call_sp_func(self._sp_handle, name, arrays, unreal_objs, info, finish, context)

    def _sp_get_sp_func_names(self, context: str) -> list[str]:
        return self._sp_client.sp_func_names(self._sp_handle, context)


class _DeferredCaller:
    """obj.call_async / obj.send_async over RPC: its attributes are the object's functions, queued."""

    __slots__ = ("_proxy", "_discard")

    def __init__(self, proxy: ObjectProxy, discard: bool) -> None:
        self._proxy = proxy
        self._discard = discard

    # __getattribute__ rather than __getattr__: every name is a function of the object, and the failed normal
    # lookup that precedes __getattr__ costs as much as the rest of queueing a call.
    def __getattribute__(self, name: str) -> Any:
        if name.startswith("__"):
            return object.__getattribute__(self, name)
        proxy = _caller_proxy(self)
        method = getattr(proxy, name)
        client = proxy._sp_client
        discard = _caller_discard(self)

        def call(**kwargs: Any) -> Any:
            with client.deferred(discard):
                return method(**kwargs)

        return call


# The slots' descriptors, read without going through __getattribute__.
_caller_proxy: Callable[[_DeferredCaller], ObjectProxy] = vars(_DeferredCaller)["_proxy"].__get__
_caller_discard: Callable[[_DeferredCaller], bool] = vars(_DeferredCaller)["_discard"].__get__
