"""The reflected world API, end to end from Python: every engine function and property."""

from __future__ import annotations

import math
import re

import pytest

import spear


def close(a: spear.FVector, b: spear.FVector, tol: float = 1e-9) -> bool:
    return abs(a.X - b.X) < tol and abs(a.Y - b.Y) < tol and abs(a.Z - b.Z) < tol


def test_spawn_find_destroy_round_trip(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        a = game.spawn_actor(uclass=spear.AStaticMeshActor, name="A", location=spear.FVector(1, 2, 3), tags=["t"])
        b = game.spawn_actor(uclass="AActor", name="B")
        assert isinstance(a, spear.AStaticMeshActor) and isinstance(a, spear.AActor)
        assert type(b).__name__ == "AActor"
        assert a.GetName() == "A" and a.GetClassName() == "AStaticMeshActor"
        assert close(a.GetActorLocation(), spear.FVector(1, 2, 3))
        assert game.find_actor_by_name(name="A") == a
        assert game.find_actor_by_name(name="nobody") is None
        assert game.find_actors_by_tag(tag="t") == [a]
        assert game.get_actor_count() == 2
        game.destroy_actor(actor=b)
        assert game.get_actor_count() == 1
        assert not b.is_valid() and a.is_valid()


def test_class_queries_respect_hierarchy(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mesh = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Mesh")
        plain = game.spawn_actor(uclass=spear.AActor, name="Plain")
        assert game.find_actors_by_class(uclass=spear.AActor) == [mesh, plain]
        assert game.find_actors_by_class(uclass=spear.AStaticMeshActor) == [mesh]
        assert game.find_actor_by_class(uclass=spear.AStaticMeshActor) == mesh
        assert game.find_actors_by_class_as_dict(uclass="AActor") == {"Mesh": mesh, "Plain": plain}
        comps = game.get_components_by_class(actor=mesh, uclass=spear.USceneComponent)
        assert [c.GetName() for c in comps] == ["StaticMeshComponent"]
        assert isinstance(comps[0], spear.UStaticMeshComponent)
        assert game.get_components_by_class_as_dict(actor=mesh, uclass=spear.UActorComponent) == {
            "StaticMeshComponent": mesh.StaticMeshComponent
        }
        assert game.get_component_by_name(actor=mesh, component_name="StaticMeshComponent") == mesh.RootComponent
        assert mesh.GetComponentByClass(ComponentClass=spear.UPrimitiveComponent) == mesh.StaticMeshComponent
        assert plain.GetComponentByClass(ComponentClass=spear.UPrimitiveComponent) is None


def test_unknown_and_abstract_classes_are_clear_errors(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        with pytest.raises(spear.NotFoundError, match=r"UWorld.spawn_actor\(\): argument 'uclass': class 'AFoo' is not registered"):
            game.spawn_actor(uclass="AFoo")
        with pytest.raises(spear.InvalidArgumentError, match="class 'UObject' does not derive from AActor"):
            game.spawn_actor(uclass="UObject")
        with pytest.raises(spear.InvalidArgumentError, match="name 'X' is already used"):
            game.spawn_actor(uclass=spear.AActor, name="X")
            game.spawn_actor(uclass=spear.AActor, name="X")
        assert game.get_actor_count() == 1  # the engine kept running


def test_destroyed_object_raises_stale_error(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Gone")
        component = actor.StaticMeshComponent
        game.destroy_actor(actor=actor)
        with pytest.raises(spear.StaleObjectError, match=r"AActor.GetActorLocation\(\): AStaticMeshActor 'Gone' \(handle \d+:\d+\) was destroyed"):
            actor.GetActorLocation()
        with pytest.raises(spear.StaleObjectError, match="UStaticMeshComponent 'StaticMeshComponent'"):
            component.GetComponentLocation()
        with pytest.raises(spear.StaleObjectError):
            game.destroy_actor(actor=actor)
        assert "destroyed" in repr(actor)


def test_calls_outside_a_frame_are_rejected(instance: spear.Instance) -> None:
    game = instance.get_game()
    with pytest.raises(spear.InvalidStateError, match=r"UWorld.get_actor_count\(\): called outside a frame"):
        game.get_actor_count()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AActor)
    with pytest.raises(spear.InvalidStateError, match="outside a frame"):
        actor.GetActorLocation()
    with instance.end_frame():
        assert actor.GetName() == "Actor_0"


def test_exception_in_frame_leaves_engine_usable(instance: spear.Instance) -> None:
    game = instance.get_game()
    with pytest.raises(ZeroDivisionError):
        with instance.begin_frame():
            game.spawn_actor(uclass=spear.AActor, name="Before")
            1 / 0
    with instance.begin_frame():
        assert game.find_actor_by_name(name="Before") is not None
    with instance.end_frame():
        pass
    with pytest.raises(spear.InvalidStateError, match="no frame has run"):
        with instance.end_frame():
            pass


def test_a_frame_begun_twice_runs_nothing_of_the_inner_block(instance: spear.Instance) -> None:
    # Over RPC a frame's begin travels with the calls of its block and the frame's execution; when it fails
    # they must not run, or the inner block would execute the frame the outer one holds.
    game = instance.get_game()
    count = instance.frame_count
    with pytest.raises(spear.InvalidStateError, match=r"^begin_frame\(\): the engine is inside begin_frame, expected idle$"):
        with instance.begin_frame():
            with instance.begin_frame():
                game.send_async.spawn_actor(uclass=spear.AActor, name="Inner")
    assert instance.frame_count == count + 1  # the outer frame ended (aborted: it ticked, then closed)
    with instance.begin_frame():
        assert game.find_actor_by_name(name="Inner") is None  # the inner block's call never ran
    with instance.end_frame():
        pass
    assert instance.frame_count == count + 2


def test_whole_number_floats_stay_floats(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=0.0, Y=2.0, Z=1.0))
        location = actor.GetActorLocation()
        assert [type(c) for c in (location.X, location.Y, location.Z)] == [float, float, float]
        assert type(game.get_time_seconds()) is float
        component = actor.StaticMeshComponent
        component.RelativeLocation = spear.FVector(X=-0.0, Y=3.0, Z=-4.0)
        stored = component.RelativeLocation
        assert stored == spear.FVector(X=0.0, Y=3.0, Z=-4.0) and type(stored.Z) is float
        assert math.copysign(1.0, stored.X) == -1.0  # the sign of zero survives too


def test_frame_state_follows_the_frame_protocol(instance: spear.Instance) -> None:
    assert instance.frame_state == "idle"
    with instance.begin_frame():
        assert instance.frame_state == "inside begin_frame"
    assert instance.frame_state == "between begin_frame and end_frame"
    with instance.end_frame():
        assert instance.frame_state == "inside end_frame"
    assert instance.frame_state == "idle"


def test_frames_advance_time_with_a_fixed_step(instance: spear.Instance) -> None:
    game = instance.get_game()
    instance.step(num_frames=3)
    with instance.begin_frame():
        assert game.get_frame_count() == 3
        assert game.get_time_seconds() == pytest.approx(3 / 60)
    with instance.end_frame():
        assert game.get_frame_count() == 4


def test_frame_timings_count_each_stage_of_the_frames(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        empty = game.get_frame_timings()
        assert empty == spear.FFrameTimings()  # nothing ticked yet
        cube = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=2.0))
        cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        cube.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, location=spear.FVector(X=-5.0, Z=1.0))
        camera.CameraSensor.Width, camera.CameraSensor.Height = 16, 16
    with instance.end_frame():
        pass
    with instance.begin_frame():
        before = game.get_frame_timings()
    with instance.end_frame():
        pass
    instance.step(num_frames=3)
    with instance.begin_frame():
        after = game.get_frame_timings()
    with instance.end_frame():
        pass
    assert after.Frames - before.Frames == 4
    assert after.PhysicsMs > before.PhysicsMs  # a body fell
    assert after.RenderingMs > before.RenderingMs  # a camera rendered
    for stage in ("ActorsMs", "PhysicsMs", "RenderingMs", "OtherMs"):
        assert getattr(after, stage) >= getattr(before, stage) >= 0.0, stage


