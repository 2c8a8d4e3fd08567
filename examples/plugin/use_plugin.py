"""Uses the example plugin (examples/plugin): Fig. 8's SpFunc, a typed SPFUNCTION, and SpFuncs over a
1080p image, in-process or in a spear-server (--rpc). Build the plugin first:

    cmake -S examples/plugin -B build/plugin -G Ninja -Dspear_DIR=$PWD/build
    cmake --build build/plugin
    PYTHONPATH=python /usr/bin/python3 examples/plugin/use_plugin.py [--rpc]

The plugin's package is build/plugin/python/my_plugin (SPEAR_PLUGIN_DIR=<dir> to use another build);
mypy reads its stubs with MYPYPATH=build/plugin/python.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np

import spear

PLUGIN_DIR = Path(os.environ.get("SPEAR_PLUGIN_DIR", Path(__file__).resolve().parents[2] / "build/plugin/python"))
sys.path.insert(0, str(PLUGIN_DIR))

from my_plugin.api import AArrayTools, AMyActor, APointFilter  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rpc", action="store_true", help="run the engine in a spear-server process")
    args = parser.parse_args()

    instance = spear.Instance(server="launch" if args.rpc else None)
    plugin = instance.load_plugin("my_plugin")
    print(f"loaded plugin '{plugin.MODULE}' ({instance.transport})")
    game = instance.get_game()

    with instance.begin_frame():
        # Fig. 8: an actor whose SpFunc is registered by Initialize(). call_sp_func is the typed spelling of
        # my_actor.my_sp_func(arrays=...), which works too (untyped).
        my_actor = game.spawn_actor(uclass=AMyActor)
        my_actor.Initialize()
        return_values = my_actor.call_sp_func("my_sp_func", arrays={"input": np.array([1.0, 2.0, 3.0])})
        print("my_sp_func:", return_values["arrays"]["output"])
        my_actor.Terminate()
        game.destroy_actor(actor=my_actor)

        # A typed SPFUNCTION: named, dtype-checked arrays in, a TypedDict of arrays out.
        points_filter = game.spawn_actor(uclass=APointFilter)
        points = np.random.default_rng(7).uniform(-1.0, 1.0, size=(10_000, 3)).astype(np.float32)
        inside = points_filter.Filter(Points=points, Center=spear.FVector(0.0, 0.0, 0.0), Radius=0.5)
        expected = np.flatnonzero(np.linalg.norm(points, axis=1) <= 0.5)
        assert np.array_equal(inside["Indices"], expected)
        print(f"Filter: {len(inside['Indices'])} of {len(points)} points within 0.5 m (numpy agrees)")

        # SpFuncs over a 1920x1080 RGBA image (through shared memory over RPC).
        tools = game.spawn_actor(uclass=AArrayTools)
        image = np.random.default_rng(1).integers(0, 256, size=(1080, 1920, 4), dtype=np.uint8)
        inverted = tools.call_sp_func("invert", arrays={"image": image})
        assert np.array_equal(inverted["arrays"]["image"], 255 - image)
        print("invert:", inverted["info"])
        print("actors of plugin classes:", game.find_actors_by_class(uclass=spear.AActor))
        game.destroy_actor(actor=points_filter)
        game.destroy_actor(actor=tools)
    with instance.end_frame():
        pass

    instance.unload_plugin("my_plugin")
    print("unloaded plugin 'my_plugin'")
    instance.close()


if __name__ == "__main__":
    main()
