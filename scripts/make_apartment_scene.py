"""Writes assets/scenes/apartment.json, the built-in default scene: a furnished room of basic shapes with
textured PBR materials (scripts/make_apartment_textures.py).

The scene is described here as plain data, loaded into an engine and saved back through the reflection
registry, so the committed file is in canonical form (every property, declaration order): loading it
and saving it again gives the same bytes.

    PYTHONPATH=python /usr/bin/python3 scripts/make_apartment_scene.py
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

CUBE = "/Engine/BasicShapes/Cube"
SPHERE = "/Engine/BasicShapes/Sphere"
CYLINDER = "/Engine/BasicShapes/Cylinder"
PLANE = "/Engine/BasicShapes/Plane"


def vec(x: float, y: float, z: float) -> dict[str, float]:
    return {"X": x, "Y": y, "Z": z}


def mesh(name: str, shape: str, material: str, location: tuple[float, float, float],
         scale: tuple[float, float, float], *, parent: str | None = None, yaw: float = 0.0,
         static: bool = True, simulate: bool = False, mass: float = 1.0) -> dict[str, Any]:
    return {
        "name": name,
        "class": "UStaticMeshComponent",
        "attach_parent": parent,
        "properties": {
            "RelativeLocation": vec(*location),
            "RelativeRotation": {"Pitch": 0.0, "Yaw": yaw, "Roll": 0.0},
            "RelativeScale3D": vec(*scale),
            "Mobility": "Static" if static else "Movable",
            "bSimulatePhysics": simulate,
            "MassInKg": mass,
            "StaticMesh": shape,
            "Materials": [material],
        },
    }


def mesh_actor(name: str, parts: list[dict[str, Any]], tags: list[str]) -> dict[str, Any]:
    if len(parts) == 1:  # the part is the actor's own StaticMeshComponent (its root)
        return {"name": name, "class": "AStaticMeshActor", "properties": {"Tags": tags},
                "components": [dict(parts[0], name="StaticMeshComponent")]}
    # Several parts: an empty root on the floor below the first part, the parts attached to it.
    first = parts[0]["properties"]["RelativeLocation"]
    origin = (first["X"], first["Y"], 0.0)
    root = mesh("StaticMeshComponent", "", "", origin, (1.0, 1.0, 1.0))
    root["properties"]["Materials"] = []
    attached = []
    for part in parts:
        p = part["properties"]["RelativeLocation"]
        relative = vec(p["X"] - origin[0], p["Y"] - origin[1], p["Z"] - origin[2])
        attached.append(dict(part, attach_parent="StaticMeshComponent",
                             properties=dict(part["properties"], RelativeLocation=relative)))
    return {"name": name, "class": "AStaticMeshActor", "properties": {"Tags": tags},
            "components": [root, *attached]}


def light(name: str, cls: str, component_cls: str, location: tuple[float, float, float],
          properties: dict[str, Any]) -> dict[str, Any]:
    return {"name": name, "class": cls, "properties": {"Tags": ["light"]},
            "components": [{"name": "LightComponent", "class": component_cls, "attach_parent": None,
                            "properties": {"RelativeLocation": vec(*location), **properties}}]}


W, D, H, T = 6.0, 5.0, 2.8, 0.1  # room width (X), depth (Y), height, wall thickness
WOOD, PLASTER, FABRIC, METAL, TILE, OAK, CLOTH = (
    f"/Game/Materials/{m}" for m in
    ("M_WoodFloor", "M_Plaster", "M_Fabric", "M_Metal", "M_CeramicTile", "M_Oak", "M_Cloth"))


def material(rgb: tuple[float, float, float], roughness: float, metallic: float = 0.0) -> dict[str, Any]:
    return {"BaseColor": {"R": rgb[0], "G": rgb[1], "B": rgb[2], "A": 1.0}, "Roughness": roughness,
            "Metallic": metallic}


def textured(maps: str, size: float, *, roughness: bool = True) -> dict[str, Any]:
    """A material whose maps (scripts/make_apartment_textures.py: assets/textures/<maps>_*.png) carry its
    colour, and its roughness and ambient occlusion where they vary, repeating every `size` metres on every box, whatever its scale
    (FMaterialDesc.TextureSize). The factors are white and 1: the maps are the values."""
    found = {"BaseColorTexture": f"/Game/textures/{maps}_color.png",
             "NormalTexture": f"/Game/textures/{maps}_normal.png", "TextureSize": size}
    if roughness:  # one ORM map: occlusion in R, roughness in G, metallic in B
        found["RoughnessMetallicTexture"] = found["OcclusionTexture"] = f"/Game/textures/{maps}_rm.png"
    return {**material((1.0, 1.0, 1.0), 1.0 if roughness else 0.9), **found}


# The window in the north wall (the one the default camera faces): its span along Y and its sill and lintel
# heights. The afternoon sun (see "Sun" below) comes through it onto the floor and the table.
WINDOW_Y, WINDOW_Z = (-0.5, 1.1), (0.9, 2.2)


def north_wall_with_window() -> list[dict[str, Any]]:
    """The north wall as four slabs around an open window (below, above, and either side of it)."""
    x, (y0, y1), (z0, z1) = W / 2 + T / 2, WINDOW_Y, WINDOW_Z
    return [
        mesh("Below", CUBE, PLASTER, (x, 0, z0 / 2), (T, D, z0)),
        mesh("Above", CUBE, PLASTER, (x, 0, (z1 + H) / 2), (T, D, H - z1)),
        mesh("Left", CUBE, PLASTER, (x, (y1 + D / 2) / 2, (z0 + z1) / 2), (T, D / 2 - y1, z1 - z0)),
        mesh("Right", CUBE, PLASTER, (x, (y0 - D / 2) / 2, (z0 + z1) / 2), (T, y0 + D / 2, z1 - z0)),
    ]


def apartment() -> dict[str, Any]:
    # The scene carries its own materials: the renderer looks slot names up in an AMaterialLibrary.
    library = {"name": "Materials", "class": "AMaterialLibrary", "properties": {"Materials": {
        WOOD: textured("wood_floor", 1.2),  # 15 cm planks
        OAK: textured("wood_floor", 2.4),  # the furniture's boards: 30 cm
        PLASTER: textured("plaster", 1.0, roughness=False),
        FABRIC: textured("fabric", 0.15),  # a 5 mm weave
        CLOTH: material((0.2, 0.3, 0.45), 0.95),  # the round things' (a box projection would seam them)
        METAL: material((0.75, 0.75, 0.78), 0.3, metallic=1.0),
        TILE: textured("ceramic_tile", 0.6),  # 15 cm tiles
    }}, "components": []}
    actors = [
        library,
        mesh_actor("Floor", [mesh("Floor", CUBE, WOOD, (0, 0, -T / 2), (W, D, T))], ["structure"]),
        mesh_actor("Ceiling", [mesh("Ceiling", CUBE, PLASTER, (0, 0, H + T / 2), (W, D, T))], ["structure"]),
        mesh_actor("WallNorth", north_wall_with_window(), ["structure"]),
        mesh_actor("WallSouth", [mesh("W", CUBE, PLASTER, (-W / 2 - T / 2, 0, H / 2), (T, D, H))], ["structure"]),
        mesh_actor("WallWest", [mesh("W", CUBE, PLASTER, (0, D / 2 + T / 2, H / 2), (W, T, H))], ["structure"]),
        mesh_actor("WallEast", [mesh("W", CUBE, TILE, (0, -D / 2 - T / 2, H / 2), (W, T, H))], ["structure"]),
        mesh_actor("Rug", [mesh("Rug", PLANE, FABRIC, (0.5, 0.0, 0.001), (2.4, 1.6, 1.0))], ["decor"]),
        mesh_actor("TableTop", [mesh("Top", CUBE, OAK, (1.2, 1.0, 0.725), (1.4, 0.8, 0.05))], ["furniture"]),
        mesh_actor("TableLegs", [
            mesh("Leg0", CYLINDER, METAL, (0.6, 0.7, 0.35), (0.06, 0.06, 0.7)),
            mesh("Leg1", CYLINDER, METAL, (1.8, 0.7, 0.35), (0.06, 0.06, 0.7)),
            mesh("Leg2", CYLINDER, METAL, (0.6, 1.3, 0.35), (0.06, 0.06, 0.7)),
            mesh("Leg3", CYLINDER, METAL, (1.8, 1.3, 0.35), (0.06, 0.06, 0.7)),
        ], ["furniture"]),
        mesh_actor("Sofa", [
            mesh("Base", CUBE, FABRIC, (-1.8, -1.6, 0.225), (2.0, 0.9, 0.45)),
            mesh("Back", CUBE, FABRIC, (-1.8, -2.0, 0.65), (2.0, 0.15, 0.5)),
        ], ["furniture"]),
        mesh_actor("Shelf", [mesh("Shelf", CUBE, OAK, (2.75, -1.5, 0.9), (0.4, 1.2, 1.8))], ["furniture"]),
        mesh_actor("FloorLamp", [
            mesh("Pole", CYLINDER, METAL, (-2.6, 2.1, 0.8), (0.05, 0.05, 1.6)),
            mesh("Shade", SPHERE, CLOTH, (-2.6, 2.1, 1.7), (0.35, 0.35, 0.35)),
        ], ["furniture"]),
        mesh_actor("Ball", [mesh("Ball", SPHERE, CLOTH, (0.0, 0.5, 0.15), (0.3, 0.3, 0.3),
                                 static=False, simulate=True, mass=0.4)], ["prop"]),
        mesh_actor("Box", [mesh("Box", CUBE, OAK, (1.0, 1.0, 0.85), (0.2, 0.2, 0.2),
                                static=False, simulate=True, mass=1.5)], ["prop"]),
        # The sun shines in through the window (travelling towards -X), and the sky atmosphere is what the
        # window shows and the light of the sky that comes in with it.
        light("Sun", "ADirectionalLight", "UDirectionalLightComponent", (0.0, 0.0, 5.0),
              {"RelativeRotation": {"Pitch": -50.0, "Yaw": 200.0, "Roll": 0.0}, "Intensity": 25.0,
               "LightColor": {"R": 1.0, "G": 0.96875, "B": 0.875, "A": 1.0}}),
        light("CeilingLamp", "APointLight", "UPointLightComponent", (0.0, 0.0, H - 0.2),
              {"Intensity": 80.0, "AttenuationRadius": 8.0,
               "LightColor": {"R": 1.0, "G": 0.875, "B": 0.75, "A": 1.0}}),
        light("ReadingLamp", "APointLight", "UPointLightComponent", (-2.6, 2.1, 1.7),
              {"Intensity": 20.0, "AttenuationRadius": 4.0, "bCastShadows": False,
               "LightColor": {"R": 1.0, "G": 0.75, "B": 0.5, "A": 1.0}}),
        {"name": "Sky", "class": "ASkyAtmosphere", "properties": {"Tags": ["sky"]}, "components": [
            {"name": "SkyAtmosphereComponent", "class": "USkyAtmosphereComponent", "attach_parent": None,
             "properties": {"Turbidity": 3.0}}]},
    ]
    return {"format": "spear.scene", "version": 1, "actors": actors}


def main() -> None:
    out = ROOT / "assets" / "scenes" / "apartment.json"
    with tempfile.TemporaryDirectory() as tmp:
        draft = Path(tmp) / "apartment_draft.json"
        draft.write_text(json.dumps(apartment(), indent=2))
        # Saved inside the first frame, before any tick, so the props are where the draft put them.
        instance = spear.Instance(scene=draft)
        with instance.begin_frame():
            instance.get_game().save_scene(path=str(out))
        instance.close()
    print(f"wrote {out.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
