"""Motion sequences: a skinned character's poses and the rigid trajectories of the objects it handles, frame by
frame (human-object motion as datasets such as HUMOTO record it), in one .npz file; and a player that poses a
character and moves the objects in a world, one frame per engine frame.

    motion = spear.motion.load_motion("/Game/motions/carry_box.npz")
    with instance.begin_frame():
        player = spear.motion.MotionPlayer(game, motion)      # spawns the character and the objects
    for frame in range(motion.frames):
        with instance.begin_frame():
            player.apply(frame)                               # the pose and the objects of this frame
        with instance.end_frame():
            pixels = camera.read_pixels()                     # rendered with them

The file (numpy's .npz, written by save_motion) holds, for F frames, B bones and O objects:

    format          "spear.motion"                 version   1
    fps             frames per second (> 0)
    skeletal_mesh   the character's skeletal mesh asset ("/Game/characters/humanoid.glb")
    bone_names      (B,) str      the bones posed, by name (any order; every bone of the mesh)
    bone_poses      (F, B, 4, 4)  each bone's transform relative to the character (EBoneSpaces.ComponentSpace)
    root_poses      (F, 4, 4)     the character's transform in the world
    object_names    (O,) str      the objects' actor names
    object_meshes   (O,) str      their static mesh assets
    object_poses    (F, O, 4, 4)  their transforms in the world

Transforms are float64 homogeneous matrices (column 3 the translation, in metres; Z up), as
USkeletalMeshComponent.GetBoneTransforms returns them. A dataset converts to this form once:
its joints' world or parent-relative rotations composed into these matrices.

A dataset that ships animated files (glTF 2.0, or FBX where assimp reads it: a skinned character and the
rigid objects it handles, moved by one clip) is read straight from them by import_motion, through the open
engine; each object's static mesh is named by the caller, as datasets ship objects' meshes on their own:

    motion = spear.motion.import_motion("/data/humoto/carry_box.glb", animation="carry",
                                        object_meshes={"box": "/data/humoto/objects/box.obj"}, fps=30.0)
    spear.motion.save_motion(motion, "carry_box.npz")      # once; later runs load_motion() it
"""

from __future__ import annotations

import os
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from spear._engine.api import (AStaticMeshActor, ASkeletalMeshActor, EBoneSpaces, FQuat, FTransform, FVector,
                               USkeletalMeshComponent, UWorld)
from spear.errors import InvalidArgumentError, NotFoundError

__all__ = ["FORMAT", "VERSION", "MotionPlayer", "MotionSequence", "import_motion", "load_motion", "save_motion",
           "transform_of"]

FORMAT = "spear.motion"
VERSION = 1


@dataclass(frozen=True)
class MotionSequence:
    """A motion sequence as load_motion returns it (see the module's documentation for each field)."""

    fps: float
    skeletal_mesh: str
    bone_names: tuple[str, ...]
    bone_poses: NDArray[np.float64]  # (F, B, 4, 4)
    root_poses: NDArray[np.float64]  # (F, 4, 4)
    object_names: tuple[str, ...] = ()
    object_meshes: tuple[str, ...] = ()
    object_poses: NDArray[np.float64] | None = None  # (F, O, 4, 4); None when there are no objects

    def __post_init__(self) -> None:
        _check(self, "MotionSequence")

    @property
    def frames(self) -> int:
        return int(self.bone_poses.shape[0])

    @property
    def duration(self) -> float:
        """Seconds from the first frame to the last."""
        return (self.frames - 1) / self.fps


def _check_matrices(where: str, key: str, value: Any, shape: tuple[int | None, ...]) -> None:
    if not isinstance(value, np.ndarray) or value.dtype != np.float64:
        raise InvalidArgumentError(f"{where}: '{key}' must be a float64 array, got "
                                   f"{getattr(value, 'dtype', type(value).__name__)}")
    if value.ndim != len(shape) or any(n is not None and n != m for n, m in zip(shape, value.shape)):
        wanted = "(" + ", ".join("*" if n is None else str(n) for n in shape) + ")"
        raise InvalidArgumentError(f"{where}: '{key}' must have shape {wanted}, got {value.shape}")
    if not np.isfinite(value).all():
        index = tuple(int(i) for i in np.argwhere(~np.isfinite(value))[0])
        raise InvalidArgumentError(f"{where}: '{key}' has a value that is not finite at {index}")
    rows = value[..., 3, :]
    bad = np.argwhere(np.abs(rows - np.array([0.0, 0.0, 0.0, 1.0])).max(axis=-1) > 1e-9)
    if len(bad):
        raise InvalidArgumentError(f"{where}: '{key}' at {tuple(int(i) for i in bad[0])} has bottom row "
                                   f"{rows[tuple(bad[0])].tolist()}, not (0, 0, 0, 1)")


