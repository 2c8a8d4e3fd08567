"""The generator's one error type: every rejected input names its file and line."""

from __future__ import annotations


class GeneratorError(Exception):
    """A header the generator cannot turn into bindings, with the place that caused it."""

    def __init__(self, file: str, line: int, message: str) -> None:
        super().__init__(f"{file}:{line}: error: {message}")
        self.file = file
        self.line = line
        self.message = message
