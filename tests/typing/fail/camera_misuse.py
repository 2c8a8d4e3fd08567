"""Negative typing case: a misspelled modality is a type error, as a dict key and as an enum member."""

from __future__ import annotations

import spear


def misuse(camera: spear.UCameraSensorComponent) -> None:
    px = camera.read_pixels()
    px["dept"]  # E: TypedDict "FCameraPixels" has no key "dept"  [typeddict-item]
    camera.Modalities = [spear.ECameraModality.Dept]  # E: "Type[ECameraModality]" has no attribute "Dept"  [attr-defined]
    camera.Modalities = ["depth"]  # E: List item 0 has incompatible type "str"; expected "ECameraModality"  [list-item]
    camera.CameraSensor  # E: "UCameraSensorComponent" has no attribute "CameraSensor"  [attr-defined]
