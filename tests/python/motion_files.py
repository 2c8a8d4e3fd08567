"""An animated glTF file of a character handling objects, written for the tests of motion import: the built-in
humanoid's file with three rigid boxes added: "Case", which the walk clip moves by its own keys; "Held", a child
of the right hand bone (moved by the clip through the hand); and "Floor", which nothing moves."""

from __future__ import annotations

import json
import struct
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from make_humanoid import glb_bytes  # noqa: E402  (the humanoid's own GLB writer)
HUMANOID = ROOT / "assets" / "characters" / "humanoid.glb"

# The Case's keys in the walk clip, in glTF's axes (Y up): seconds and translations.
CASE_TIMES = (0.0, 0.55, 1.1)
CASE_KEYS = ((0.0, 1.0, 0.3), (0.5, 1.0, 0.3), (1.0, 1.2, 0.3))
HELD_OFFSET = (0.0, -0.12, 0.0)  # from the hand bone, in glTF's axes
FLOOR_AT = (0.0, -5.0, 0.0)


def _read_glb(path: Path) -> tuple[dict, bytearray]:  # type: ignore[type-arg]
    data = path.read_bytes()
    json_length = struct.unpack_from("<I", data, 12)[0]
    document = json.loads(data[20:20 + json_length])
    binary_at = 20 + json_length
    binary_length = struct.unpack_from("<I", data, binary_at)[0]
    return document, bytearray(data[binary_at + 8:binary_at + 8 + binary_length])


def _write_glb(path: Path, document: dict, binary: bytearray) -> None:  # type: ignore[type-arg]
    document["buffers"][0]["byteLength"] = len(binary)
    path.write_bytes(glb_bytes(document, binary))


def _accessor(document: dict, binary: bytearray, array: np.ndarray, kind: str,  # type: ignore[type-arg]
              component: int, target: int | None = None, bounds: bool = False) -> int:
    binary += b"\0" * (-len(binary) % 4)
    view = {"buffer": 0, "byteOffset": len(binary), "byteLength": array.nbytes}
    if target is not None:
        view["target"] = target
    binary += array.tobytes()
    document["bufferViews"].append(view)
    accessor = {"bufferView": len(document["bufferViews"]) - 1, "componentType": component,
                "count": int(array.shape[0]), "type": kind}
    if bounds:
        flat = array.reshape(array.shape[0], -1)
        accessor["min"], accessor["max"] = flat.min(axis=0).tolist(), flat.max(axis=0).tolist()
    document["accessors"].append(accessor)
    return len(document["accessors"]) - 1


def write_carry_glb(path: Path) -> Path:
    document, binary = _read_glb(HUMANOID)
    corners = np.array([[x, y, z] for x in (-0.1, 0.1) for y in (-0.1, 0.1) for z in (-0.1, 0.1)], np.float32)
    faces = np.array([0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                      2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3], np.uint16)
    positions = _accessor(document, binary, corners, "VEC3", 5126, 34962, bounds=True)
    indices = _accessor(document, binary, faces, "SCALAR", 5123, 34963)
    document["meshes"].append({"name": "box", "primitives": [
        {"attributes": {"POSITION": positions}, "indices": indices, "material": 0}]})
    box = len(document["meshes"]) - 1
    nodes = document["nodes"]
    hand = next(i for i, node in enumerate(nodes) if node.get("name") == "hand_r")
    nodes.append({"name": "Case", "mesh": box, "translation": list(CASE_KEYS[0])})
    case = len(nodes) - 1
    nodes.append({"name": "Held", "mesh": box, "translation": list(HELD_OFFSET)})
    nodes[hand].setdefault("children", []).append(len(nodes) - 1)
    nodes.append({"name": "Floor", "mesh": box, "translation": list(FLOOR_AT)})
    document["scenes"][0]["nodes"] += [case, len(nodes) - 1]
    walk = next(a for a in document["animations"] if a["name"] == "walk")
    times = _accessor(document, binary, np.array(CASE_TIMES, np.float32), "SCALAR", 5126, bounds=True)
    keys = _accessor(document, binary, np.array(CASE_KEYS, np.float32), "VEC3", 5126)
    walk["samplers"].append({"input": times, "output": keys, "interpolation": "LINEAR"})
    walk["channels"].append({"sampler": len(walk["samplers"]) - 1, "target": {"node": case, "path": "translation"}})
    _write_glb(path, document, binary)
    return path
