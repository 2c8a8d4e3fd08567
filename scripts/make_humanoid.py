#!/usr/bin/env python3
"""Writes assets/characters/humanoid.glb: a rigged, low-poly humanoid with idle, walk and run clips.

Everything is computed here (no modelling tool, nothing downloaded), so the file is the project's own, CC0 1.0
like the rest of assets/. The body is a set of elliptical tubes along the bones (torso, arms, legs, feet, hands)
and an ellipsoid head, skinned to an 18-bone skeleton named as Unreal's mannequin names its bones (root, pelvis,
spine_01, ..., foot_r); near each joint a tube's vertices blend linearly between the two bones that meet there,
so elbows and knees bend without tearing. The clips are in place (no root motion): a character's movement moves
the actor, the clip moves the limbs.

Authored in spear's axes (Z up, X forward, Y left; a character faces +X, its left side is +Y) and written in
glTF's (Y up): (x, y, z) -> (x, z, -y), which spear's importer turns back.

    /usr/bin/python3 scripts/make_humanoid.py            # writes the file
    /usr/bin/python3 scripts/make_humanoid.py --check    # exit 1 unless the committed file is what it makes
"""

from __future__ import annotations

import argparse
import json
import math
import struct
import sys
from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parent.parent / "assets" / "characters" / "humanoid.glb"

# name, parent, joint position in the bind pose (metres, spear axes). Parents come before their children.
BONES: list[tuple[str, str | None, tuple[float, float, float]]] = [
    ("root", None, (0.0, 0.0, 0.0)),
    ("pelvis", "root", (0.0, 0.0, 0.95)),
    ("spine_01", "pelvis", (0.0, 0.0, 1.08)),
    ("spine_02", "spine_01", (0.0, 0.0, 1.25)),
    ("neck_01", "spine_02", (0.0, 0.0, 1.47)),
    ("head", "neck_01", (0.0, 0.0, 1.57)),
    ("upperarm_l", "spine_02", (0.0, 0.215, 1.43)),
    ("lowerarm_l", "upperarm_l", (0.0, 0.225, 1.15)),
    ("hand_l", "lowerarm_l", (0.0, 0.23, 0.90)),
    ("upperarm_r", "spine_02", (0.0, -0.215, 1.43)),
    ("lowerarm_r", "upperarm_r", (0.0, -0.225, 1.15)),
    ("hand_r", "lowerarm_r", (0.0, -0.23, 0.90)),
    ("thigh_l", "pelvis", (0.0, 0.10, 0.92)),
    ("calf_l", "thigh_l", (0.0, 0.10, 0.50)),
    ("foot_l", "calf_l", (0.0, 0.10, 0.09)),
    ("thigh_r", "pelvis", (0.0, -0.10, 0.92)),
    ("calf_r", "thigh_r", (0.0, -0.10, 0.50)),
    ("foot_r", "calf_r", (0.0, -0.10, 0.09)),
]
BONE_INDEX = {name: i for i, (name, _, _) in enumerate(BONES)}
JOINT = {name: np.array(position) for name, _, position in BONES}

# Linear base colours (glTF's baseColorFactor), one primitive each.
MATERIALS = [
    ("skin", (0.62, 0.40, 0.30)),
    ("shirt", (0.10, 0.22, 0.45)),
    ("trousers", (0.09, 0.09, 0.11)),
    ("shoes", (0.04, 0.03, 0.025)),
]
SKIN, SHIRT, TROUSERS, SHOES = range(4)

SIDES = 14  # vertices around each ring
BLEND = 0.06  # metres either side of a joint over which two bones share a tube's vertices


class Builder:
    """Vertices (position, normal, 4 bone indices, 4 weights) and triangles per material."""

    def __init__(self) -> None:
        self.positions: list[np.ndarray] = []
        self.normals: list[np.ndarray] = []
        self.joints: list[tuple[int, int, int, int]] = []
        self.weights: list[tuple[float, float, float, float]] = []
        self.triangles: list[list[tuple[int, int, int]]] = [[] for _ in MATERIALS]

    def vertex(self, position: np.ndarray, normal: np.ndarray, influences: dict[str, float]) -> int:
        pairs = sorted(((w, BONE_INDEX[b]) for b, w in influences.items() if w > 0.0), reverse=True)[:4]
        total = sum(w for w, _ in pairs)
        pairs += [(0.0, 0)] * (4 - len(pairs))
        self.positions.append(position)
        self.normals.append(normal / np.linalg.norm(normal))
        self.joints.append(tuple(j for _, j in pairs))  # type: ignore[arg-type]
        self.weights.append(tuple(w / total for w, _ in pairs))  # type: ignore[arg-type]
        return len(self.positions) - 1


