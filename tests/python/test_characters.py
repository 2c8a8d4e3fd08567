"""Skeletal meshes (USkeletalMeshComponent, ASkeletalMeshActor): the built-in humanoid's skeleton, the bind pose
rendering as the same file's static mesh does, clips playing, whole poses read and set as arrays, bones as
sockets, and bad input refused with the pose left as it was; both transports."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

import spear
from test_character import course

ROOT = Path(__file__).resolve().parents[2]
HUMANOID = "/Game/characters/humanoid.glb"
M = spear.ECameraModality
WORLD, COMPONENT = spear.EBoneSpaces.WorldSpace, spear.EBoneSpaces.ComponentSpace


def _character(game: spear.UWorld, name: str = "Person", x: float = 0.0) -> spear.USkeletalMeshComponent:
    actor = game.spawn_actor(uclass=spear.ASkeletalMeshActor, name=name, location=spear.FVector(x, 0.0, 0.0))
    mesh = actor.SkeletalMeshComponent
    mesh.SetSkeletalMesh(NewMesh=HUMANOID)
    return mesh


def _front_camera(game: spear.UWorld, modalities: list[spear.ECameraModality], side: bool = False, size: int = 64
                  ) -> spear.UCameraSensorComponent:
    """A camera 4 m in front of a character at the origin looking back at it (it faces +X), or at its left side."""
    location, yaw = ((0.0, 4.0, 1.0), -90.0) if side else ((4.0, 0.0, 1.0), 180.0)
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(*location),
                              rotation=spear.FRotator(Yaw=yaw)).CameraSensor
    camera.Width, camera.Height, camera.FOV = size, size, 30.0
    camera.Modalities = modalities
    return camera


def test_the_humanoid_is_what_its_script_makes() -> None:
    # The committed character is generated, not edited: the script compares it with what it makes now.
    script = ROOT / "scripts" / "make_humanoid.py"
    result = subprocess.run([sys.executable, str(script), "--check"], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_humanoid_has_a_named_skeleton_and_clips(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mesh = _character(game, x=2.0)
        assert mesh.GetNumBones() == 18
        assert mesh.GetBoneName(BoneIndex=0) == "root"
        assert mesh.GetBoneIndex(BoneName="head") > 0
        assert mesh.GetBoneIndex(BoneName="tail") == -1
        assert mesh.GetAnimationNames() == ["idle", "walk", "run"]
        head = mesh.GetBoneTransform(BoneName="head", Space=WORLD)
        local = mesh.GetBoneTransform(BoneName="head", Space=COMPONENT)
    with instance.end_frame():
        pass
    assert (head.Translation.X, head.Translation.Y, head.Translation.Z) == pytest.approx((2.0, 0.0, 1.57), abs=1e-5)
    assert (local.Translation.X, local.Translation.Z) == pytest.approx((0.0, 1.57), abs=1e-5)


def test_the_bind_pose_renders_as_the_static_mesh_of_the_same_file(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        skinned = _character(game)
        # Large enough in the image that the static copy is drawn at full detail (imported static meshes get
        # simplified levels for where they are small; a skinned mesh never does).
        camera = _front_camera(game, [M.Depth, M.ObjectIds], size=256)
    with instance.end_frame():
        skinned_pixels = camera.read_pixels()
    with instance.begin_frame():
        skinned.bVisible = False
        static = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Statue").StaticMeshComponent
        static.SetStaticMesh(NewMesh=HUMANOID)
    with instance.end_frame():
        static_pixels = camera.read_pixels()
    skinned_depth, static_depth = skinned_pixels["depth"], static_pixels["depth"]
    assert (skinned_depth > 0).sum() > 5000  # the figure fills part of the view
    assert np.array_equal(skinned_depth > 0, static_depth > 0)
    # Within 2 mm (a pixel here is 8 mm across): the static copy's depth is its finest level's, which may still
    # leave out vertices whose removal moves no outline by half a pixel.
    assert np.abs(skinned_depth - static_depth).max() < 2e-3
    ids = np.unique(skinned_pixels["object_ids"])
    assert len(ids[ids != 0]) == 4  # skin, shirt, trousers, shoes: one id per material slot


def _silhouette(camera: spear.UCameraSensorComponent) -> NDArray[np.bool_]:
    return np.asarray(camera.read_pixels()["depth"] > 0)


def test_a_playing_clip_moves_the_limbs_and_the_image(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mesh = _character(game)
        camera = _front_camera(game, [M.Depth], side=True)  # from the side: the legs swing across the view
        bind_foot = mesh.GetBoneTransform(BoneName="foot_l", Space=COMPONENT).Translation
    with instance.end_frame():
        standing = _silhouette(camera)
    with instance.begin_frame():
        mesh.PlayAnimation(NewAnimToPlay="walk", bLoop=True)
        assert mesh.IsPlaying() and mesh.GetPlayLength() == pytest.approx(1.1, abs=1e-3)
    with instance.end_frame():
        pass
    for _ in range(16):  # 17 frames of 1/60 s: about a quarter of the 1.1 s cycle, the stride near its widest
        with instance.begin_frame():
            pass
        with instance.end_frame():
            pass
    with instance.begin_frame():
        position = mesh.GetPosition()
        foot = mesh.GetBoneTransform(BoneName="foot_l", Space=COMPONENT).Translation
    with instance.end_frame():
        walking = _silhouette(camera)
    assert position == pytest.approx(17 / 60, abs=1e-6)
    assert abs(foot.X - bind_foot.X) > 0.1  # the left leg swung along the walking direction
    assert (standing != walking).sum() > 40
    # Stopped, the pose stays; SetPosition poses it at once; a looping clip wraps around.
    with instance.begin_frame():
        mesh.Stop()
        held = mesh.GetBoneTransforms(Space=COMPONENT)
    with instance.end_frame():
        pass
    with instance.begin_frame():
        assert not mesh.IsPlaying()
        assert np.array_equal(mesh.GetBoneTransforms(Space=COMPONENT), held)
        mesh.SetPosition(InPos=0.0)
        assert not np.allclose(mesh.GetBoneTransforms(Space=COMPONENT)[:, :3, 3], held[:, :3, 3], atol=1e-3)
        mesh.PlayAnimation(NewAnimToPlay="run", bLoop=True)
        mesh.SetPosition(InPos=0.69)
    with instance.end_frame():
        pass
    with instance.begin_frame():
        assert mesh.GetPosition() == pytest.approx(0.69 + 1 / 60 - 0.7, abs=1e-6)  # past the end: from the start
    with instance.end_frame():
        pass


def test_a_whole_pose_is_read_and_set_as_one_array(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mesh = _character(game, x=1.0)
        pose = mesh.GetBoneTransforms(Space=COMPONENT)
        world = mesh.GetBoneTransforms(Space=WORLD)
    with instance.end_frame():
        pass
    assert pose.shape == (18, 4, 4) and pose.dtype == np.float64
    assert np.allclose(world[:, :3, 3] - pose[:, :3, 3], [1.0, 0.0, 0.0])
    # The head turned 90 degrees about Z, and its world pose set back: a round trip.
    head = 5
    turned = pose.copy()
    turned[head, :3, :3] = turned[head, :3, :3] @ np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    with instance.begin_frame():
        assert mesh.GetBoneName(BoneIndex=head) == "head"
        mesh.SetBoneTransforms(Transforms=turned, Space=COMPONENT)
        back = mesh.GetBoneTransforms(Space=COMPONENT)
        mesh.SetBoneTransforms(Transforms=world, Space=WORLD)
        restored = mesh.GetBoneTransforms(Space=COMPONENT)
    with instance.end_frame():
        pass
    assert np.allclose(back, turned, atol=1e-9)
    assert np.allclose(restored, pose, atol=1e-9)


def test_world_space_poses_follow_a_turned_and_scaled_component(instance: spear.Instance) -> None:
    """Each bone's world matrix is the component's world matrix times the bone's component-space one, for a
    component turned about two axes and scaled unevenly, as GetBoneTransform gives each bone."""
    game = instance.get_game()
    with instance.begin_frame():
        mesh = _character(game, x=1.0)
        mesh.SetRelativeRotation(NewRotation=spear.FRotator(Pitch=20.0, Yaw=35.0, Roll=-10.0))
        mesh.SetRelativeScale3D(NewScale3D=spear.FVector(1.5, 0.5, 2.0))
        pose = mesh.GetBoneTransforms(Space=COMPONENT)
        world = mesh.GetBoneTransforms(Space=WORLD)
        crowd = spear.USkeletalMeshComponent.GetBoneTransformsOfComponents(Components=[mesh], Space=WORLD)
        singles = [mesh.GetBoneTransform(BoneName=mesh.GetBoneName(BoneIndex=i), Space=WORLD) for i in range(18)]
        component = mesh.GetComponentTransform()
    with instance.end_frame():
        pass
    # The component's world matrix: its rotation's columns scaled, its translation.
    q = component.Rotation
    x, y, z, w = q.X, q.Y, q.Z, q.W
    rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    matrix = np.eye(4)
    matrix[:3, :3] = rotation * [component.Scale3D.X, component.Scale3D.Y, component.Scale3D.Z]
    matrix[:3, 3] = [component.Translation.X, component.Translation.Y, component.Translation.Z]
    assert not np.allclose(rotation, np.eye(3))
    assert np.allclose(world, matrix @ pose, atol=1e-12)
    assert np.array_equal(world[:, 3], np.tile([0.0, 0.0, 0.0, 1.0], (18, 1)))
    assert np.array_equal(crowd[0], world)
    for i, single in enumerate(singles):  # the translations: FTransform composes scale, rotation, translation
        assert (single.Translation.X, single.Translation.Y, single.Translation.Z) == pytest.approx(
            tuple(world[i, :3, 3]), abs=1e-9)


def test_a_crowds_poses_come_back_as_one_array(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        meshes = [_character(game, name=f"Person{i}", x=float(i)) for i in range(3)]
        meshes[1].PlayAnimation(NewAnimToPlay="run", bLoop=True)
        meshes[1].SetPosition(InPos=0.3)
        crowd = spear.USkeletalMeshComponent.GetBoneTransformsOfComponents(Components=meshes, Space=WORLD)
        each = [mesh.GetBoneTransforms(Space=WORLD) for mesh in meshes]
        other = game.spawn_actor(uclass=spear.ASkeletalMeshActor, name="Empty").SkeletalMeshComponent  # no mesh
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"GetBoneTransformsOfComponents\(\): Components\[1\] \(.*\) has 0 bones, Components\[0\] has 18"):
            spear.USkeletalMeshComponent.GetBoneTransformsOfComponents(Components=[meshes[0], other], Space=WORLD)
    with instance.end_frame():
        pass
    assert crowd.shape == (3, 18, 4, 4)
    for i in range(3):
        assert np.array_equal(crowd[i], each[i])


def test_a_camera_follows_a_bone_it_is_attached_to(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mesh = _character(game)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="HeadCamera").CameraSensor
        camera.AttachToComponent(Parent=mesh, SocketName="head")
        assert camera.AttachSocketName == "head"
        before = camera.GetComponentLocation()
        forward, up = camera.GetForwardVector(), camera.GetUpVector()
        mesh.PlayAnimation(NewAnimToPlay="run", bLoop=True)
        mesh.SetPosition(InPos=0.2)
        during = camera.GetComponentLocation()
        head = mesh.GetSocketTransform(InSocketName="head").Translation
        with pytest.raises(spear.NotFoundError, match=r"has no socket 'hat'"):
            camera.AttachToComponent(Parent=mesh, SocketName="hat")
    with instance.end_frame():
        pass
    assert (before.X, before.Z) == pytest.approx((0.0, 1.57), abs=1e-5)
    assert (forward.X, up.Z) == pytest.approx((1.0, 1.0), abs=1e-6)  # the bone's axes are the character's
    assert (during.X, during.Y, during.Z) == pytest.approx((head.X, head.Y, head.Z), abs=1e-9)
    assert abs(during.X - before.X) > 0.02  # running leans the upper body forward


def test_bad_input_is_refused_and_the_pose_is_left_as_it_was(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    static_file = tmp_path / "triangle.obj"
    static_file.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with instance.begin_frame():
        mesh = _character(game)
        pose = mesh.GetBoneTransforms(Space=COMPONENT)
        with pytest.raises(spear.InvalidArgumentError, match=r"Transforms must have shape \(18, 4, 4\), got \(17, 4, 4\)"):
            mesh.SetBoneTransforms(Transforms=pose[1:], Space=COMPONENT)
        broken = pose.copy()
        broken[3, 0, 0] = np.nan
        with pytest.raises(spear.InvalidArgumentError, match=r"Transforms\[3\] \('spine_02'\) is not finite"):
            mesh.SetBoneTransforms(Transforms=broken, Space=COMPONENT)
        broken = pose.copy()
        broken[2, 3, 0] = 1.0
        with pytest.raises(spear.InvalidArgumentError, match=r"has bottom row \(1, 0, 0, 1\)"):
            mesh.SetBoneTransforms(Transforms=broken, Space=COMPONENT)
        broken = pose.copy()
        broken[4, :3, :3] = 0.0
        with pytest.raises(spear.InvalidArgumentError, match=r"scales an axis to zero"):
            mesh.SetBoneTransforms(Transforms=broken, Space=COMPONENT)
        assert np.array_equal(mesh.GetBoneTransforms(Space=COMPONENT), pose)
        with pytest.raises(spear.NotFoundError, match=r"has no bone 'tail' \(its skeleton's bones: 'root', 'pelvis'"):
            mesh.GetBoneTransform(BoneName="tail", Space=WORLD)
        with pytest.raises(spear.InvalidArgumentError, match=r"GetBoneName\(\): BoneIndex 18 is out of range \[0, 18\)"):
            mesh.GetBoneName(BoneIndex=18)
        with pytest.raises(spear.NotFoundError, match=r"has no clip 'dance' \(its clips: 'idle', 'walk', 'run'"):
            mesh.PlayAnimation(NewAnimToPlay="dance", bLoop=True)
        with pytest.raises(spear.InvalidArgumentError, match=r"has no skeleton"):
            mesh.SetSkeletalMesh(NewMesh=str(static_file))
        with pytest.raises(spear.NotFoundError, match=r"no such file 'missing.glb'"):
            mesh.SetSkeletalMesh(NewMesh="missing.glb")
        with pytest.raises(spear.InvalidArgumentError, match=r"PlayRate must be finite"):
            mesh.SetPlayRate(Rate=float("inf"))
        assert mesh.SkeletalMesh == HUMANOID and mesh.GetNumBones() == 18
        assert np.array_equal(mesh.GetBoneTransforms(Space=COMPONENT), pose)
    with instance.end_frame():
        pass


def test_a_blend_space_mixes_clips_by_its_input(instance: spear.Instance) -> None:
    game = instance.get_game()
    samples = [spear.FBlendSample(Animation="idle", SampleValue=0.0),
               spear.FBlendSample(Animation="walk", SampleValue=1.25),
               spear.FBlendSample(Animation="run", SampleValue=3.2)]
    with instance.begin_frame():
        mesh = _character(game)
        mesh.SetBlendSpace(Samples=samples)
        mesh.SetBlendSpaceInput(Input=0.0)
        assert mesh.AnimationMode == spear.EAnimationMode.AnimationBlendSpace and mesh.IsPlaying()
        assert mesh.GetBlendSpaceWeights() == [1.0, 0.0, 0.0]
        mesh.SetBlendSpaceInput(Input=2.225)  # half way from walking to running
        assert mesh.GetBlendSpaceWeights() == pytest.approx([0.0, 0.5, 0.5])
        mesh.SetBlendSpaceInput(Input=9.0)  # faster than the run: the run alone, quicker
        assert mesh.GetBlendSpaceWeights() == [0.0, 0.0, 1.0]
        with pytest.raises(spear.InvalidArgumentError, match=r"BlendSpace\[1\]\.SampleValue = 0 must be finite and greater"):
            mesh.SetBlendSpace(Samples=[samples[0], spear.FBlendSample(Animation="walk", SampleValue=0.0)])
        with pytest.raises(spear.NotFoundError, match=r"has no clip 'dance'"):
            mesh.SetBlendSpace(Samples=[spear.FBlendSample(Animation="dance", SampleValue=0.0)])
        assert mesh.BlendSpace == samples  # unchanged by the refused ones
        mesh.PlayAnimation(NewAnimToPlay="walk", bLoop=True)  # one clip again
        assert mesh.AnimationMode == spear.EAnimationMode.AnimationSingleNode
    with instance.end_frame():
        pass


def test_a_character_is_a_humanoid_whose_legs_move_as_it_walks(instance: spear.Instance) -> None:
    game = instance.get_game()
    character, player = course(instance, 0.3)  # standing at the origin; nothing in its way along +Y
    with instance.begin_frame():
        body = character.Mesh
        assert body.SkeletalMesh == HUMANOID and body.GetNumBones() == 18
        feet = body.GetComponentLocation()
        standing = body.GetBlendSpaceWeights()
    with instance.end_frame():
        pass
    assert feet.Z == pytest.approx(0.0, abs=0.03)  # on the floor, at the capsule's bottom
    assert standing[0] == pytest.approx(1.0)  # idle
    for _ in range(40):  # walking along +Y at 1.25 m/s (the walk clip's own speed)
        with instance.begin_frame():
            character.CharacterMovement.MaxWalkSpeed = 1.25
            game.inject_input_for_actor(actor=player, input_action_name="MoveRight", value=spear.FVector(X=-1.0))
        with instance.end_frame():
            pass
    with instance.begin_frame():
        walking = body.GetBlendSpaceWeights()
        heading = body.GetComponentRotation().Yaw
        foot = body.GetBoneTransform(BoneName="foot_l", Space=spear.EBoneSpaces.ComponentSpace).Translation
    with instance.end_frame():
        pass
    assert walking[1] > 0.9  # the walk clip, at about its own speed
    with instance.begin_frame():
        character.SetActorLocation(NewLocation=spear.FVector(-10.0, 10.0, 0.95))  # a teleport is no run
    with instance.end_frame():
        pass
    with instance.begin_frame():
        after_teleport = body.GetBlendSpaceWeights()
        turned = body.GetComponentRotation().Yaw
    with instance.end_frame():
        pass
    assert after_teleport[2] == 0.0 and turned == pytest.approx(heading, abs=2.0)
    assert heading == pytest.approx(90.0, abs=2.0)  # the body turned to face +Y, where it walks
    assert abs(foot.X) > 0.03 or foot.Z > 0.12  # a foot off its standing place


def test_body_part_ids_tell_the_parts_apart(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mesh = _character(game)
        camera = _front_camera(game, [M.ObjectIds], size=128)
    with instance.end_frame():
        by_material = np.unique(camera.read_pixels()["object_ids"])
    with instance.begin_frame():
        assert mesh.GetBodyPartOfSlot(MaterialSlot=0) == ""  # off: a slot is a material
        mesh.bBodyPartIds = True
    with instance.end_frame():
        ids = camera.read_pixels()["object_ids"]
    with instance.begin_frame():
        parts: dict[str, int] = {}
        for object_id in np.unique(ids):
            found, actor, component, slot, material = camera.GetObjectIdInfo(ObjectId=int(object_id))
            if found and isinstance(component, spear.USkeletalMeshComponent):
                bone = component.GetBodyPartOfSlot(MaterialSlot=slot)
                parts[bone] = parts.get(bone, 0) + int((ids == object_id).sum())
        with pytest.raises(spear.InvalidArgumentError, match=r"GetBodyPartOfSlot\(\): MaterialSlot 999 is out of range"):
            mesh.GetBodyPartOfSlot(MaterialSlot=999)
    with instance.end_frame():
        pass
    assert len(by_material[by_material != 0]) == 4
    # Seen from the front: the head, both hands, both feet and the trunk, each its own ids.
    assert {"head", "hand_l", "hand_r", "foot_l", "foot_r", "spine_02", "thigh_l", "calf_r"} <= set(parts), parts
    assert parts["head"] > 20 and parts["spine_02"] > parts["hand_l"]


def test_characters_share_their_files_materials(instance: spear.Instance) -> None:
    # material_ids names a material, not a character: two humanoids show the file's four materials, not eight.
    game = instance.get_game()
    with instance.begin_frame():
        _character(game, name="Left", x=0.0)
        right = _character(game, name="Right", x=0.0)
        right.GetOwner().SetActorLocation(NewLocation=spear.FVector(0.0, -0.6, 0.0))  # type: ignore[union-attr]
        camera = _front_camera(game, [M.MaterialIds, M.ObjectIds], size=96)
    with instance.end_frame():
        pixels = camera.read_pixels()
    materials, objects = np.unique(pixels["material_ids"]), np.unique(pixels["object_ids"])
    assert len(materials[materials != 0]) == 4
    assert len(objects[objects != 0]) == 8  # one id per (character, slot)


def test_mesh_components_set_material_slots_alike(instance: spear.Instance) -> None:
    """SetMaterial grows a static or a skeletal mesh component's slot list, and refuses a slot outside
    [0, 256) naming the class, leaving the list as it was."""
    game = instance.get_game()
    with instance.begin_frame():
        skeletal = _character(game)
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box").StaticMeshComponent
        for component, owner in ((skeletal, "USkeletalMeshComponent"), (box, "UStaticMeshComponent")):
            component.SetMaterial(ElementIndex=2, Material="Paint")
            assert component.Materials == ["", "", "Paint"]
            for index in (-1, 256):
                with pytest.raises(spear.InvalidArgumentError,
                                   match=rf"^{owner}\.SetMaterial\(\): ElementIndex {index} is out of range \[0, 256\)$"):
                    component.SetMaterial(ElementIndex=index, Material="Paint")
            assert component.Materials == ["", "", "Paint"]
    with instance.end_frame():
        pass
