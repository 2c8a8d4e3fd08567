"""Every example runs as its docstring says, on both transports where it takes --server (the plugin,
MuJoCo and MCP examples have their own tests: test_plugins.py, test_mujoco_interop.py, test_mcp_server.py)."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

ROOT = Path(__file__).resolve().parents[2]
TRANSPORTS = {"inprocess": [], "rpc": ["--server", "launch"]}


def run_example(name: str, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(ROOT / "examples" / name), *args], capture_output=True, text=True,
                          timeout=300, cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT / "python")})


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_import_meshes_drops_and_renders_the_imported_copies(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "sheet.png"
    result = run_example("import_meshes.py", "--count", "3", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert f"imported {tmp_path / 'torus.obj'}: 0.800 x 0.800 x 0.200 m; dropping 3 copies" in result.stdout
    resting = [line for line in result.stdout.splitlines() if line.startswith("Mesh")]
    assert len(resting) == 3
    for line in resting:  # a torus 0.2 m thick lies flat at z = 0.1 or leans on another
        assert 0.09 <= float(line.split("z = ")[1].split(" m")[0]) <= 0.5, line
    assert "in view: Floor, Mesh0, Mesh1, Mesh2" in result.stdout
    assert Image.open(out).size == (960, 360)


def test_import_meshes_reports_a_file_it_cannot_read(tmp_path: Path) -> None:
    result = run_example("import_meshes.py", "--mesh", str(tmp_path / "missing.obj"), "--out", str(tmp_path / "x.png"))
    assert result.returncode != 0
    assert f"could not import {tmp_path / 'missing.obj'}" in result.stderr


@pytest.mark.parametrize("transport", TRANSPORTS)
@pytest.mark.parametrize("physics", ["bullet", "mujoco"])
def test_cosim_benchmark_prints_table3_and_lands_images(transport: str, physics: str, tmp_path: Path) -> None:
    if physics == "mujoco" and not (ROOT / "build" / "python" / "mujoco_interop").is_dir():
        pytest.skip("the mujoco_interop plugin is built only when Debian's libmujoco-dev is installed")
    results = tmp_path / "results.json"
    result = run_example("cosim_benchmark.py", "--objects", "4", "--views", "1", "2", "--width", "96", "--height",
                         "64", "--frames", "3", "--physics", physics, "--json", str(results), "--png",
                         str(tmp_path), "--breakdown", *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    lines = result.stdout.splitlines()
    head = lines.index("| cell | frame | calls | tick | read | end | physics | rendering | gpu shadow | gpu surface "
                       "| readback |")
    for row, cell in zip(lines[head + 2:head + 4], ("N=4, 1 view", "N=4, 2 views")):
        values = [float(v) for v in row.strip("| ").split(" | ")[1:]]
        assert row.startswith(f"| {cell} | ") and len(values) == 10 and min(values) >= 0.0, row
        assert sum(values[1:5]) <= values[0] * 1.05  # the phases split the frame
    assert lines[1] == "| simulator | N=4, 1 view | N=4, 2 views |"
    assert lines[3].startswith(f"| spear ({'rpc' if transport == 'rpc' else 'inprocess'}, {physics}, 96x64) | ")
    assert lines[4].startswith("| UnrealCV+ (paper, RTX 4090 laptop) | 279.4 | 528.5 |")
    assert "3/3 frames" in result.stderr  # progress on the long runs
    cells = json.loads(results.read_text())
    assert [(c["objects"], c["views"], c["frames"]) for c in cells] == [(4, 1, 3), (4, 2, 3)]
    assert all(c["ms_per_frame"] > 0 for c in cells)
    for views in (1, 2):
        image = Image.open(tmp_path / f"cosim_n4_v{views}.png")
        assert image.size == (96, 64)
        assert len(set(image.getdata())) > 20  # ground, sky, shaded objects and their shadows


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_getting_started_spawns_queries_and_destroys(transport: str) -> None:
    result = run_example("getting_started.py", *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "after destroying Marker:" in result.stdout
    assert "using the destroyed actor raises StaleObjectError:" in result.stdout


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_physics_and_input_rests_the_crate_on_the_table(transport: str) -> None:
    result = run_example("physics_and_input.py", *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    resting = [line for line in result.stdout.splitlines() if line.startswith("crate rests at z = ")]
    assert len(resting) == 1, result.stdout
    assert 0.88 <= float(resting[0].split("z = ")[1].split(" m")[0]) <= 0.92  # table top 0.75 m + 0.15 m


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_editor_play_copies_the_world_and_saves_the_edit(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "edited.json"
    result = run_example("editor_play.py", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "ball present: True" in result.stdout  # destroyed in the game copy only
    assert json.loads(out.read_text())  # written whole


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_blueprints_spawn_and_settle(transport: str) -> None:
    result = run_example("blueprints.py", *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "came to rest at Z = " in result.stdout
    assert "Walker is a BP_Walker: 18 bones, playing 'walk'" in result.stdout
    assert "Walker runs now ('run', 0.70 s a cycle, at 1.5x)" in result.stdout


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_render_image_writes_the_contact_sheet(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "sheet.png"
    result = run_example("render_image.py", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "object ids visible:" in result.stdout
    image = Image.open(out)
    assert image.size[0] > 0 and len(set(image.convert("RGB").getdata())) > 100


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_import_motion_plays_a_sequence_with_an_object_and_renders_body_parts(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "motion.png"
    result = run_example("import_motion.py", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert ("/Game/motions/carry_case.npz: 60 frames at 30 fps (1.97 s), 18 bones of /Game/characters/humanoid.glb, "
            "objects: Case") in result.stdout
    assert "frame 60/60 (" in result.stdout
    parts = result.stdout.split("body parts seen: ")[1].splitlines()[0].split(", ")
    assert {"head", "pelvis", "thigh_l", "thigh_r", "foot_l", "foot_r"} <= set(parts), parts
    image = Image.open(out)
    assert image.size == (3 * 320, 4 * (240 + 16))
    assert len(set(image.convert("RGB").getdata())) > 1000  # rendered frames, not blank ones


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_import_motion_reads_an_animated_gltf_file(transport: str, tmp_path: Path) -> None:
    from motion_files import write_carry_glb

    gltf = write_carry_glb(tmp_path / "carry.glb")
    result = run_example("import_motion.py", "--motion", str(gltf), "--animation", "walk", "--fps", "20",
                         "--object-mesh", "Case=/Engine/BasicShapes/Cube",
                         "--object-mesh", "Held=/Engine/BasicShapes/Sphere",
                         "--out", str(tmp_path / "motion.png"), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert f"{gltf}: 23 frames at 20 fps (1.10 s), 18 bones of {gltf}, objects: " in result.stdout
    assert "frame 23/23 (" in result.stdout
    refused = run_example("import_motion.py", "--motion", str(gltf), "--animation", "walk",
                          "--out", str(tmp_path / "refused.png"), *TRANSPORTS[transport])
    assert refused.returncode != 0 and "name the static mesh of each in object_meshes" in refused.stderr


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_animated_characters_walk_run_and_carry_a_head_camera(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "characters.png"
    result = run_example("animated_characters.py", "--frames", "12", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "18 bones: root, pelvis, spine_01" in result.stdout
    assert "clips: idle, walk, run" in result.stdout
    assert "frame 12/12 (" in result.stdout
    # 13 frames of 1/60 s into the 1.1 s walk (the set-up frame and 12 more).
    assert "walker at 0.22 s of 'walk'" in result.stdout
    assert "runner pose: 18 bones x 4 x 4" in result.stdout
    image = Image.open(out)
    assert image.size == (3 * 320, 4 * (240 + 20))
    assert len(set(image.convert("RGB").getdata())) > 1000  # rendered rooms and people, not blank frames


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_control_game_animation_walks_runs_and_stops_a_possessed_humanoid(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "game.png"
    result = run_example("control_game_animation.py", "--frames", "60", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert ("its body: /Game/characters/humanoid.glb (18 bones), blend space idle at 0 m/s, walk at 1.25 m/s, "
            "run at 3.2 m/s") in result.stdout
    # Each phase's first line shows the pose the phase before it ended in (the speed is smoothed over 0.1 s):
    # walking when the turn starts, running when the stop starts, standing idle at the end.
    poses = {m[1]: {clip: float(w) for clip, w in re.findall(r"(\w+) ([\d.]+)", m[2])}
             for m in re.finditer(r"frame (\d+/60) \w+: .*?, pose (.*)", result.stdout)}
    assert poses["19/60"].get("walk", 0.0) > 0.9, result.stdout
    assert poses["46/60"].get("run", 0.0) > 0.5, result.stdout
    assert poses["60/60"].get("idle", 0.0) > 0.8, result.stdout
    image = Image.open(out)
    assert image.size == (4 * 320, 2 * (240 + 20))
    assert len(set(image.convert("RGB").getdata())) > 1000


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_control_pawn_flies_the_player_and_hands_it_over(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "views.png"
    result = run_example("control_pawn.py", "--frames", "40", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "player 0: PlayerController_0 possesses DefaultPawn_0 at (-2.60, -0.60, 1.40)" in result.stdout
    assert "frame 40/40: pawn at (" in result.stdout
    assert "after SwapPlayerControllers: player 0 is SecondController, possessing DefaultPawn_0: True" in result.stdout
    assert "after AI Possess: DefaultPawn_0 is player-controlled: False, player 0 has a pawn: False" in result.stdout
    # The character walks until the wall's face (y = -2.5) stops its capsule (radius 0.35), on the floor.
    assert ("character Walker walked from (0.60, 0.20) to (0.60, -2.15), standing 0.90 m up, on the ground: True"
            in result.stdout)
    image = Image.open(out)
    assert image.size == (4 * 320, 240)
    assert len(set(image.convert("L").getdata())) > 20  # a rendered room, not a blank frame


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_control_city_sample_drives_traffic_on_lanes_and_hands_the_players_car_over(transport: str,
                                                                                     tmp_path: Path) -> None:
    out = tmp_path / "city"
    result = run_example("control_city_sample.py", "--cars", "8", "--frames", "600", "--handover", "300",
                         "--every", "60", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert re.search(r"lanes: \d+ lanes \(Sidewalk, Driving\), 20 junctions", result.stdout), result.stdout
    assert "player 0 drives PlayerCar from lane " in result.stdout
    # The player kept to its lane and stopped before the junction, then the autopilot took the car on.
    stop = re.search(r"frame 300: the player's car stands at (-?[\d.]+) m/s, ([\d.]+) m before the junction",
                     result.stdout)
    assert stop, result.stdout
    assert abs(float(stop.group(1))) < 0.3 and 1.0 < float(stop.group(2)) < 12.0
    assert "frame 300: the player hands PlayerCar to the autopilot" in result.stdout
    moved = re.search(r"traffic travelled (\d+) m on average, the player's car (\d+) m; no car was more than "
                      r"([\d.]+) m off its lane's centre line", result.stdout)
    assert moved, result.stdout
    assert int(moved.group(1)) > 30 and int(moved.group(2)) > 15
    assert float(moved.group(3)) < 1.75  # half a lane
    assert len(list(out.glob("chase_*.png"))) == 10
    assert Image.open(out / "map.png").size == (528, 408)
    strip = Image.open(out.with_suffix(".png"))
    assert strip.size[1] == 2 * 270 and strip.size[0] > 2 * 480


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_control_car_drives_into_the_crate_and_writes_its_frames(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "car"
    result = run_example("control_car.py", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "frame 240/240: car at (" in result.stdout
    pushed = re.search(r"crate pushed from \(15\.5, 9\.5\) to \((-?[\d.]+), (-?[\d.]+)\)", result.stdout)
    assert pushed, result.stdout
    assert float(pushed.group(1)) > 16.0 and float(pushed.group(2)) > 10.0  # the car drove into it
    assert len(list(out.glob("frame_*.png"))) == 25
    strip = Image.open(out.with_suffix(".png"))
    assert strip.size == (4 * 480, 270)
    assert len(set(strip.convert("L").getdata())) > 20  # a rendered scene, not a blank frame


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_stream_levels_loads_ahead_and_unloads_behind(transport: str, tmp_path: Path) -> None:
    result = run_example("stream_levels.py", "--out", str(tmp_path), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "step 1/24: camera at x = -10 m, levels loaded: Block0, Block1; 21 actors" in result.stdout
    assert "step 19/24: camera at x = 80 m, levels loaded: Block2; 13 actors" in result.stdout
    assert sorted(p.name for p in (tmp_path / "levels").iterdir()) == [f"block_{b}.json" for b in range(3)]
    strip = Image.open(tmp_path / "views.png")
    assert strip.size == (4 * 320, 180)
    assert len(set(strip.convert("L").getdata())) > 20  # a rendered street, not a blank frame


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_navigation_plans_episodes_walks_one_and_draws_the_map(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "nav"
    result = run_example("navigation.py", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert re.search(r"navigation mesh: \d+ tiles, \d+ polygons, [\d.]+ m\^2 walkable", result.stdout), result.stdout
    episodes = re.findall(r"episode \d+/8: (\w+), geodesic ([\d.]+) m, straight line ([\d.]+) m", result.stdout)
    assert len(episodes) == 8
    assert all(status == "Success" and float(g) >= float(s) - 1e-2 for status, g, s in episodes)
    walked = re.search(r"walked ([\d.]+) m in \d+ frames \(the path is ([\d.]+) m\)", result.stdout)
    assert walked, result.stdout
    # The walker follows the path and stops its radius plus the acceptance radius short of the goal.
    assert abs(float(walked.group(1)) - float(walked.group(2))) < 1.0
    assert list(out.glob("frame_*.png"))
    image = Image.open(tmp_path / "nav_map.png").convert("RGB")
    colours = set(image.getdata())
    assert (220, 40, 30) in colours and (60, 90, 200) in colours and (200, 220, 190) in colours


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_control_city_generator_spells_spear_and_regenerates(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "city.png"
    result = run_example("control_city_generator.py", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    generated = re.search(r"generated (\d+) buildings in \d+ ms around 13 road splines", result.stdout)
    assert generated and int(generated.group(1)) > 500, result.stdout
    assert "generate again with nothing changed: the same actors: True" in result.stdout
    # The road splines' lanes: the letters' strokes meet at junctions (P, E, A and R), and moving the letters
    # apart rebuilds the same lanes elsewhere.
    lanes = re.search(r"lanes: (\d+) lanes, (\d+) junctions", result.stdout)
    assert lanes and int(lanes.group(1)) > 100 and int(lanes.group(2)) >= 8, result.stdout
    assert f"lanes rebuilt: {lanes.group(1)} lanes, {lanes.group(2)} junctions" in result.stdout
    for image_path in (out, tmp_path / "city_wide.png"):
        image = Image.open(image_path)
        assert image.size == (1280, 720)
        assert len(set(image.convert("L").getdata())) > 20  # buildings, roads and shadows


@pytest.mark.parametrize("servers", [[], ["--servers", "2"]], ids=["worlds", "servers"])
def test_vector_env_steps_the_environments_and_writes_their_grid(servers: list[str], tmp_path: Path) -> None:
    out = tmp_path / "grid.png"
    result = run_example("vector_env.py", "--envs", "4", "--steps", "5", "--out", str(out), *servers)
    assert result.returncode == 0, result.stdout + result.stderr
    where = "2 spear-servers" if servers else "one in-process engine"
    assert re.search(rf"^4 environments in {where}: 5 steps in [\d.]+ s, \d+ environment steps/s", result.stdout,
                     re.M), result.stdout
    sheet = np.asarray(Image.open(out))
    assert sheet.shape == (2 * 96 + 2, 2 * 96 + 2, 3)
    for r in range(2):  # each tile shows the grey floor with the red puck and the green goal on it
        for c in range(2):
            tile = sheet[r * 98:r * 98 + 96, c * 98:c * 98 + 96].reshape(-1, 3).astype(int)
            assert np.any((tile[:, 0] > tile[:, 1] + 60)), f"no red puck in tile {r},{c}"
            assert np.any((tile[:, 1] > tile[:, 0] + 30)), f"no green goal in tile {r},{c}"


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_raster_vs_path_traced_writes_both_renderings_side_by_side(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "both.png"
    result = run_example("raster_vs_path_traced.py", "--width", "64", "--height", "48", "--samples", "8",
                         "--per-frame", "4", "--out", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert "froze Ball, Box for the still view path tracing needs" in result.stdout
    assert "path traced: 4/8 samples per pixel" in result.stderr  # progress as samples accumulate
    assert "path traced: 8/8 samples per pixel" in result.stderr
    image = np.asarray(Image.open(out))
    assert image.shape == (48 + 22, 128, 3)
    raster, traced = image[22:, :64].astype(float), image[22:, 64:].astype(float)
    assert raster.std() > 10 and traced.std() > 10  # both show the room, not a flat colour


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_movie_render_queue_renders_the_camera_move_to_files_and_resumes(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "movie"
    args = ["--frames", "6", "--width", "64", "--height", "48", "--out", str(out), *TRANSPORTS[transport]]
    result = run_example("movie_render_queue.py", *args)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "render: [########################] 6/6 frames" in result.stderr  # the progress bar
    bars = [line for line in result.stderr.splitlines() if line.startswith("render: [")]
    assert 2 <= len(bars) <= 5, bars  # piped: a line at the start and per quarter, not one per frame
    assert "rendered 6 frames, skipped 0 already written" in result.stdout
    for modality, suffix in [("final_color", "png"), ("depth", "exr"), ("normal", "exr"), ("object_ids", "exr")]:
        assert sorted(p.name for p in (out / modality).iterdir()) == [f"{k:04d}.{suffix}" for k in range(6)]
    assert json.loads((out / "camera" / "0005.json").read_text())["width"] == 64
    assert Image.open(out / "preview.png").size == (2 * 64, 48)  # frames 0 and 5
    video = (out / "final_color.mp4").read_bytes()
    assert video[4:8] == b"ftyp" and b"avc1" in video and "final_color.mp4 and" in result.stdout
    frames = [np.asarray(Image.open(out / "final_color" / f"{k:04d}.png")) for k in (0, 5)]
    assert frames[0].std() > 10 and not np.array_equal(frames[0], frames[1])  # the room, seen as the camera moves

    (out / "depth" / "0003.exr").unlink()
    result = run_example("movie_render_queue.py", *args)  # run again: resumes
    assert result.returncode == 0, result.stdout + result.stderr
    assert "rendered 1 frames, skipped 5 already written" in result.stdout


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_anti_aliasing_shows_each_method_and_spatial_samples_come_closest(transport: str,
                                                                                tmp_path: Path) -> None:
    out = tmp_path / "anti_aliasing.png"
    result = run_example("anti_aliasing.py", "--out", str(out), "--width", "160", "--height", "120",
                         *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    found = {m.group(1): (float(m.group(2)), float(m.group(3)), m.group(4)) for m in re.finditer(
        r"^(AAM_\w+|SpatialSampleCount \d+)\s+mean ([0-9.]+), 99th percentile ([0-9.]+) .*without anti-aliasing: "
        r"(\w+)$", result.stdout, re.MULTILINE)}
    assert sorted(found) == ["AAM_FXAA", "AAM_MSAA", "AAM_None", "SpatialSampleCount 16", "SpatialSampleCount 4"], result.stdout
    assert all(same == "True" for _, _, same in found.values())  # ids untouched
    assert found["AAM_MSAA"][0] < 0.6 * found["AAM_None"][0]
    assert found["AAM_FXAA"][0] < found["AAM_None"][0]
    four, sixteen = found["SpatialSampleCount 4"], found["SpatialSampleCount 16"]
    assert sixteen[0] < four[0] < found["AAM_MSAA"][0], result.stdout
    assert sixteen[1] < found["AAM_MSAA"][1], result.stdout
    assert out.is_file() and out.stat().st_size > 0


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_sky_and_environment_lights_the_shaded_faces_and_writes_four_skies(transport: str, tmp_path: Path) -> None:
    out = tmp_path / "skies.png"
    result = run_example("sky_and_environment.py", "--out", str(out), "--width", "96", "--height", "64",
                         *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    shade = {m.group(1).strip(): (float(m.group(2)), float(m.group(3))) for m in re.finditer(
        r"^(.+?)\s+shaded faces ([0-9.]+), background ([0-9.]+)", result.stdout, re.MULTILINE)}
    assert len(shade) == 4, result.stdout
    uniform, atmosphere = shade["default uniform sky"], shade["ASkyAtmosphere"]
    assert atmosphere[0] > 2.0 * uniform[0]  # the sky lights what the sun does not
    assert uniform[1] == 0.0 and atmosphere[1] > 0.0 and shade["HDR panorama (park.exr)"][1] > 0.0
    image = Image.open(out)
    assert image.size == (192, 128) and len(set(image.convert("RGB").getdata())) > 100


def test_every_example_takes_server() -> None:
    """Every example runs in-process or against a server: --server is among its options."""
    for example in sorted((ROOT / "examples").glob("*.py")):
        result = run_example(example.name, "--help")
        assert result.returncode == 0 and "--server" in result.stdout, example.name


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_inspect_scene_serves_the_page_and_saves_its_screenshot(transport: str, tmp_path: Path) -> None:
    pytest.importorskip("selenium", reason="python3-selenium is not installed (test.sh installs it)")
    out = tmp_path / "inspector.png"
    result = run_example("inspect_scene.py", "--seconds", "1", "--screenshot", str(out), *TRANSPORTS[transport])
    assert result.returncode == 0, result.stdout + result.stderr
    assert re.search(r"inspect_scene: open http://127\.0\.0\.1:\d+/\?token=[0-9a-f]{32}", result.stdout)
    assert re.search(r"inspect_scene: ran \d+ frames", result.stdout)
    image = Image.open(out)
    assert image.size[0] >= 1000 and len(set(image.convert("RGB").getdata())) > 1000  # the page with the camera's image
