"""One benchmark's section of BENCHMARKS.md: the command that reproduces it and its results, kept between
markers of its own (<!-- name:begin --> ... <!-- name:end -->) so that a rerun replaces exactly it."""

from __future__ import annotations

from pathlib import Path


def markers(name: str) -> tuple[str, str]:
    return f"<!-- {name}:begin -->", f"<!-- {name}:end -->"


def section(name: str, command: str, body: list[str]) -> str:
    """The section's text: its begin marker, the command in a bash block, a blank line, `body`, its end marker."""
    begin, end = markers(name)
    return "\n".join([begin, "```bash", command, "```", "", *body, end])


def replace_section(path: Path, name: str, heading: str, text: str) -> None:
    """Puts `text` (a section() of `name`) in place of the file's section of that name, or appends it under
    `heading` when the file has none yet."""
    begin, end = markers(name)
    document = path.read_text()
    if begin in document and end in document:
        document = document[:document.index(begin)] + text + document[document.index(end) + len(end):]
    else:
        document = document.rstrip("\n") + f"\n\n## {heading}\n\n" + text + "\n"
    path.write_text(document)
