"""Motion sequences (spear.motion): the built-in sequence is what its script records; files round-trip and bad
ones are refused naming the file and the key; a player poses the character, places it and moves the objects as
the sequence says, frame by frame, and renders them; a sequence for another skeleton leaves the world as it was.
Both transports."""

from __future__ import annotations

import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

import spear
import spear.motion
from spear.motion import MotionSequence, load_motion, save_motion

ROOT = Path(__file__).resolve().parents[2]
CARRY = "/Game/motions/carry_case.npz"
COMPONENT = spear.EBoneSpaces.ComponentSpace


def _matrix(transform: spear.FTransform) -> NDArray[np.float64]:
    """The 4 x 4 matrix of an FTransform (scale, then rotation, then translation)."""
    q = transform.Rotation
    x, y, z, w = q.X, q.Y, q.Z, q.W
    rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    s = transform.Scale3D
    matrix = np.eye(4)
    matrix[:3, :3] = rotation @ np.diag([s.X, s.Y, s.Z])
    matrix[:3, 3] = [transform.Translation.X, transform.Translation.Y, transform.Translation.Z]
    return matrix


def _yaw(degrees: float, x: float = 0.0, y: float = 0.0) -> NDArray[np.float64]:
    a = math.radians(degrees)
    matrix = np.eye(4)
    matrix[:2, :2] = [[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]]
    matrix[:2, 3] = [x, y]
    return matrix


def test_the_built_in_sequence_is_what_its_script_records() -> None:
    result = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_motion.py"), "--check"],
                            capture_output=True, text=True, timeout=120, env={"PYTHONPATH": str(ROOT / "python")})
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_built_in_sequence_holds_a_walk_with_a_case() -> None:
    motion = load_motion(CARRY)
    assert (motion.frames, motion.fps, motion.skeletal_mesh) == (60, 30.0, "/Game/characters/humanoid.glb")
    assert len(motion.bone_names) == 18 and "hand_r" in motion.bone_names
    assert motion.object_names == ("Case",) and motion.object_poses is not None
    assert motion.duration == pytest.approx(59 / 30)
    # The root walks forward along +X at the clip's stride speed; the case stays near the right hand.
    assert motion.root_poses[-1, 0, 3] == pytest.approx(1.25 * 59 / 30)
    hand = motion.bone_names.index("hand_r")
    hand_world = motion.root_poses @ motion.bone_poses[:, hand]
    gap = np.linalg.norm(motion.object_poses[:, 0, :3, 3] - hand_world[:, :3, 3], axis=1)
    assert np.allclose(gap, 0.12)


def test_transform_of_matches_the_matrix() -> None:
    rng = np.random.default_rng(3)
    for _ in range(200):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        transform = spear.FTransform(Rotation=spear.FQuat(*map(float, q)), Scale3D=spear.FVector(*map(float, rng.uniform(0.1, 3.0, 3))),
                                     Translation=spear.FVector(*map(float, rng.normal(size=3))))
        matrix = _matrix(transform)
        assert np.allclose(_matrix(spear.motion.transform_of(matrix)), matrix, atol=1e-9)


def test_a_sequence_round_trips_through_its_file(tmp_path: Path) -> None:
    motion = load_motion(CARRY)
    path = tmp_path / "copy.npz"
    save_motion(motion, path)
    again = load_motion(path)
    assert again.bone_names == motion.bone_names and again.object_meshes == motion.object_meshes
    assert np.array_equal(again.bone_poses, motion.bone_poses)
    assert again.object_poses is not None and motion.object_poses is not None
    assert np.array_equal(again.object_poses, motion.object_poses)
    assert [p.name for p in tmp_path.iterdir()] == ["copy.npz"]  # written whole: no temporary file left
    # No objects: a character's motion alone.
    alone = replace(motion, object_names=(), object_meshes=(), object_poses=None)
    save_motion(alone, path)
    assert load_motion(path).object_names == () and load_motion(path).object_poses is None


def _write(path: Path, **changes: object) -> Path:
    motion = load_motion(CARRY)
    arrays: dict[str, object] = dict(
        format=np.array("spear.motion"), version=np.array(1), fps=np.array(30.0),
        skeletal_mesh=np.array(motion.skeletal_mesh), bone_names=np.array(motion.bone_names),
        bone_poses=motion.bone_poses, root_poses=motion.root_poses, object_names=np.array(motion.object_names),
        object_meshes=np.array(motion.object_meshes), object_poses=motion.object_poses)
    arrays.update(changes)
    np.savez(path, **{key: value for key, value in arrays.items() if value is not None})
    return path