def _check(motion: MotionSequence, where: str) -> None:
    if isinstance(motion.fps, bool) or not (isinstance(motion.fps, (int, float)) and np.isfinite(motion.fps)
                                            and motion.fps > 0.0):
        raise InvalidArgumentError(f"{where}: 'fps' must be a positive number, got {motion.fps!r}")
    if not motion.skeletal_mesh:
        raise InvalidArgumentError(f"{where}: 'skeletal_mesh' is empty")
    frames = motion.bone_poses.shape[0] if isinstance(motion.bone_poses, np.ndarray) else None
    _check_matrices(where, "bone_poses", motion.bone_poses, (None, len(motion.bone_names), 4, 4))
    if frames == 0:
        raise InvalidArgumentError(f"{where}: the sequence has no frames")
    if len(set(motion.bone_names)) != len(motion.bone_names):
        raise InvalidArgumentError(f"{where}: 'bone_names' names a bone twice")
    _check_matrices(where, "root_poses", motion.root_poses, (frames, 4, 4))
    if len(motion.object_meshes) != len(motion.object_names):
        raise InvalidArgumentError(f"{where}: {len(motion.object_names)} object names but "
                                   f"{len(motion.object_meshes)} object meshes")
    if motion.object_names:
        _check_matrices(where, "object_poses", motion.object_poses, (frames, len(motion.object_names), 4, 4))
    elif motion.object_poses is not None and motion.object_poses.size:
        raise InvalidArgumentError(f"{where}: 'object_poses' given for no objects")


def resolve_asset_file(path: str | os.PathLike[str]) -> Path:
    """A file path, or "/Game/<rest>" for a file of the built-in assets (the checkout's assets/<rest>, or the
    installed package's own copy)."""
    text = os.fspath(path)
    if text.startswith("/Game/"):
        here = Path(__file__).resolve().parent
        rest = text[len("/Game/"):]
        for candidate in (here.parents[1] / "assets" / rest, here / "assets" / rest):
            if candidate.is_file():
                return candidate
        raise NotFoundError(f"load_motion(): no built-in asset '{text}'")
    return Path(text)


def load_motion(path: str | os.PathLike[str]) -> MotionSequence:
    """Reads and checks a motion sequence file. Raises NotFoundError for a missing file, InvalidArgumentError
    naming the file and the key for anything else wrong with it (not .npz, another format or version, a missing
    key, an array of the wrong shape or type, a value that is not finite)."""
    file = resolve_asset_file(path)
    where = f"load_motion('{os.fspath(path)}')"
    if not file.is_file():
        raise NotFoundError(f"{where}: no such file")
    try:
        with np.load(file, allow_pickle=False) as data:
            arrays: dict[str, NDArray[Any]] = {key: data[key] for key in data.files}
    except (zipfile.BadZipFile, ValueError, OSError) as error:
        raise InvalidArgumentError(f"{where}: not a motion sequence (.npz) file: {error}") from None

    def take(key: str) -> NDArray[Any]:
        if key not in arrays:
            raise InvalidArgumentError(f"{where}: missing '{key}'")
        return arrays[key]

    def text(key: str) -> str:
        value = take(key)
        if value.dtype.kind != "U" or value.ndim != 0:
            raise InvalidArgumentError(f"{where}: '{key}' must be a string")
        return str(value)

    def names(key: str) -> tuple[str, ...]:
        value = take(key)
        if value.ndim != 1 or (value.size and value.dtype.kind != "U"):
            raise InvalidArgumentError(f"{where}: '{key}' must be a 1-D array of strings")
        return tuple(str(v) for v in value)

    if text("format") != FORMAT:
        raise InvalidArgumentError(f"{where}: 'format' must be \"{FORMAT}\", got \"{text('format')}\"")
    version = take("version")
    if version.ndim != 0 or version.dtype.kind not in "iu" or int(version) != VERSION:
        raise InvalidArgumentError(f"{where}: 'version' {version!r} is not supported (expected {VERSION})")
    fps = take("fps")
    if fps.ndim != 0 or fps.dtype.kind not in "fiu":
        raise InvalidArgumentError(f"{where}: 'fps' must be a number")
    object_names = names("object_names")
    fields: dict[str, Any] = dict(
        fps=float(fps), skeletal_mesh=text("skeletal_mesh"), bone_names=names("bone_names"),
        bone_poses=take("bone_poses"), root_poses=take("root_poses"), object_names=object_names,
        object_meshes=names("object_meshes"), object_poses=take("object_poses") if object_names else None)
    try:
        return MotionSequence(**fields)
    except InvalidArgumentError as error:  # named for the file rather than for the constructor
        raise InvalidArgumentError(f"{where}: {str(error).removeprefix('MotionSequence: ')}") from None