def test_properties_read_write_with_types(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
        comp = actor.StaticMeshComponent
        assert comp.Mobility is spear.EComponentMobility.Movable
        comp.RelativeLocation = spear.FVector(0.0, 0.0, 2.0)
        assert comp.RelativeLocation == spear.FVector(0.0, 0.0, 2.0)
        assert close(actor.GetActorLocation(), spear.FVector(0, 0, 2))
        comp.Materials = ["red", "blue"]
        assert comp.Materials == ["red", "blue"]
        comp.SetMaterial(ElementIndex=3, Material="green")
        assert comp.Materials == ["red", "blue", "", "green"]
        actor.Tags = ["a", "b"]
        assert actor.ActorHasTag(Tag="b") and not actor.ActorHasTag(Tag="c")
        comp.bVisible = False
        assert comp.bVisible is False
        with pytest.raises(AttributeError):
            actor.RootComponent = comp  # type: ignore[misc]
        with pytest.raises(TypeError):
            comp.RelativeLocation = (1.0, 2.0, 3.0)  # type: ignore[assignment]


def test_static_components_refuse_to_move(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Wall")
        comp = actor.StaticMeshComponent
        comp.SetMobility(NewMobility=spear.EComponentMobility.Static)
        with pytest.raises(spear.InvalidStateError, match="is static; set its Mobility to Movable"):
            actor.SetActorLocation(NewLocation=spear.FVector(1, 0, 0))
        with pytest.raises(spear.InvalidStateError, match="is static"):
            comp.RelativeLocation = spear.FVector(1, 0, 0)
        assert comp.RelativeLocation == spear.FVector()
        comp.Mobility = spear.EComponentMobility.Movable
        assert actor.SetActorLocation(NewLocation=spear.FVector(1, 0, 0))


def test_transforms_and_attachment(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        parent = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(1, 0, 0))
        child = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(1, 1, 0))
        parent.SetActorRotation(NewRotation=spear.FRotator(Yaw=90.0))
        rot = parent.GetActorRotation()
        assert rot.Yaw == pytest.approx(90.0) and rot.Pitch == pytest.approx(0.0, abs=1e-9)
        forward = parent.GetActorForwardVector()
        assert close(forward, spear.FVector(0, 1, 0), 1e-9)  # Yaw turns X toward Y
        child.RootComponent.AttachToComponent(Parent=parent.RootComponent, bKeepWorldTransform=True)
        assert close(child.GetActorLocation(), spear.FVector(1, 1, 0), 1e-9)
        assert child.RootComponent.GetAttachParent() == parent.RootComponent
        assert parent.RootComponent.GetChildrenComponents(bIncludeAllDescendants=True) == [child.RootComponent]
        parent.SetActorLocation(NewLocation=spear.FVector(2, 0, 0))
        assert close(child.GetActorLocation(), spear.FVector(2, 1, 0), 1e-9)
        with pytest.raises(spear.InvalidArgumentError, match="would make a cycle"):
            parent.RootComponent.AttachToComponent(Parent=child.RootComponent)
        child.RootComponent.DetachFromComponent()
        assert child.RootComponent.GetAttachParent() is None
        assert close(child.GetActorLocation(), spear.FVector(2, 1, 0), 1e-9)
        t = parent.GetActorTransform()
        assert isinstance(t, spear.FTransform) and t.Scale3D == spear.FVector(1, 1, 1)
        parent.SetActorScale3D(NewScale3D=spear.FVector(2, 2, 2))
        assert parent.GetActorScale3D() == spear.FVector(2, 2, 2)
        pitched = game.spawn_actor(uclass=spear.AStaticMeshActor, rotation=spear.FRotator(Pitch=30.0))
        up = pitched.RootComponent.GetForwardVector()
        assert up.Z == pytest.approx(math.sin(math.radians(30)))  # Pitch raises X toward +Z


def test_out_parameters_come_back_as_named_tuple(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(0, 0, 1))
        actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        actor.SetActorScale3D(NewScale3D=spear.FVector(2, 4, 6))
        bounds = actor.GetActorBounds(bOnlyCollidingComponents=False)
        assert isinstance(bounds, spear.AActor.GetActorBoundsResult)
        assert close(bounds.Origin, spear.FVector(0, 0, 1)) and close(bounds.BoxExtent, spear.FVector(1, 2, 3))
        origin, extent = actor.StaticMeshComponent.GetBounds()
        assert close(extent, spear.FVector(1, 2, 3))
        with pytest.raises(spear.NotFoundError, match=r"SetStaticMesh\(\): '/Engine/BasicShapes/Teapot' is not a built-in "
                                                      r"shape \(/Engine/BasicShapes/Cube, /Engine/BasicShapes/Sphere, "):
            actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Teapot")
        with pytest.raises(spear.NotFoundError, match=r"SetStaticMesh\(\): mesh file 'meshes/no_such_mesh.ply' not found "
                                                      r"\(looked for in the working directory, "):
            actor.StaticMeshComponent.SetStaticMesh(NewMesh="meshes/no_such_mesh.ply")


def test_keyword_only_and_argument_checks(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AActor)
        with pytest.raises(TypeError):
            actor.SetActorLocation(spear.FVector())  # type: ignore[misc]
        with pytest.raises(TypeError):
            actor.SetActorLocation(NewLocaton=spear.FVector())  # type: ignore[call-arg]
        with pytest.raises(TypeError):
            actor.SetActorLocation(NewLocation="here")  # type: ignore[arg-type]
        with pytest.raises(spear.InvalidArgumentError, match="ElementIndex -1 is out of range"):
            game.spawn_actor(uclass=spear.AStaticMeshActor).StaticMeshComponent.SetMaterial(ElementIndex=-1, Material="x")


def test_default_object_lives_outside_the_world(instance: spear.Instance) -> None:
    game = instance.get_game()
    cdo = None
    with instance.begin_frame():
        cdo = game.get_default_object(uclass=spear.AStaticMeshActor)
        assert cdo.GetName() == "Default__AStaticMeshActor"
        assert cdo.GetWorld() is None
        assert game.get_actor_count() == 0
    assert cdo.GetName() == "Default__AStaticMeshActor"  # usable outside frames: it is not in a world


def test_dynamic_access_goes_through_the_registry(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Dyn")
        comp = actor.StaticMeshComponent
        instance.set_property(uobject=comp, path="RelativeLocation", value=spear.FVector(1, 2, 3))
        assert instance.get_property(uobject=comp, path="RelativeLocation") == spear.FVector(1, 2, 3)
        instance.set_property(uobject=comp, path="RelativeLocation.Z", value=9.0)
        assert instance.get_property(uobject=comp, path="RelativeLocation.Z") == 9.0
        assert instance.get_property(uobject=comp, path="Mobility") is spear.EComponentMobility.Movable
        loc = instance.call_function(uobject=actor, function="GetActorLocation")
        assert loc == spear.FVector(1, 2, 9)
        found = instance.call_function(uobject=game, function="find_actors_by_class", args={"uclass": spear.AActor})
        assert found == [actor]
        out = instance.call_function(uobject=actor, function="GetActorBounds", args={"bOnlyCollidingComponents": False})
        assert set(out) == {"Origin", "BoxExtent"}
        with pytest.raises(spear.NotFoundError, match="class 'AStaticMeshActor' has no function 'Fly'"):
            instance.call_function(uobject=actor, function="Fly")
        with pytest.raises(spear.NotFoundError, match="has no property 'Colour'"):
            instance.get_property(uobject=actor, path="Colour")
        with pytest.raises(spear.InvalidArgumentError, match="unexpected argument 'NewLocaton'"):
            instance.call_function(uobject=actor, function="SetActorLocation", args={"NewLocaton": spear.FVector()})
        with pytest.raises(spear.InvalidArgumentError, match="missing argument 'NewLocation'"):
            instance.call_function(uobject=actor, function="SetActorLocation")
        with pytest.raises(spear.InvalidArgumentError, match="argument 'NewLocation' must be FVector, got str"):
            instance.call_function(uobject=actor, function="SetActorLocation", args={"NewLocation": "x"})
        with pytest.raises(spear.InvalidArgumentError, match="is read-only"):
            instance.set_property(uobject=actor, path="RootComponent", value=None)
        # An enum takes its own enum's values only (a bare int is refused on both transports).
        with pytest.raises(spear.InvalidArgumentError, match="Mobility must be EComponentMobility, got int 3"):
            instance.set_property(uobject=comp, path="Mobility", value=3)
        instance.set_property(uobject=comp, path="Mobility", value=spear.EComponentMobility.Movable)
        assert comp.Mobility is spear.EComponentMobility.Movable


def test_property_paths_reach_through_references_lists_and_dicts(instance: spear.Instance) -> None:
    # One walk of the path, in the engine (core/reflect/property_path.h), for both transports: the same values
    # and the same errors, each naming the segment that is not there.
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate")
        actor.Tags = ["crate", "prop"]
        actor.StaticMeshComponent.SetMaterial(ElementIndex=1, Material="Gold")
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
        library.SetMaterial(Name="Red", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(1.0, 0.0, 0.0, 1.0)))
        get = lambda o, p: instance.get_property(uobject=o, path=p)  # noqa: E731
        assert get(actor, "Tags[1]") == "prop"
        assert get(actor, "StaticMeshComponent.Materials[1]") == "Gold"
        assert get(actor, "RootComponent.RelativeScale3D.X") == 1.0
        assert get(library, "Materials[Red].BaseColor") == spear.FLinearColor(1.0, 0.0, 0.0, 1.0)
        assert get(library, "Materials['Red'].BaseColor.R") == 1.0
        assert isinstance(get(actor, "RootComponent"), spear.UStaticMeshComponent)

        instance.set_property(uobject=actor, path="StaticMeshComponent.RelativeScale3D.X", value=2.0)
        instance.set_property(uobject=actor, path="RootComponent.RelativeLocation.Z", value=3.0)
        instance.set_property(uobject=actor, path="Tags[0]", value="box")
        instance.set_property(uobject=library, path="Materials[Blue]", value=spear.FMaterialDesc(Roughness=0.25))
        assert actor.StaticMeshComponent.RelativeScale3D.X == 2.0 and actor.GetActorLocation().Z == 3.0
        assert actor.Tags == ["box", "prop"]
        assert library.GetMaterial(Name="Blue").Roughness == 0.25
        # Written through the property's setter, so a bad value is refused as any write would refuse it.
        with pytest.raises(spear.InvalidArgumentError, match=r"SetMaterials\(\): material 'Blue': Roughness must be in \[0, 1\], got 3"):
            instance.set_property(uobject=library, path="Materials[Blue].Roughness", value=3.0)

        for path, error, message in [
            ("RootComponent.NoSuch", spear.NotFoundError,
             r"class 'UStaticMeshComponent' has no property 'NoSuch' \(at 'RootComponent'\)"),
            ("RootComponent.RelativeLocation.Q", spear.NotFoundError,
             r"struct 'FVector' has no field 'Q' \(at 'RootComponent.RelativeLocation'\)"),
            ("Tags[2]", spear.NotFoundError, r"'Tags' has 2 items, no \[2\]"),
            ("Tags[first]", spear.InvalidArgumentError, r"'Tags' is a list, indexed by a number, not 'first'"),
            ("Tags.Length", spear.NotFoundError, r"'Tags' is list\[str\], which has no field 'Length'"),
            ("Tags[", spear.InvalidArgumentError, r"property path 'Tags\[' expects an index or key in \[\]"),
        ]:
            with pytest.raises(error, match=rf"^get_property\('{re.escape(path)}'\): {message}"):
                get(actor, path)
        with pytest.raises(spear.NotFoundError, match=r"'Materials' has no key 'Green' \(its keys: 'Blue', 'Red'\)"):
            get(library, "Materials[Green].BaseColor")
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^set_property\('RootComponent'\): property 'RootComponent' of class "
                                 r"'AStaticMeshActor' is read-only"):
            instance.set_property(uobject=actor, path="RootComponent", value=None)