def test_bad_files_are_refused_naming_the_file_and_the_key(tmp_path: Path) -> None:
    with pytest.raises(spear.NotFoundError, match=r"load_motion\('.*missing.npz'\): no such file"):
        load_motion(tmp_path / "missing.npz")
    with pytest.raises(spear.NotFoundError, match=r"no built-in asset '/Game/motions/none.npz'"):
        load_motion("/Game/motions/none.npz")
    (tmp_path / "text.npz").write_text("not a zip")
    with pytest.raises(spear.InvalidArgumentError, match=r"text.npz'\): not a motion sequence \(.npz\) file"):
        load_motion(tmp_path / "text.npz")
    poses = load_motion(CARRY).bone_poses
    nan = poses.copy()
    nan[7, 3, 1, 2] = np.nan
    skewed = poses.copy()
    skewed[2, 5, 3, 0] = 0.5
    cases: list[tuple[dict[str, object], str]] = [
        ({"format": np.array("spear.scene")}, "'format' must be \"spear.motion\", got \"spear.scene\""),
        ({"version": np.array(2)}, "'version' array(2) is not supported (expected 1)"),
        ({"bone_poses": None}, "missing 'bone_poses'"),
        ({"fps": np.array(0.0)}, "'fps' must be a positive number, got 0.0"),
        ({"bone_poses": poses[:, :5]}, r"'bone_poses' must have shape (*, 18, 4, 4), got (60, 5, 4, 4)"),
        ({"bone_poses": poses.astype(np.float32)}, "'bone_poses' must be a float64 array, got float32"),
        ({"bone_poses": nan}, "'bone_poses' has a value that is not finite at (7, 3, 1, 2)"),
        ({"bone_poses": skewed}, "'bone_poses' at (2, 5) has bottom row [0.5, 0.0, 0.0, 1.0], not (0, 0, 0, 1)"),
        ({"root_poses": load_motion(CARRY).root_poses[:10]}, "'root_poses' must have shape (60, 4, 4), got (10, 4, 4)"),
        ({"object_meshes": np.array(["a", "b"])}, "1 object names but 2 object meshes"),
        ({"bone_names": np.array(["root"] * 18)}, "'bone_names' names a bone twice"),
    ]
    for number, (changes, message) in enumerate(cases):
        path = _write(tmp_path / f"bad{number}.npz", **changes)
        with pytest.raises(spear.InvalidArgumentError) as raised:
            load_motion(path)
        assert str(raised.value) == f"load_motion('{path}'): {message}"


def test_a_player_poses_and_places_the_character_and_its_objects(instance: spear.Instance) -> None:
    motion = load_motion(CARRY)
    assert motion.object_poses is not None
    place = _yaw(30.0, 2.0, -1.0)
    game = instance.get_game()
    with instance.begin_frame():
        player = spear.motion.MotionPlayer(game, motion, name="Carrier", placement=place)
        assert player.character.GetName() == "Carrier"
        assert [o.GetName() for o in player.objects] == ["Case"]
    with instance.end_frame():
        pass
    mesh_bones: list[str] = []
    for frame in (0, 17, 59):
        with instance.begin_frame():
            player.apply(frame)
        with instance.end_frame():
            pass
        with instance.begin_frame():
            if not mesh_bones:
                mesh_bones = [player.mesh.GetBoneName(BoneIndex=i) for i in range(player.mesh.GetNumBones())]
            order = [motion.bone_names.index(bone) for bone in mesh_bones]
            pose = player.mesh.GetBoneTransforms(Space=COMPONENT)
            root = _matrix(player.character.GetActorTransform())
            case = _matrix(player.objects[0].GetActorTransform())
        with instance.end_frame():
            pass
        assert np.allclose(pose, motion.bone_poses[frame][order], atol=1e-6)
        assert np.allclose(root, place @ motion.root_poses[frame], atol=1e-6)
        assert np.allclose(case, place @ motion.object_poses[frame, 0], atol=1e-6)
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError, match=r"MotionPlayer.apply\(\): frame 60 is outside 0..59"):
            player.apply(60)
    with instance.end_frame():
        pass