def import_motion(path: str | os.PathLike[str], *, animation: str = "", fps: float = 30.0,
                  object_meshes: Mapping[str, str] | None = None) -> MotionSequence:
    """Reads clip `animation` ("" for the file's only clip) of an animated file holding a skinned character and
    the rigid objects it handles (glTF 2.0; FBX where assimp reads it), at `fps` frames per second from the
    clip's start to its end, through the open engine (USkeletalMeshComponent.ReadMotionFile: the character's
    bones in component space, each object's node in the file's space turned Z-up, the root at the origin).

    The objects are the file's nodes with a mesh that no bone deforms and that the clip moves; `object_meshes`
    names the static mesh asset to show for each, by node name: a mesh in that node's own frame and size (the
    object's mesh as the dataset ships it; a built-in shape is a metre across). The character is the file itself
    (its skinned meshes). Raises NotFoundError for a missing file or clip (naming the clips there are), InvalidArgumentError
    for a file without skeleton or clip, a rate that is not positive, or an object without a mesh (naming it)
    or a mesh for no object of the file."""
    where = f"import_motion('{os.fspath(path)}')"
    meshes = dict(object_meshes or {})
    read = USkeletalMeshComponent.ReadMotionFile(Filename=os.fspath(path), Animation=animation, FrameRate=fps)
    names = tuple(read["ObjectNames"])
    missing = [name for name in names if name not in meshes]
    if missing:
        raise InvalidArgumentError(f"{where}: clip '{read['Animation']}' moves {', '.join(map(repr, missing))}: name "
                                   f"the static mesh of each in object_meshes (e.g. {{{missing[0]!r}: "
                                   "'/Game/objects/box.obj'})")
    unknown = sorted(set(meshes) - set(names))
    if unknown:
        raise InvalidArgumentError(f"{where}: object_meshes names {', '.join(map(repr, unknown))}, which clip "
                                   f"'{read['Animation']}' does not move (it moves "
                                   f"{', '.join(map(repr, names)) or 'no object'})")
    bones = np.ascontiguousarray(read["BoneTransforms"], dtype=np.float64)
    return MotionSequence(fps=float(fps), skeletal_mesh=os.fspath(path), bone_names=tuple(read["BoneNames"]),
                          bone_poses=bones, root_poses=np.tile(np.eye(4), (bones.shape[0], 1, 1)),
                          object_names=names, object_meshes=tuple(meshes[name] for name in names),
                          object_poses=np.ascontiguousarray(read["ObjectTransforms"], dtype=np.float64)
                          if names else None)


def save_motion(motion: MotionSequence, path: str | os.PathLike[str]) -> None:
    """Writes `motion` to `path` (.npz, compressed), whole: to a temporary file first, renamed over `path`."""
    target = Path(path)
    temporary = target.with_name(f".{target.name}.tmp")
    objects = motion.object_poses if motion.object_poses is not None else np.zeros((motion.frames, 0, 4, 4))
    try:
        with open(temporary, "wb") as out:
            np.savez_compressed(out, format=np.array(FORMAT), version=np.array(VERSION), fps=np.array(motion.fps),
                                skeletal_mesh=np.array(motion.skeletal_mesh),
                                bone_names=np.array(motion.bone_names, dtype=str), bone_poses=motion.bone_poses,
                                root_poses=motion.root_poses, object_names=np.array(motion.object_names, dtype=str),
                                object_meshes=np.array(motion.object_meshes, dtype=str), object_poses=objects)
        os.replace(temporary, target)
    finally:
        temporary.unlink(missing_ok=True)