def test_editor_world_needs_an_editor_instance(instance: spear.Instance) -> None:
    with pytest.raises(spear.InvalidStateError, match="runs standalone and has no editor world"):
        instance.get_editor()


def test_batched_locations_travel_as_numpy_arrays(instance: spear.Instance) -> None:
    import numpy as np

    game = instance.get_game()
    with instance.begin_frame():
        actors = [game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=float(i))) for i in range(4)]
        locations = game.get_actor_locations(actors=actors)
        assert locations.dtype == np.float64 and locations.shape == (4, 3)
        assert list(locations[:, 0]) == [0.0, 1.0, 2.0, 3.0]
        targets = np.arange(12, dtype=np.float64).reshape(4, 3)
        game.set_actor_locations(actors=actors, locations=targets)
        assert actors[2].GetActorLocation() == spear.FVector(X=6.0, Y=7.0, Z=8.0)
        assert np.array_equal(game.get_actor_locations(actors=actors), targets)
        big = [game.spawn_actor(uclass=spear.AStaticMeshActor) for _ in range(3000)]  # > 64 KiB: shared memory
        moved = np.random.default_rng(1).normal(size=(3000, 3))
        game.set_actor_locations(actors=big, locations=moved)
        assert np.array_equal(game.get_actor_locations(actors=big), moved)
        with pytest.raises(TypeError, match=r"set_actor_locations\(\): argument 'locations' must have dtype float64, got float32"):
            game.set_actor_locations(actors=actors, locations=targets.astype(np.float32))
        with pytest.raises(spear.InvalidArgumentError, match=r"locations must have shape \(4, 3\), got \(3,\)"):
            game.set_actor_locations(actors=actors, locations=np.zeros(3))


