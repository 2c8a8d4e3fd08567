#!/usr/bin/env python3
"""Writes assets/motions/carry_case.npz: a human-object motion sequence (spear.motion's format) of the built-in
humanoid walking 2.5 m with a case in its right hand, 60 frames at 30 frames per second.

Recorded with the engine itself, so the file is the project's own (CC0 1.0 like the rest of assets/): the
humanoid's walk clip sampled at each frame's time (USkeletalMeshComponent.SetPosition) gives the bone poses
(component space); the character's root moves forward at the clip's stride speed; the case is held 12 cm below
the right hand's bone, so its trajectory swings with the arm. Frame 0 stands at the origin facing +X: a player
places the sequence where it wants it (spear.motion.MotionPlayer's placement).

    PYTHONPATH=python /usr/bin/python3 scripts/make_motion.py            # writes the file
    PYTHONPATH=python /usr/bin/python3 scripts/make_motion.py --check    # exit 1 unless the committed file is
                                                                          # what it records
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import spear
import spear.motion

OUT = Path(__file__).resolve().parent.parent / "assets" / "motions" / "carry_case.npz"
HUMANOID = "/Game/characters/humanoid.glb"
FPS, FRAMES = 30.0, 60
WALK_SPEED = 1.25  # metres per second: the walk clip's stride (as ACharacter's blend space has it)
CASE_SIZE = (0.32, 0.10, 0.24)  # metres: the case's length (forward), width and height
CASE_BELOW_HAND = 0.12  # metres from the hand bone down to the case's centre


def record() -> spear.motion.MotionSequence:
    instance = spear.Instance()
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.ASkeletalMeshActor, name="Recorder")
        mesh = actor.SkeletalMeshComponent
        mesh.SetSkeletalMesh(NewMesh=HUMANOID)
        mesh.SetAnimToPlay(NewAnimToPlay="walk")
        names = tuple(mesh.GetBoneName(BoneIndex=i) for i in range(mesh.GetNumBones()))
        hand = names.index("hand_r")
        length = mesh.GetPlayLength()
        poses = []
        for frame in range(FRAMES):
            mesh.SetPosition(InPos=(frame / FPS) % length)
            poses.append(mesh.GetBoneTransforms(Space=spear.EBoneSpaces.ComponentSpace))
    with instance.end_frame():
        pass
    instance.close()

    bone_poses = np.stack(poses)
    root_poses = np.tile(np.eye(4), (FRAMES, 1, 1))
    root_poses[:, 0, 3] = WALK_SPEED * np.arange(FRAMES) / FPS
    case_in_hand = np.diag([*CASE_SIZE, 1.0])
    case_in_hand[2, 3] = -CASE_BELOW_HAND
    case_poses = root_poses @ bone_poses[:, hand] @ case_in_hand
    return spear.motion.MotionSequence(
        fps=FPS, skeletal_mesh=HUMANOID, bone_names=names, bone_poses=bone_poses, root_poses=root_poses,
        object_names=("Case",), object_meshes=("/Engine/BasicShapes/Cube",), object_poses=case_poses[:, None])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--check", action="store_true", help="compare with the committed file instead of writing")
    args = parser.parse_args()
    motion = record()
    if args.check:
        committed = spear.motion.load_motion(OUT)
        assert committed.object_poses is not None and motion.object_poses is not None
        same = (committed.bone_names == motion.bone_names and committed.object_meshes == motion.object_meshes
                and committed.fps == motion.fps and committed.skeletal_mesh == motion.skeletal_mesh
                and all(np.allclose(a, b, atol=1e-9) for a, b in (
                    (committed.bone_poses, motion.bone_poses), (committed.root_poses, motion.root_poses),
                    (committed.object_poses, motion.object_poses))))
        print(f"{OUT}: {'matches' if same else 'differs from'} what scripts/make_motion.py records")
        return 0 if same else 1
    OUT.parent.mkdir(parents=True, exist_ok=True)
    spear.motion.save_motion(motion, OUT)
    print(f"wrote {OUT}: {motion.frames} frames at {motion.fps:g} fps, {len(motion.bone_names)} bones, "
          f"objects {', '.join(motion.object_names)} ({OUT.stat().st_size // 1024} KiB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
