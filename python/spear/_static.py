"""Static functions of engine classes, called on the class as in C++:

    pc = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)

A static SPFUNCTION has no object to say which engine should run it, so the call goes where its
arguments live: the engine of the first engine-object argument (the WorldContextObject of UE's
function libraries; the first element of a list argument counts too), else the only open spear.Instance. Called on an object (`proxy.Fn(...)`), it
goes to that object's engine. The types are in api.pyi (a @staticmethod); this is the runtime.
"""

from __future__ import annotations

from typing import Any

from spear import errors
from spear._blueprint import check_call
from spear._object import SpObject
from spear._type_code import TypeCode


class StaticFunction:
    """A class attribute of the typed API standing for one static function of an engine class."""

    __slots__ = ("_class_name", "_function", "_result_type", "_params", "_result_tuple_name")

    def __init__(self, class_name: str, function: str, result_type: TypeCode, params: tuple[tuple[str, bool], ...],
                 result_tuple_name: str | None = None) -> None:
        self._class_name = class_name
        self._function = function
        self._result_type = result_type
        self._params = params  # (name, required) of each parameter, all keyword-only
        self._result_tuple_name = result_tuple_name

    @property
    def context(self) -> str:
        return f"{self._class_name}.{self._function}()"

    def __get__(self, obj: object, owner: type | None = None) -> Any:
        from spear._rpc_proxy import ObjectProxy

        def call(*args: Any, **kwargs: Any) -> Any:
            # Refused here, before routing, so that both transports raise Python's own TypeError (the
            # server would answer a missing argument with InvalidArgumentError).
            check_call(self.context, args, kwargs, self._params, method=False)
            if isinstance(obj, ObjectProxy):
                return self._call_rpc(obj._sp_client, owner, kwargs)
            return self._call_routed(owner, kwargs)

        call.__name__ = self._function
        call.__qualname__ = f"{self._class_name}.{self._function}"
        return call

    def _call_routed(self, owner: type | None, kwargs: dict[str, Any]) -> Any:
        from spear import _inprocess
        from spear._rpc_proxy import ObjectProxy

        for argument in kwargs.values():
            value = argument[0] if isinstance(argument, (list, tuple)) and argument else argument
            if isinstance(value, ObjectProxy):
                return self._call_rpc(value._sp_client, owner, kwargs)
            if isinstance(value, SpObject):
                return self._call_native(_inprocess.native_class(self._class_name), kwargs)
        from spear import instance

        connection = instance.only_open_instance(self.context)._rpc_connection()
        if connection is not None:
            return self._call_rpc(connection, owner, kwargs)
        return self._call_native(_inprocess.native_class(self._class_name), kwargs)

    def _call_rpc(self, client: Any, owner: type | None, kwargs: dict[str, Any]) -> Any:
        result_tuple = getattr(owner, self._result_tuple_name) if self._result_tuple_name and owner else None
        return client.call_static(self._class_name, self._function, kwargs, self._result_type, self.context,
                                  result_tuple)

    def _call_native(self, native_class: Any, kwargs: dict[str, Any]) -> Any:
        if native_class is None:
            raise errors.NotFoundError(f"{self.context}: class '{self._class_name}' is not loaded in this process")
        return getattr(native_class, self._function)(**kwargs)