def test_a_played_frame_renders_with_body_parts_and_the_object(instance: spear.Instance) -> None:
    motion = load_motion(CARRY)
    game = instance.get_game()
    with instance.begin_frame():
        player = spear.motion.MotionPlayer(game, motion)
        player.mesh.bBodyPartIds = True
        player.apply(20)
        # 5 m to the character's left side, looking at where it is at frame 20.
        x = float(motion.root_poses[20, 0, 3])
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(x, 5.0, 1.0),
                                  rotation=spear.FRotator(Yaw=-90.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 96, 96, 30.0
        camera.Modalities = [spear.ECameraModality.ObjectIds]
    with instance.end_frame():
        ids = camera.read_pixels()["object_ids"]
    parts: set[str] = set()
    case_pixels = 0
    with instance.begin_frame():
        for object_id in np.unique(ids[ids != 0]):
            found, actor, component, slot, _ = camera.GetObjectIdInfo(ObjectId=int(object_id))
            assert found
            if isinstance(component, spear.USkeletalMeshComponent):
                parts.add(component.GetBodyPartOfSlot(MaterialSlot=slot))
            elif actor is not None and actor.GetName() == "Case":
                case_pixels = int((ids == object_id).sum())
    with instance.end_frame():
        pass
    assert {"head", "pelvis", "thigh_l", "calf_l", "upperarm_l"} <= parts, parts
    assert case_pixels > 20


def test_a_sequence_for_another_skeleton_leaves_the_world_as_it_was(instance: spear.Instance) -> None:
    motion = load_motion(CARRY)
    renamed = replace(motion, bone_names=tuple("hand_x" if b == "hand_r" else b for b in motion.bone_names))
    game = instance.get_game()
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError) as raised:
            spear.motion.MotionPlayer(game, renamed, name="Wrong")
        assert game.find_actor_by_name(name="Wrong") is None
        assert game.find_actor_by_name(name="Case") is None
        with pytest.raises(spear.InvalidArgumentError, match=r"'placement' must have shape \(4, 4\)"):
            spear.motion.MotionPlayer(game, motion, placement=np.eye(3))
    with instance.end_frame():
        pass
    assert str(raised.value) == ("MotionPlayer(): the sequence's bones do not match /Game/characters/humanoid.glb's: "
                                 "missing hand_r; not in the mesh hand_x")


# -- motion straight from an animated file (glTF: the humanoid with boxes, tests/python/motion_files.py) ---------

def _spear_axes(gltf: tuple[float, float, float]) -> NDArray[np.float64]:
    """A glTF position (Y up) in spear's axes (Z up): (x, y, z) -> (x, -z, y)."""
    x, y, z = gltf
    return np.array([x, -z, y])


def test_a_motion_file_reads_the_character_and_the_objects_the_clip_moves(instance: spear.Instance,
                                                                            tmp_path: Path) -> None:
    from motion_files import CASE_KEYS, CASE_TIMES, HELD_OFFSET, write_carry_glb

    path = str(write_carry_glb(tmp_path / "carry.glb"))
    game = instance.get_game()
    with instance.begin_frame():
        read = spear.USkeletalMeshComponent.ReadMotionFile(Filename=path, Animation="walk", FrameRate=10.0)
        mesh = game.spawn_actor(uclass=spear.ASkeletalMeshActor, name="Reference").SkeletalMeshComponent
        mesh.SetSkeletalMesh(NewMesh=path)
        mesh_bones = [mesh.GetBoneName(BoneIndex=i) for i in range(mesh.GetNumBones())]
        mesh.PlayAnimation(NewAnimToPlay="walk", bLoop=False)
        poses = []
        for frame in (0, 3, 11):  # the clip's start, between keys, its end (1.1 s)
            mesh.SetPosition(InPos=frame / 10.0)
            poses.append(mesh.GetBoneTransforms(Space=COMPONENT))
        bounds = mesh.GetBounds()
    with instance.end_frame():
        pass
    assert (read["Animation"], read["FrameRate"]) == ("walk", 10.0)
    assert read["BoneNames"] == mesh_bones
    assert read["BoneTransforms"].shape == (12, len(mesh_bones), 4, 4)  # 1.1 s at 10 frames/s, both ends
    for frame, pose in zip((0, 3, 11), poses):
        assert np.allclose(read["BoneTransforms"][frame], pose, atol=1e-9)
    # The Floor is moved by nothing: not an object. The Case by its own keys, the Held box by the hand.
    assert sorted(read["ObjectNames"]) == ["Case", "Held"]
    objects = read["ObjectTransforms"]
    assert objects.shape == (12, 2, 4, 4)
    case, held = read["ObjectNames"].index("Case"), read["ObjectNames"].index("Held")
    for frame in range(12):
        t = frame / 10.0
        k = 0 if t <= CASE_TIMES[1] else 1
        w = (t - CASE_TIMES[k]) / (CASE_TIMES[k + 1] - CASE_TIMES[k])
        gltf = (1 - w) * np.array(CASE_KEYS[k]) + w * np.array(CASE_KEYS[k + 1])
        assert np.allclose(objects[frame, case, :3, 3], _spear_axes(tuple(gltf)), atol=1e-6), frame
        assert np.allclose(objects[frame, case, :3, :3], np.eye(3), atol=1e-9)
    hand = read["BoneNames"].index("hand_r")
    offset = np.eye(4)
    offset[:3, 3] = _spear_axes(HELD_OFFSET)
    for frame, pose in zip((0, 3, 11), poses):
        assert np.allclose(objects[frame, held], pose[hand] @ offset, atol=1e-6)
    # The character is the skinned mesh alone: the boxes (the Floor 5 m below) are not drawn with it.
    assert bounds.Origin.Z - bounds.BoxExtent.Z > -0.5


