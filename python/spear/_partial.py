"""The dict a partial struct (SPSTRUCT(TypedDict, Partial), such as FCameraPixels) crosses to Python as, on
both transports: a plain dict whose missing keys say why they are missing. A key that is a field but absent
(a modality the camera does not render) is told apart from one that is no field at all (a misspelling)."""

from __future__ import annotations

from typing import Any


class PartialDict(dict[str, Any]):
    __slots__ = ("_struct",)

    def __init__(self, struct: type, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._struct = struct

    def __missing__(self, key: object) -> Any:
        name = self._struct.__name__
        fields = list(getattr(self._struct, "__annotations__", {}))
        # In the struct's field order, so that both transports say the same words.
        held = ", ".join(repr(k) for k in fields if k in self) or "nothing"
        if key in fields:
            about = " ".join((self._struct.__doc__ or "").split())
            reason = f" {about}" if about else ""
            raise KeyError(f"{key!r} is not in this {name} (it holds {held}).{reason}")
        raise KeyError(f"{key!r} is not a field of {name} (its fields: {', '.join(fields)})")

    def __reduce__(self) -> tuple[Any, ...]:
        return (PartialDict, (self._struct, dict(self)))