def transform_of(matrix: NDArray[np.float64]) -> FTransform:
    """The FTransform of a 4 x 4 homogeneous matrix of rotation and positive scale (scale, then rotation, then
    translation, as FTransform applies them)."""
    linear = matrix[:3, :3]
    scale = np.linalg.norm(linear, axis=0)
    r = linear / scale
    # The quaternion of the rotation matrix r, from its largest component (stable for every rotation).
    trace = r[0, 0] + r[1, 1] + r[2, 2]
    if trace > 0.0:
        s = 2.0 * np.sqrt(1.0 + trace)
        q = ((r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, 0.25 * s)
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = 2.0 * np.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2])
        q = (0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s, (r[2, 1] - r[1, 2]) / s)
    elif r[1, 1] > r[2, 2]:
        s = 2.0 * np.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2])
        q = ((r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s, (r[0, 2] - r[2, 0]) / s)
    else:
        s = 2.0 * np.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1])
        q = ((r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s, (r[1, 0] - r[0, 1]) / s)
    x, y, z, w = (float(c) for c in q)
    return FTransform(Translation=FVector(*(float(t) for t in matrix[:3, 3])), Rotation=FQuat(x, y, z, w),
                      Scale3D=FVector(*(float(c) for c in scale)))


class MotionPlayer:
    """Plays a MotionSequence in a world. Made inside a frame: spawns the character (an ASkeletalMeshActor
    named `name` showing motion.skeletal_mesh) and one AStaticMeshActor per object, named as the sequence
    names them. apply(frame), inside a frame, poses the character and moves the objects to that frame's
    transforms; what the engine renders at the end of that frame shows them (lock-step: one sequence frame
    per engine frame, whatever the engine's time step). `placement`, a 4 x 4 homogeneous matrix, puts the
    sequence's own frame of reference (its origin, where a dataset recorded it) into the world: the root's
    and the objects' world transforms are placement @ theirs."""

    def __init__(self, game: UWorld, motion: MotionSequence, name: str = "MotionCharacter",
                 placement: NDArray[np.float64] | None = None) -> None:
        self.motion: MotionSequence = motion
        self.placement: NDArray[np.float64] = (np.eye(4) if placement is None
                                               else np.asarray(placement, dtype=np.float64))
        _check_matrices("MotionPlayer()", "placement", self.placement, (4, 4))
        self.character: ASkeletalMeshActor = game.spawn_actor(uclass=ASkeletalMeshActor, name=name)
        self.mesh: USkeletalMeshComponent = self.character.SkeletalMeshComponent
        self.mesh.SetSkeletalMesh(NewMesh=motion.skeletal_mesh)
        mesh_bones = [self.mesh.GetBoneName(BoneIndex=i) for i in range(self.mesh.GetNumBones())]
        index = {bone: i for i, bone in enumerate(motion.bone_names)}
        missing = [bone for bone in mesh_bones if bone not in index]
        extra = sorted(set(motion.bone_names) - set(mesh_bones))
        if missing or extra:
            game.destroy_actor(actor=self.character)
            raise InvalidArgumentError(
                f"MotionPlayer(): the sequence's bones do not match {motion.skeletal_mesh}'s: "
                + "; ".join(part for part in (f"missing {', '.join(missing)}" if missing else "",
                                              f"not in the mesh {', '.join(extra)}" if extra else "") if part))
        # The sequence's bones in the mesh's order, once: each frame is then one array for SetBoneTransforms.
        self._order = np.array([index[bone] for bone in mesh_bones], dtype=np.intp)
        self.objects: list[AStaticMeshActor] = []
        for object_name, mesh in zip(motion.object_names, motion.object_meshes):
            actor = game.spawn_actor(uclass=AStaticMeshActor, name=object_name)
            actor.StaticMeshComponent.SetStaticMesh(NewMesh=mesh)
            self.objects.append(actor)

    def apply(self, frame: int) -> None:
        """Poses the character and places the objects as at `frame` (0 <= frame < motion.frames)."""
        if not 0 <= frame < self.motion.frames:
            raise InvalidArgumentError(f"MotionPlayer.apply(): frame {frame} is outside 0..{self.motion.frames - 1}")
        self.character.SetActorTransform(NewTransform=transform_of(self.placement @ self.motion.root_poses[frame]))
        pose = np.ascontiguousarray(self.motion.bone_poses[frame][self._order])
        self.mesh.SetBoneTransforms(Transforms=pose, Space=EBoneSpaces.ComponentSpace)
        if self.motion.object_poses is not None:
            for actor, matrix in zip(self.objects, self.motion.object_poses[frame]):
                actor.SetActorTransform(NewTransform=transform_of(self.placement @ matrix))
