"""Replacing one benchmark's section of BENCHMARKS.md, kept between its own begin and end markers."""

from __future__ import annotations

from pathlib import Path


def replace_section(path: Path, begin: str, end: str, heading: str, section: str) -> None:
    """Puts `section` (which starts with `begin` and ends with `end`) in place of the text between the markers,
    or appends it under `heading` when the file has no such section yet."""
    text = path.read_text()
    if begin in text and end in text:
        text = text[:text.index(begin)] + section + text[text.index(end) + len(end):]
    else:
        text = text.rstrip("\n") + f"\n\n## {heading}\n\n" + section + "\n"
    path.write_text(text)