def test_import_motion_makes_a_sequence_a_player_plays(instance: spear.Instance, tmp_path: Path) -> None:
    from motion_files import write_carry_glb

    path = str(write_carry_glb(tmp_path / "carry.glb"))
    game = instance.get_game()
    with instance.begin_frame():
        motion = spear.motion.import_motion(path, animation="walk", fps=20.0,
                                            object_meshes={"Case": "/Engine/BasicShapes/Cube",
                                                           "Held": "/Engine/BasicShapes/Sphere"})
        player = spear.motion.MotionPlayer(game, motion, name="Importer")
    with instance.end_frame():
        pass
    assert (motion.frames, motion.fps, motion.skeletal_mesh) == (23, 20.0, path)
    assert motion.object_meshes == tuple({"Case": "/Engine/BasicShapes/Cube", "Held": "/Engine/BasicShapes/Sphere"}[n]
                                         for n in motion.object_names)
    assert np.array_equal(motion.root_poses, np.tile(np.eye(4), (23, 1, 1)))
    assert motion.object_poses is not None
    with instance.begin_frame():
        player.apply(7)
    with instance.end_frame():
        pass
    with instance.begin_frame():
        placed = [_matrix(actor.GetActorTransform()) for actor in player.objects]
    with instance.end_frame():
        pass
    for matrix, expected in zip(placed, motion.object_poses[7]):
        assert np.allclose(matrix, expected, atol=1e-6)
    # Saved and loaded as any sequence.
    save_motion(motion, tmp_path / "carry.npz")
    loaded = load_motion(tmp_path / "carry.npz")
    assert loaded.object_names == motion.object_names and np.array_equal(loaded.bone_poses, motion.bone_poses)


def test_bad_motion_files_and_arguments_are_refused_naming_them(instance: spear.Instance, tmp_path: Path) -> None:
    from motion_files import write_carry_glb

    path = str(write_carry_glb(tmp_path / "carry.glb"))
    read = spear.USkeletalMeshComponent.ReadMotionFile
    with instance.begin_frame():
        with pytest.raises(spear.NotFoundError, match=r"has no clip 'jump' \(it has 'idle', 'walk', 'run'\)"):
            read(Filename=path, Animation="jump", FrameRate=30.0)
        with pytest.raises(spear.InvalidArgumentError, match=r"has 3 clips \('idle', 'walk', 'run'\): name the one"):
            read(Filename=path, Animation="", FrameRate=30.0)
        for rate in (0.0, -1.0, math.inf, math.nan):
            with pytest.raises(spear.InvalidArgumentError, match=r"importMotion\(\): FrameRate must be a positive"):
                read(Filename=path, Animation="walk", FrameRate=rate)
        with pytest.raises(spear.InvalidArgumentError, match=r"more than 1000000"):
            read(Filename=path, Animation="walk", FrameRate=1e9)
        with pytest.raises(spear.NotFoundError, match=r"no such file '.*nowhere.glb'"):
            read(Filename=str(tmp_path / "nowhere.glb"), Animation="walk", FrameRate=30.0)
        with pytest.raises(spear.InvalidArgumentError, match=r"has no skeleton"):
            read(Filename=_static_mesh_file(tmp_path), Animation="", FrameRate=30.0)
        with pytest.raises(spear.InvalidArgumentError, match=r"clip 'walk' moves '(Held|Case)'.*object_meshes"):
            spear.motion.import_motion(path, animation="walk", object_meshes={"Case": "/Engine/BasicShapes/Cube"})
        cube = "/Engine/BasicShapes/Cube"
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"object_meshes names 'Floor', which clip 'walk' does not"):
            spear.motion.import_motion(path, animation="walk",
                                       object_meshes={"Case": cube, "Held": cube, "Floor": cube})
        # The engine serves on.
        assert read(Filename=path, Animation="idle", FrameRate=5.0)["Animation"] == "idle"
    with instance.end_frame():
        pass


def _static_mesh_file(folder: Path) -> str:
    """An OBJ triangle: a mesh file without a skeleton."""
    path = folder / "triangle.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    return str(path)
