"""Negative typing case: misuse of motion sequences. Every marked line must be rejected by mypy --strict (`# E:`)
and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear
import spear.motion


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    player = spear.motion.MotionPlayer(game, "/Game/motions/carry_case.npz")  # E: Argument 2 to "MotionPlayer" has incompatible type "str"; expected "MotionSequence"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['/Game/motions/carry_case.npz']" cannot be assigned to parameter "motion" of type "MotionSequence" in function "__init__" / "Literal['/Game/motions/carry_case.npz']" is not assignable to "MotionSequence"
    motion = spear.motion.load_motion("/Game/motions/carry_case.npz")
    player.apply(frame=1.5)  # E: Argument "frame" to "apply" of "MotionPlayer" has incompatible type "float"; expected "int"  [arg-type]  # P: reportArgumentType: Argument of type "float" cannot be assigned to parameter "frame" of type "int" in function "apply" / "float" is not assignable to "int"
    motion.frames = 10  # E: Property "frames" defined in "MotionSequence" is read-only  [misc]  # P: reportAttributeAccessIssue: Cannot assign to attribute "frames" for class "MotionSequence" / "Literal[10]" is not assignable to "property"
    motion.bone_poses.shape.x  # E: "Tuple[int, ...]" has no attribute "x"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "x" for class "_Shape" / Attribute "x" is unknown
    spear.motion.MotionPlayer(game, motion, placement=[[1.0]])  # E: Argument "placement" to "MotionPlayer" has incompatible type "List[List[float]]"; expected "Optional[ndarray[Any, dtype[floating[_64Bit]]]]"  [arg-type]  # P: reportArgumentType: Argument of type "list[list[float]]" cannot be assigned to parameter "placement" of type "NDArray[float64] | None" in function "__init__" / Type "list[list[float]]" is not assignable to type "NDArray[float64] | None" / "list[list[float]]" is not assignable to "ndarray[Any, dtype[float64]]" / "list[list[float]]" is not assignable to "None"
    read = spear.USkeletalMeshComponent.ReadMotionFile(Filename="a.glb", Animation="walk", FrameRate=30.0)
    read["Bones"]  # E: TypedDict "FMotionFile" has no key "Bones"  [typeddict-item]  # P: reportGeneralTypeIssues: Could not access item in TypedDict / "Bones" is not a defined key in "FMotionFile"
    spear.motion.import_motion("a.glb", object_meshes=["Case"])  # E: Argument "object_meshes" to "import_motion" has incompatible type "List[str]"; expected "Optional[Mapping[str, str]]"  [arg-type]  # P: reportArgumentType: Argument of type "list[str]" cannot be assigned to parameter "object_meshes" of type "Mapping[str, str] | None" in function "import_motion" / Type "list[str]" is not assignable to type "Mapping[str, str] | None" / "list[str]" is not assignable to "Mapping[str, str]" / "list[str]" is not assignable to "None"
    spear.motion.import_motion("a.glb", "walk")  # E: Too many positional arguments for "import_motion"  [misc]  # P: reportCallIssue: Expected 1 positional argument
