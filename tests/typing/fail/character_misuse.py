"""Negative typing case: misuse of skeletal meshes. Every marked line must be rejected by mypy --strict (`# E:`)
and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    mesh = game.spawn_actor(uclass=spear.ASkeletalMeshActor).SkeletalMeshComponent
    mesh.GetBoneTransform(BoneName=3, Space=spear.EBoneSpaces.WorldSpace)  # E: Argument "BoneName" to "GetBoneTransform" of "USkeletalMeshComponent" has incompatible type "int"; expected "str"  [arg-type]  # P: reportArgumentType: Argument of type "Literal[3]" cannot be assigned to parameter "BoneName" of type "str" in function "GetBoneTransform" / "Literal[3]" is not assignable to "str"
    mesh.GetBoneTransform(BoneName="head", Space=spear.ESplineCoordinateSpace.World)  # E: Argument "Space" to "GetBoneTransform" of "USkeletalMeshComponent" has incompatible type "ESplineCoordinateSpace"; expected "EBoneSpaces"  [arg-type]  # P: reportArgumentType: Argument of type "Literal[ESplineCoordinateSpace.World]" cannot be assigned to parameter "Space" of type "EBoneSpaces" in function "GetBoneTransform" / "Literal[ESplineCoordinateSpace.World]" is not assignable to "EBoneSpaces"
    mesh.PlayAnimation(NewAnimToPlay="walk", bLooping=True)  # E: Unexpected keyword argument "bLooping" for "PlayAnimation" of "USkeletalMeshComponent"; did you mean "bLoop"?  [call-arg]  # P: reportCallIssue: Argument missing for parameter "bLoop"  # P: reportCallIssue: No parameter named "bLooping"
    mesh.AnimationToPlay = "run"  # E: "USkeletalMeshComponent" has no attribute "AnimationToPlay"; maybe "AnimToPlay"?  [attr-defined]  # P: reportAttributeAccessIssue: Cannot assign to attribute "AnimationToPlay" for class "USkeletalMeshComponent" / Attribute "AnimationToPlay" is unknown
    mesh.SetBoneTransforms(Transforms=[[1.0]], Space=spear.EBoneSpaces.ComponentSpace)  # E: Argument "Transforms" to "SetBoneTransforms" of "USkeletalMeshComponent" has incompatible type "List[List[float]]"; expected "ndarray[Any, dtype[floating[_64Bit]]]"  [arg-type]  # P: reportArgumentType: Argument of type "list[list[float]]" cannot be assigned to parameter "Transforms" of type "NDArray[float64]" in function "SetBoneTransforms" / "list[list[float]]" is not assignable to "ndarray[Any, dtype[float64]]"
    mesh.GetBoneTransforms().shape.x  # E: "Tuple[int, ...]" has no attribute "x"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "x" for class "_Shape" / Attribute "x" is unknown