def frame(direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors across `direction`: the first as near the lateral axis (Y) as it allows."""
    d = direction / np.linalg.norm(direction)
    side = np.array([0.0, 1.0, 0.0])
    if abs(d @ side) > 0.9:
        side = np.array([1.0, 0.0, 0.0])
    u = side - (side @ d) * d
    u /= np.linalg.norm(u)
    return u, np.cross(d, u)


def tube(b: Builder, path: list[np.ndarray], bones: list[str], radii: list[tuple[float, float]],
         material: "callable[[float], int]", start_bone: str | None = None, spacing: float = 0.03) -> None:
    """An elliptical tube along `path` (segment i owned by bones[i]), capped at both ends.

    radii[k] = (across the lateral axis, across the other) at path point k, linear between points.
    Within BLEND of an inner joint the vertices blend between the two segments' bones; with start_bone, the
    start blends half into it (a limb into the body part it hangs from). material(f) picks the material of
    the band at fraction f of the length.
    """
    lengths = [float(np.linalg.norm(path[i + 1] - path[i])) for i in range(len(path) - 1)]
    total = sum(lengths)
    joints_at = np.cumsum([0.0] + lengths)
    rings = max(2, int(round(total / spacing)) + 1)
    ring_starts: list[int] = []
    ring_materials: list[int] = []
    for r in range(rings):
        s = total * r / (rings - 1)
        seg = min(int(np.searchsorted(joints_at, s, side="right")) - 1, len(lengths) - 1)
        t = (s - joints_at[seg]) / lengths[seg]
        centre = path[seg] + t * (path[seg + 1] - path[seg])
        ry = radii[seg][0] + t * (radii[seg + 1][0] - radii[seg][0])
        rx = radii[seg][1] + t * (radii[seg + 1][1] - radii[seg][1])
        influences: dict[str, float] = {bones[seg]: 1.0}
        if seg + 1 < len(lengths) and joints_at[seg + 1] - s < BLEND:  # approaching the next joint
            w = 0.5 * (1.0 - (joints_at[seg + 1] - s) / BLEND)
            influences = {bones[seg]: 1.0 - w, bones[seg + 1]: w}
        elif seg > 0 and s - joints_at[seg] < BLEND:  # just past the previous joint
            w = 0.5 * (1.0 - (s - joints_at[seg]) / BLEND)
            influences = {bones[seg]: 1.0 - w, bones[seg - 1]: w}
        elif seg == 0 and start_bone is not None and s < BLEND:
            w = 0.5 * (1.0 - s / BLEND)
            influences = {bones[0]: 1.0 - w, start_bone: w}
        direction = path[seg + 1] - path[seg]
        u, v = frame(direction)
        ring_starts.append(len(b.positions))
        ring_materials.append(material(s / total))
        for k in range(SIDES):
            a = 2.0 * math.pi * k / SIDES
            offset = ry * math.cos(a) * u + rx * math.sin(a) * v
            normal = (math.cos(a) / ry) * u + (math.sin(a) / rx) * v
            b.vertex(centre + offset, normal, influences)
    for r in range(rings - 1):
        m = ring_materials[r]
        for k in range(SIDES):
            a0, a1 = ring_starts[r] + k, ring_starts[r] + (k + 1) % SIDES
            b0, b1 = ring_starts[r + 1] + k, ring_starts[r + 1] + (k + 1) % SIDES
            b.triangles[m] += [(a0, a1, b1), (a0, b1, b0)]
    # Caps: flat fans, their own vertices (a hard edge), wound to face out.
    for end, ring in ((0, 0), (1, rings - 1)):
        first = ring_starts[ring]
        direction = path[1] - path[0] if end == 0 else path[-1] - path[-2]
        outward = -direction if end == 0 else direction
        seg = 0 if end == 0 else len(lengths) - 1
        centre = path[0] if end == 0 else path[-1]
        influences = {bones[seg]: 1.0}
        if end == 0 and start_bone is not None:
            influences = {bones[0]: 0.5, start_bone: 0.5}
        c = b.vertex(centre, outward, influences)
        rim = [b.vertex(b.positions[first + k], outward, influences) for k in range(SIDES)]
        m = ring_materials[ring]
        for k in range(SIDES):
            i0, i1 = rim[k], rim[(k + 1) % SIDES]
            b.triangles[m].append((c, i1, i0) if end == 0 else (c, i0, i1))


def ellipsoid(b: Builder, centre: np.ndarray, radii: tuple[float, float, float], bone: str, material: int,
              stacks: int = 10) -> None:
    rx, ry, rz = radii
    start = len(b.positions)
    for i in range(stacks + 1):
        theta = math.pi * i / stacks
        for k in range(SIDES):
            phi = 2.0 * math.pi * k / SIDES
            d = np.array([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)])
            b.vertex(centre + d * np.array(radii), d / np.array([rx, ry, rz]), {bone: 1.0})
    for i in range(stacks):
        for k in range(SIDES):
            a0, a1 = start + i * SIDES + k, start + i * SIDES + (k + 1) % SIDES
            b0, b1 = a0 + SIDES, a1 + SIDES
            if i > 0:
                b.triangles[material].append((a0, b0, a1))
            if i < stacks - 1:
                b.triangles[material].append((a1, b0, b1))


def body() -> Builder:
    b = Builder()
    z = lambda h: np.array([0.0, 0.0, h])  # noqa: E731
    # Torso: hips to shoulders; trousers below the belt.
    tube(b, [z(0.84), JOINT["spine_01"], JOINT["spine_02"], z(1.47)], ["pelvis", "spine_01", "spine_02"],
         [(0.165, 0.11), (0.15, 0.10), (0.17, 0.11), (0.19, 0.10)],
         lambda f: TROUSERS if f < 0.22 else SHIRT)
    tube(b, [z(1.45), z(1.58)], ["neck_01"], [(0.05, 0.05), (0.05, 0.05)], lambda f: SKIN, "spine_02")
    ellipsoid(b, np.array([0.015, 0.0, 1.67]), (0.10, 0.085, 0.115), "head", SKIN)
    for side in ("l", "r"):
        # Arms: shoulder to wrist, short sleeves; hands.
        shoulder, elbow, wrist = JOINT[f"upperarm_{side}"], JOINT[f"lowerarm_{side}"], JOINT[f"hand_{side}"]
        tube(b, [shoulder + z(0.02), elbow, wrist], [f"upperarm_{side}", f"lowerarm_{side}"],
             [(0.05, 0.055), (0.04, 0.045), (0.032, 0.035)], lambda f: SHIRT if f < 0.3 else SKIN, "spine_02")
        tube(b, [wrist, wrist + np.array([0.0, 0.005 if side == "l" else -0.005, -0.16])], [f"hand_{side}"],
             [(0.022, 0.04), (0.018, 0.03)], lambda f: SKIN, f"lowerarm_{side}")
        # Legs: hip to ankle; feet forward from behind the ankle.
        hip, knee, ankle = JOINT[f"thigh_{side}"], JOINT[f"calf_{side}"], JOINT[f"foot_{side}"]
        tube(b, [hip + z(0.04), knee, ankle + z(0.03)], [f"thigh_{side}", f"calf_{side}"],
             [(0.08, 0.085), (0.055, 0.06), (0.045, 0.045)], lambda f: TROUSERS, "pelvis")
        tube(b, [ankle + np.array([-0.05, 0.0, -0.04]), ankle + np.array([0.17, 0.0, -0.06])], [f"foot_{side}"],
             [(0.048, 0.045), (0.045, 0.03)], lambda f: SHOES, f"calf_{side}")
    return b


def quat(axis: tuple[float, float, float], angle: float) -> np.ndarray:
    """(x, y, z, w) in glTF's axes for a rotation by `angle` about spear-axis `axis`."""
    a = np.array(axis, dtype=float)
    a /= np.linalg.norm(a)
    s = math.sin(angle / 2.0)
    return np.array([a[0] * s, a[2] * s, -a[1] * s, math.cos(angle / 2.0)])


def compose(*qs: np.ndarray) -> np.ndarray:
    """The product q1 q2 ... of (x, y, z, w) quaternions: q2 applied first."""
    out = np.array([0.0, 0.0, 0.0, 1.0])
    for q in qs:
        x1, y1, z1, w1 = out
        x2, y2, z2, w2 = q
        out = np.array([w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2])
    return out


LATERAL = (0.0, 1.0, 0.0)  # +angle swings a hanging limb backward, tilts the upper body forward
VERTICAL = (0.0, 0.0, 1.0)
FORWARD = (1.0, 0.0, 0.0)


def clip(period: float, keys: int, pose: "callable[[float], dict[str, tuple[np.ndarray, np.ndarray | None]]]"):
    """A looping clip: `keys` + 1 keys over `period` seconds (the last equals the first)."""
    times = [period * k / keys for k in range(keys + 1)]
    frames = [pose(2.0 * math.pi * (k % keys) / keys) for k in range(keys + 1)]
    return times, frames


def walk_like(stride: float, knee: float, arm: float, elbow: float, lean: float, bob: float):
    def pose(phi: float) -> dict[str, tuple[np.ndarray, np.ndarray | None]]:
        s = math.sin(phi)
        out: dict[str, tuple[np.ndarray, np.ndarray | None]] = {}
        pelvis_drop = -bob * (1.0 - math.cos(2.0 * phi)) / 2.0
        out["pelvis"] = (quat(VERTICAL, 0.08 * s), np.array([0.0, pelvis_drop, 0.0]))  # glTF axes: Y is up
        out["spine_01"] = (quat(LATERAL, lean), None)
        out["spine_02"] = (quat(VERTICAL, -0.12 * s), None)
        out["neck_01"] = (quat(LATERAL, -lean * 0.6), None)
        for side, sign in (("l", 1.0), ("r", -1.0)):
            ss = sign * s
            phase = phi if sign > 0 else phi + math.pi
            out[f"thigh_{side}"] = (quat(LATERAL, -stride * ss - lean), None)
            bend = knee * max(0.0, math.sin(phase - 2.2)) + 0.1 * knee
            out[f"calf_{side}"] = (quat(LATERAL, bend), None)
            out[f"foot_{side}"] = (quat(LATERAL, -0.25 * stride * math.cos(phase)), None)
            out[f"upperarm_{side}"] = (compose(quat(LATERAL, arm * ss), quat(FORWARD, sign * 0.06)), None)
            out[f"lowerarm_{side}"] = (quat(LATERAL, -elbow - 0.3 * elbow * max(0.0, -ss)), None)
        return out
    return pose


def idle(phi: float) -> dict[str, tuple[np.ndarray, np.ndarray | None]]:
    s, c = math.sin(phi), math.cos(phi)
    out: dict[str, tuple[np.ndarray, np.ndarray | None]] = {
        "spine_02": (quat(LATERAL, 0.02 * s), None),
        "neck_01": (quat(VERTICAL, 0.05 * math.sin(2.0 * phi)), None),
        "head": (quat(VERTICAL, 0.25 * s), None),
    }
    for side, sign in (("l", 1.0), ("r", -1.0)):
        out[f"upperarm_{side}"] = (compose(quat(LATERAL, 0.04 * c), quat(FORWARD, sign * 0.08)), None)
        out[f"lowerarm_{side}"] = (quat(LATERAL, -0.15 - 0.03 * s), None)
    return out


CLIPS = {
    "idle": clip(3.0, 24, idle),
    "walk": clip(1.1, 22, walk_like(stride=0.42, knee=0.9, arm=0.32, elbow=0.25, lean=0.04, bob=0.025)),
    "run": clip(0.7, 20, walk_like(stride=0.75, knee=1.6, arm=0.65, elbow=1.35, lean=0.22, bob=0.05)),
}


def gltf_vec(p: np.ndarray) -> list[float]:
    return [float(p[0]), float(p[2]), float(-p[1])]


def build() -> bytes:
    b = body()
    binary = bytearray()
    buffer_views: list[dict] = []
    accessors: list[dict] = []

    def add(array: np.ndarray, component: int, kind: str, target: int | None = None,
            bounds: bool = False) -> int:
        while len(binary) % 4:
            binary.append(0)
        data = array.tobytes()
        view = {"buffer": 0, "byteOffset": len(binary), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        binary.extend(data)
        buffer_views.append(view)
        accessor = {"bufferView": len(buffer_views) - 1, "componentType": component,
                    "count": int(array.shape[0]), "type": kind}
        if bounds:
            flat = array.reshape(array.shape[0], -1)
            accessor["min"] = [float(v) for v in flat.min(axis=0)]
            accessor["max"] = [float(v) for v in flat.max(axis=0)]
        accessors.append(accessor)
        return len(accessors) - 1

    FLOAT, USHORT, UINT = 5126, 5123, 5125
    positions = np.array([gltf_vec(p) for p in b.positions], dtype=np.float32)
    normals = np.array([gltf_vec(n) for n in b.normals], dtype=np.float32)
    # One set of vertex arrays per primitive (material), holding only the vertices its triangles use: assimp's
    # glTF importer (Debian's 5.2) gives wrong bone weights to the second and later primitives that share arrays.
    joints = np.array(b.joints, dtype=np.uint16)
    weights = np.array(b.weights, dtype=np.float32)
    primitives = []
    for m, triangles in enumerate(b.triangles):
        corners = np.array(triangles, dtype=np.uint32).reshape(-1)
        used, remapped = np.unique(corners, return_inverse=True)
        attributes = {
            "POSITION": add(positions[used], FLOAT, "VEC3", 34962, bounds=True),
            "NORMAL": add(normals[used], FLOAT, "VEC3", 34962),
            "JOINTS_0": add(joints[used], USHORT, "VEC4", 34962),
            "WEIGHTS_0": add(weights[used], FLOAT, "VEC4", 34962),
        }
        indices = add(remapped.astype(np.uint32), UINT, "SCALAR", 34963)
        primitives.append({"attributes": attributes, "indices": indices, "material": m})

    # Nodes: the bones (translation from the parent's joint, no rotation in the bind pose), then the mesh.
    nodes: list[dict] = []
    for name, parent, position in BONES:
        offset = np.array(position) - (JOINT[parent] if parent else np.zeros(3))
        nodes.append({"name": name, "translation": gltf_vec(offset)})
    for i, (name, parent, _) in enumerate(BONES):
        children = [j for j, (_, p, _) in enumerate(BONES) if p == name]
        if children:
            nodes[i]["children"] = children
    inverse_bind = []
    for name, _, position in BONES:
        m = np.eye(4)
        m[:3, 3] = -np.array(gltf_vec(np.array(position)))
        inverse_bind.append(m.T.reshape(-1))  # glTF matrices are column-major
    skin = {"name": "humanoid_skeleton", "joints": list(range(len(BONES))), "skeleton": 0,
            "inverseBindMatrices": add(np.array(inverse_bind, dtype=np.float32), FLOAT, "MAT4")}
    nodes.append({"name": "humanoid", "mesh": 0, "skin": 0})

    animations = []
    for clip_name, (times, frames) in CLIPS.items():
        samplers: list[dict] = []
        channels: list[dict] = []
        time_accessor = add(np.array(times, dtype=np.float32), FLOAT, "SCALAR", bounds=True)
        animated = sorted({bone for f in frames for bone in f}, key=BONE_INDEX.__getitem__)
        for bone in animated:
            rotations = np.array([f[bone][0] for f in frames], dtype=np.float32)
            samplers.append({"input": time_accessor, "output": add(rotations, FLOAT, "VEC4"),
                             "interpolation": "LINEAR"})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": BONE_INDEX[bone], "path": "rotation"}})
            if frames[0][bone][1] is not None:
                bind = np.array(gltf_vec(JOINT[bone] - JOINT[BONES[BONE_INDEX[bone]][1]]))
                translations = np.array([bind + f[bone][1] for f in frames], dtype=np.float32)
                samplers.append({"input": time_accessor, "output": add(translations, FLOAT, "VEC3"),
                                 "interpolation": "LINEAR"})
                channels.append({"sampler": len(samplers) - 1,
                                 "target": {"node": BONE_INDEX[bone], "path": "translation"}})
        animations.append({"name": clip_name, "samplers": samplers, "channels": channels})

    document = {
        "asset": {"version": "2.0", "generator": "spear scripts/make_humanoid.py", "copyright": "CC0 1.0"},
        "scene": 0,
        "scenes": [{"name": "humanoid", "nodes": [0, len(nodes) - 1]}],
        "nodes": nodes,
        "meshes": [{"name": "humanoid", "primitives": primitives}],
        "skins": [skin],
        "materials": [{"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0,
                                                               "roughnessFactor": 0.7}}
                      for name, rgb in MATERIALS],
        "animations": animations,
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [{"byteLength": len(binary)}],
    }
    return glb_bytes(document, binary)


def glb_bytes(document: dict, binary: bytearray) -> bytes:  # type: ignore[type-arg]
    """A binary glTF file of `document` (its JSON) and `binary` (its one buffer), each chunk padded to 4 bytes."""
    text = json.dumps(document, separators=(",", ":"), sort_keys=True).encode()
    text += b" " * (-len(text) % 4)
    binary = binary + b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text
            + struct.pack("<II", len(binary), 0x004E4942) + bytes(binary))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="only compare with the committed file")
    args = parser.parse_args()
    data = build()
    if args.check:
        same = OUT.exists() and OUT.read_bytes() == data
        print(f"{OUT}: {'up to date' if same else 'differs from what scripts/make_humanoid.py makes'}")
        return 0 if same else 1
    OUT.parent.mkdir(parents=True, exist_ok=True)
    temporary = OUT.with_suffix(".glb.tmp")
    temporary.write_bytes(data)
    temporary.replace(OUT)
    b = body()
    print(f"{OUT}: {len(b.positions)} vertices, {sum(len(t) for t in b.triangles)} triangles, {len(BONES)} bones, "
          f"clips {', '.join(f'{n} ({t[0][-1]:.2f} s)' for n, t in CLIPS.items())}; {len(data)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
