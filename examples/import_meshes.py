"""Import mesh files (OBJ, PLY, glTF: anything assimp reads), drop copies with physics, and render them.

Without --mesh a torus is written as an OBJ file first; give your own file to import it instead. A mesh
file collides as its convex hull when simulated (as its triangles when static). The copies fall onto a
floor for six simulated seconds; the final frame's colour and object-id images go into one PNG.

    PYTHONPATH=python /usr/bin/python3 examples/import_meshes.py [--mesh FILE] [--count 6] [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
import spear.images

SECONDS = 6  # simulated, at the engine's default 60 frames per second


def write_torus(path: Path, major: float = 0.3, minor: float = 0.1, rings: int = 32, sides: int = 16) -> Path:
    """A torus around Z as an OBJ file: (rings x sides) vertices, two triangles per quad."""
    lines: list[str] = []
    for i in range(rings):
        u = 2 * math.pi * i / rings
        for j in range(sides):
            v = 2 * math.pi * j / sides
            r = major + minor * math.cos(v)
            lines.append(f"v {r * math.cos(u):.6f} {r * math.sin(u):.6f} {minor * math.sin(v):.6f}")
    for i in range(rings):
        for j in range(sides):
            a = i * sides + j + 1  # OBJ indices start at 1
            b = (i + 1) % rings * sides + j + 1
            c = (i + 1) % rings * sides + (j + 1) % sides + 1
            d = i * sides + (j + 1) % sides + 1
            lines += [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--mesh", help="a mesh file to import (default: a torus written to out/torus.obj)")
    parser.add_argument("--count", type=int, default=6, help="how many copies to drop (default: %(default)s)")
    parser.add_argument("--out", default="out/import_meshes.png", help="where to write the images")
    parser.add_argument("--server", default=None, help="run the engine in a spear-server ('launch' or an address)")
    args = parser.parse_args()
    mesh_file = Path(args.mesh) if args.mesh else write_torus(Path(args.out).parent / "torus.obj")

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor", location=spear.FVector(Z=-0.5))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(8.0, 8.0, 1.0))
        floor.StaticMeshComponent.SetMobility(NewMobility=spear.EComponentMobility.Static)
        floor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Wood")
        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                               rotation=spear.FRotator(Pitch=-55.0, Yaw=-40.0))
        sun.LightComponent.Intensity = 4.0
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.SkyColor = spear.FLinearColor(0.6, 0.75, 1.0, 1.0)

        bodies: list[spear.AStaticMeshActor] = []
        for i in range(args.count):
            angle = 2 * math.pi * i / max(args.count, 1)
            body = game.spawn_actor(
                uclass=spear.AStaticMeshActor, name=f"Mesh{i}",
                location=spear.FVector(1.1 * math.cos(angle), 1.1 * math.sin(angle), 0.8 + 0.5 * i),
                rotation=spear.FRotator(Pitch=35.0 * i, Yaw=50.0 * i, Roll=20.0 * i))
            mesh = body.StaticMeshComponent
            # A file that is missing or cannot be read raises NotFoundError or InvalidArgumentError, naming it.
            try:
                mesh.SetStaticMesh(NewMesh=str(mesh_file))
            except (spear.NotFoundError, spear.InvalidArgumentError) as error:
                raise SystemExit(f"could not import {mesh_file}: {error}") from None
            mesh.SetMaterial(ElementIndex=0, Material="Gold" if i % 2 else "Plastic")
            mesh.SetSimulatePhysics(bSimulate=True)
            bodies.append(body)
        extent = bodies[0].GetActorBounds(bOnlyCollidingComponents=True).BoxExtent
        print(f"imported {mesh_file}: {2 * extent.X:.3f} x {2 * extent.Y:.3f} x {2 * extent.Z:.3f} m; "
              f"dropping {len(bodies)} copies")

        camera_actor = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                        location=spear.FVector(-2.8, -1.5, 2.0),
                                        rotation=spear.FRotator(Pitch=-32.0, Yaw=28.0))
        camera = camera_actor.CameraSensor
        camera.Width, camera.Height, camera.FOV = 480, 360, 60.0
        camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.ObjectIds]
    with instance.end_frame():
        pass

    for second in range(1, SECONDS + 1):
        instance.step(num_frames=60)
        print(f"  {second} s simulated")

    with instance.begin_frame():
        pass
    with instance.end_frame():
        pixels = camera.read_pixels()
        for body in bodies:
            state = "moving" if body.StaticMeshComponent.IsAnyRigidBodyAwake() else "at rest"
            print(f"{body.GetName()}: z = {body.GetActorLocation().Z:.3f} m, {state}")
        assert "final_color" in pixels and "object_ids" in pixels  # the modalities asked for
        seen = {info.Actor.GetName() for i in np.unique(pixels["object_ids"]) if i != 0
                for info in [camera.GetObjectIdInfo(ObjectId=int(i))] if info.Actor is not None}
        print(f"in view: {', '.join(sorted(seen))}")

    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet = np.concatenate([pixels["final_color"][..., :3], spear.images.id_colours(pixels["object_ids"])], axis=1)
    Image.fromarray(sheet).save(out)
    print(f"wrote {out.resolve()}")
    instance.close()


if __name__ == "__main__":
    main()