def test_components_are_added_to_a_running_actor_and_work_at_once(instance: spear.Instance) -> None:
    # A camera on a spawned robot, attached to its head, and a light on it: UE's AddComponentByClass, typed as
    # the class asked for, named after it, attached where asked, working in the next frame.
    game = instance.get_game()
    with instance.begin_frame():
        robot = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Robot", location=spear.FVector(X=1.0))
        head = robot.AddComponentByClass(ComponentClass=spear.UStaticMeshComponent, Name="Head",
                                         RelativeTransform=spear.FTransform(Translation=spear.FVector(Z=1.5)))
        assert isinstance(head, spear.UStaticMeshComponent)
        head.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        camera = robot.AddComponentByClass(
            ComponentClass=spear.UCameraSensorComponent, AttachParent="Head",
            RelativeTransform=spear.FTransform(Translation=spear.FVector(X=0.5)))
        assert isinstance(camera, spear.UCameraSensorComponent)  # typed: its own members without a cast
        camera.Width, camera.Height = 16, 12
        camera.Modalities = [spear.ECameraModality.Depth]
        lamp = robot.AddComponentByClass(ComponentClass=spear.UPointLightComponent)
        again = robot.AddComponentByClass(ComponentClass=spear.UPointLightComponent)
        assert (camera.GetName(), lamp.GetName(), again.GetName()) == (
            "CameraSensorComponent", "PointLightComponent", "PointLightComponent_1")
        assert camera.GetAttachParent() == head
        assert camera.GetComponentLocation() == spear.FVector(X=1.5, Z=1.5)
        assert game.get_component_by_name(actor=robot, component_name="Head") == head
    with instance.end_frame():
        assert camera.read_pixels()["depth"].shape == (12, 16)
    with instance.begin_frame():
        robot.K2_DestroyComponent(Component=again)
        assert [c.GetName() for c in robot.K2_GetComponents()] == [
            "StaticMeshComponent", "Head", "CameraSensorComponent", "PointLightComponent"]
        with pytest.raises(spear.StaleObjectError):
            again.GetName()
        with pytest.raises(spear.InvalidArgumentError, match=(
                r"AActor\.AddComponentByClass\(\): AStaticMeshActor 'Robot' already has a component named 'Head'")):
            robot.AddComponentByClass(ComponentClass=spear.USceneComponent, Name="Head")
        with pytest.raises(spear.InvalidArgumentError, match=(
                r"AttachParent 'Hand' is not a scene component of AStaticMeshActor 'Robot'")):
            robot.AddComponentByClass(ComponentClass=spear.USceneComponent, AttachParent="Hand")
        with pytest.raises(spear.InvalidArgumentError, match=r"the root component of AStaticMeshActor 'Robot'"):
            robot.K2_DestroyComponent(Component=robot.StaticMeshComponent)
