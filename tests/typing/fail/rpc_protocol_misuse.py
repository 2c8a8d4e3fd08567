"""Negative typing case: requests of the RPC client that the protocol (core/rpc/protocol.json) does not have.
The client's request(op, **fields) is typed per op from that one source, as the server's names are; every
marked line must be rejected by mypy --strict (`# E:`) and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

from spear._protocol import message
from spear._rpc_client import RpcConnection


def misuse(connection: RpcConnection) -> None:
    connection.request("get", object=None, propery="Tags")  # E: No overload variant of "request" of "Requests" matches argument types "str", "None", "str"  [call-overload]  # P: reportCallIssue: No overloads for "request" match the provided arguments / Argument types: (Literal['get'], None, Literal['Tags'])
    connection.request("frame", action="begn")  # E: No overload variant of "request" of "Requests" matches argument types "str", "str"  [call-overload]  # P: reportArgumentType: Argument of type "Literal['begn']" cannot be assigned to parameter "action" of type "FrameAction" in function "request" / Type "Literal['begn']" is not assignable to type "FrameAction" / "Literal['begn']" is not assignable to type "Literal['begin']" / "Literal['begn']" is not assignable to type "Literal['execute']" / "Literal['begn']" is not assignable to type "Literal['begin_end']" / "Literal['begn']" is not assignable to type "Literal['end']" / "Literal['begn']" is not assignable to type "Literal['abort']" / "Literal['begn']" is not assignable to type "Literal['state']"  # P: reportCallIssue: No overloads for "request" match the provided arguments
    connection.request("spawn", uclass="AActor")  # E: No overload variant of "request" of "Requests" matches argument types "str", "str"  [call-overload]  # P: reportCallIssue: No overloads for "request" match the provided arguments / Argument types: (Literal['spawn'], Literal['AActor'])
    message({"op": "worlds", "action": "list", "nmae": "x"})  # E: Argument 1 to "message" has incompatible type "Dict[str, str]"; expected "Union[HelloMessage, ShmProofMessage, WorldMessage, WorldsMessage, FrameMessage, InspectMessage, CallMessage, CallTypedMessage, GetMessage, GetTypedMessage, SetMessage, LoadPluginMessage, UnloadPluginMessage, SpFuncMessage, SpFuncNamesMessage, IsValidMessage, DescribeMessage, EchoMessage, ShutdownMessage, BatchMessage]"  [arg-type]  # P: reportArgumentType: Argument of type "dict[str, str]" cannot be assigned to parameter "checked" of type "Message" in function "message" / Type "dict[str, str]" is not assignable to type "Message" / "dict[str, str]" is not assignable to "HelloMessage" / "dict[str, str]" is not assignable to "ShmProofMessage" / "dict[str, str]" is not assignable to "WorldMessage" / "dict[str, str]" is not assignable to "WorldsMessage" / "dict[str, str]" is not assignable to "FrameMessage" / "dict[str, str]" is not assignable to "InspectMessage" / "dict[str, str]" is not assignable to "CallMessage" / ...
