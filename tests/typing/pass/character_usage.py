"""Positive typing case: skeletal meshes, their bones, clips, whole poses and sockets."""

from __future__ import annotations

from typing import assert_type

import numpy as np
from numpy.typing import NDArray

import spear


def animate(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        person = game.spawn_actor(uclass=spear.ASkeletalMeshActor, name="Person")
        mesh = person.SkeletalMeshComponent
        assert_type(mesh, spear.USkeletalMeshComponent)
        assert_type(mesh.SetSkeletalMesh(NewMesh="/Game/characters/humanoid.glb"), bool)
        assert_type(mesh.GetNumBones(), int)
        assert_type(mesh.GetBoneName(BoneIndex=0), str)
        assert_type(mesh.GetBoneIndex(BoneName="head"), int)
        assert_type(mesh.GetBoneTransform(BoneName="head", Space=spear.EBoneSpaces.WorldSpace), spear.FTransform)
        assert_type(mesh.GetAnimationNames(), list[str])
        mesh.PlayAnimation(NewAnimToPlay="walk", bLoop=True)
        mesh.PlayRate = 1.5
        assert_type(mesh.GetPosition(), float)
        pose = mesh.GetBoneTransforms(Space=spear.EBoneSpaces.ComponentSpace)
        assert_type(pose, NDArray[np.float64])
        mesh.SetBoneTransforms(Transforms=pose, Space=spear.EBoneSpaces.ComponentSpace)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="HeadCamera").CameraSensor
        camera.AttachToComponent(Parent=mesh, SocketName="head")
        assert_type(mesh.GetSocketTransform(InSocketName="head"), spear.FTransform)
        assert_type(camera.AttachSocketName, str)
        mesh.bBodyPartIds = True  # object_ids per body part
        assert_type(mesh.GetBodyPartOfSlot(MaterialSlot=0), str)
        mesh.SetBlendSpace(Samples=[spear.FBlendSample(Animation="idle", SampleValue=0.0),
                                    spear.FBlendSample(Animation="walk", SampleValue=1.25)])
        mesh.SetBlendSpaceInput(Input=0.6)
        assert_type(mesh.GetBlendSpaceWeights(), list[float])
        crowd = spear.USkeletalMeshComponent.GetBoneTransformsOfComponents(Components=[mesh],
                                                                          Space=spear.EBoneSpaces.WorldSpace)
        assert_type(crowd, NDArray[np.float64])
    with instance.end_frame():
        pass
