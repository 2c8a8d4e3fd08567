"""Procedural generation: the time UPCGComponent.Generate() takes to lay out and spawn N buildings (city blocks of
one building each, no roads), and the navigation mesh build over the generated city, in-process.

    PYTHONPATH=python /usr/bin/python3 bench/bench_procedural.py [--sizes 40 80 160]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--sizes", type=float, nargs="+", default=[40.0, 80.0, 160.0], help="city sides in metres")
    args = parser.parse_args()
    print("| city side | buildings | Generate() | per building | navmesh tiles | navmesh build |")
    print("|---:|---:|---:|---:|---:|---:|")
    for side in args.sizes:
        instance = spear.Instance()
        game = instance.get_game()
        with instance.begin_frame():
            ground = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=-0.5))
            ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
            ground.SetActorScale3D(NewScale3D=spear.FVector(side + 10.0, side + 10.0, 1.0))
            city = game.spawn_actor(uclass=spear.APCGVolume, name="City", location=spear.FVector(Z=10.0))
            city.BoxComponent.SetBoxExtent(InBoxExtent=spear.FVector(side / 2, side / 2, 12.0))
            pcg = city.PCGComponent
            pcg.GenerationMode = spear.EPCGGenerationMode.CityBlocks
            pcg.BlockSize, pcg.StreetWidth, pcg.LotsPerSide = 4.0, 3.0, 1
            pcg.Generate()
            count, seconds = len(pcg.GetGeneratedActors()), pcg.GetLastGenerationSeconds()
            nav = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game).GetDefaultNavDataInstance()
            tiles, build = nav.GetNumTiles(), nav.GetLastBuildSeconds()
        with instance.end_frame():
            pass
        instance.close()
        print(f"| {side:.0f} m | {count} | {seconds * 1e3:.0f} ms | {seconds / count * 1e6:.0f} µs | {tiles} "
              f"| {build * 1e3:.0f} ms |", flush=True)


if __name__ == "__main__":
    main()
