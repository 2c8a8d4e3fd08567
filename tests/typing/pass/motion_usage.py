"""Positive typing case: motion sequences (spear.motion) loaded, checked and played, as a pipeline writes them."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

import spear
import spear.motion


def play(instance: spear.Instance, path: str) -> list[NDArray[np.uint32]]:
    motion: spear.motion.MotionSequence = spear.motion.load_motion(path)
    frames: int = motion.frames
    seconds: float = motion.duration
    assert seconds >= 0.0
    poses: NDArray[np.float64] = motion.bone_poses
    assert poses.shape[1] == len(motion.bone_names)
    game = instance.get_game()
    with instance.begin_frame():
        player = spear.motion.MotionPlayer(game, motion, placement=np.eye(4))
        character: spear.ASkeletalMeshActor = player.character
        objects: list[spear.AStaticMeshActor] = player.objects
        player.mesh.bBodyPartIds = True
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
        camera.Modalities = [spear.ECameraModality.ObjectIds]
        assert character.GetName() and len(objects) == len(motion.object_names)
    with instance.end_frame():
        pass
    ids: list[NDArray[np.uint32]] = []
    for frame in range(frames):
        with instance.begin_frame():
            player.apply(frame)
        with instance.end_frame():
            pixels = camera.read_pixels()
            assert "object_ids" in pixels
            ids.append(pixels["object_ids"])
    transform: spear.FTransform = spear.motion.transform_of(motion.root_poses[0])
    assert transform.Scale3D.X > 0.0
    return ids


def import_from_file(path: str) -> spear.motion.MotionSequence:
    read: spear.FMotionFile = spear.USkeletalMeshComponent.ReadMotionFile(Filename=path, Animation="walk",
                                                                          FrameRate=30.0)
    poses: NDArray[np.float64] = read["BoneTransforms"]
    objects: list[str] = read["ObjectNames"]
    assert poses.shape[1] == len(read["BoneNames"]) and read["ObjectTransforms"].shape[1] == len(objects)
    return spear.motion.import_motion(path, animation=read["Animation"], fps=read["FrameRate"],
                                      object_meshes={name: "/Engine/BasicShapes/Cube" for name in objects})
