"""Physics in the world: bodies for primitive components, resting heights, determinism, traces, forces."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import spear

CUBE = "/Engine/BasicShapes/Cube"
SPHERE = "/Engine/BasicShapes/Sphere"
CYLINDER = "/Engine/BasicShapes/Cylinder"
PLANE = "/Engine/BasicShapes/Plane"


def spawn_floor(game: spear.UWorld) -> spear.AStaticMeshActor:
    """A static 20 m x 20 m slab whose top face is at z = 0."""
    floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor", location=spear.FVector(Z=-0.5))
    mesh = floor.StaticMeshComponent
    mesh.SetStaticMesh(NewMesh=CUBE)
    mesh.SetRelativeScale3D(NewScale3D=spear.FVector(20, 20, 1))
    mesh.SetMobility(NewMobility=spear.EComponentMobility.Static)
    return floor


def spawn_body(game: spear.UWorld, name: str, mesh: str, location: spear.FVector,
               scale: spear.FVector = spear.FVector(1, 1, 1)) -> spear.AStaticMeshActor:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=location)
    component = actor.StaticMeshComponent
    component.SetStaticMesh(NewMesh=mesh)
    component.SetRelativeScale3D(NewScale3D=scale)
    component.SetSimulatePhysics(bSimulate=True)
    return actor


def test_bodies_fall_and_rest_on_the_floor_at_their_analytic_height(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        spawn_floor(game)
        cube = spawn_body(game, "Cube", CUBE, spear.FVector(0, 0, 2))
        ball = spawn_body(game, "Ball", SPHERE, spear.FVector(3, 0, 3), spear.FVector(0.4, 0.4, 0.4))
        drum = spawn_body(game, "Drum", CYLINDER, spear.FVector(-3, 0, 1), spear.FVector(1, 1, 2))
        slab = spawn_body(game, "Slab", CUBE, spear.FVector(0, 4, 1), spear.FVector(2, 1, 0.5))
        assert cube.StaticMeshComponent.IsSimulatingPhysics()
    with instance.end_frame():
        pass
    instance.step(num_frames=180)  # 3 s
    with instance.begin_frame():
        assert cube.GetActorLocation().Z == pytest.approx(0.5, abs=1e-3)
        assert ball.GetActorLocation().Z == pytest.approx(0.2, abs=1e-3)
        assert drum.GetActorLocation().Z == pytest.approx(1.0, abs=1e-3)  # half height 0.5 * 2
        assert slab.GetActorLocation().Z == pytest.approx(0.25, abs=1e-3)
        assert abs(cube.GetActorLocation().X) < 1e-2  # a flat landing barely slides
        assert cube.StaticMeshComponent.GetPhysicsLinearVelocity().Z == pytest.approx(0.0, abs=1e-2)


def test_a_plane_mesh_is_a_thin_slab_under_its_face(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(Z=1.0))
        ground.StaticMeshComponent.SetStaticMesh(NewMesh=PLANE)
        ground.SetActorScale3D(NewScale3D=spear.FVector(10, 10, 3))  # the slab's thickness ignores the Z scale
        cube = spawn_body(game, "Cube", CUBE, spear.FVector(0, 0, 3), spear.FVector(0.5, 0.5, 0.5))
        ball = spawn_body(game, "Ball", SPHERE, spear.FVector(2, 0, 3), spear.FVector(0.4, 0.4, 0.4))
    with instance.end_frame():
        pass
    instance.step(num_frames=180)
    with instance.begin_frame():
        assert cube.GetActorLocation().Z == pytest.approx(1.25, abs=1e-3)
        assert ball.GetActorLocation().Z == pytest.approx(1.2, abs=1e-3)
        down = game.line_trace_single(start=spear.FVector(-2, 0, 10), end=spear.FVector(-2, 0, -10))
        assert down.actor == ground and down.hit.Location.Z == pytest.approx(1.0, abs=1e-9)
        up = game.line_trace_single(start=spear.FVector(-2, 0, -10), end=spear.FVector(-2, 0, 10))
        assert up.actor == ground and up.hit.Location.Z == pytest.approx(0.99, abs=1e-9)  # its back face
        beside = game.line_trace_single(start=spear.FVector(6, 0, 10), end=spear.FVector(6, 0, -10))
        assert not beside.ReturnValue  # the slab ends with the plane
    with instance.end_frame():
        pass


def test_free_fall_follows_gravity(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        cube = spawn_body(game, "Cube", CUBE, spear.FVector(0, 0, 100))
    with instance.end_frame():
        pass
    instance.step(num_frames=59)  # 60 frames in all: 1 s
    with instance.begin_frame():
        # Semi-implicit Euler in 1/240 s substeps: z = z0 - g dt^2 n(n+1)/2 with n = 240.
        dt, n = 1.0 / 240.0, 240
        assert cube.GetActorLocation().Z == pytest.approx(100 - 9.81 * dt * dt * n * (n + 1) / 2, abs=1e-6)
        assert cube.StaticMeshComponent.GetPhysicsLinearVelocity().Z == pytest.approx(-9.81, abs=1e-6)


def run_scripted_scene() -> list[tuple[float, ...]]:
    """A stack of rotated boxes and balls pushed around; returns every pose after 2 s."""
    instance = spear.Instance()
    game = instance.get_game()
    bodies = []
    with instance.begin_frame():
        spawn_floor(game)
        for i in range(6):
            actor = spawn_body(game, f"Box{i}", CUBE if i % 2 == 0 else SPHERE,
                               spear.FVector(0.1 * i, 0.05 * i, 0.6 + 1.1 * i))
            actor.SetActorRotation(NewRotation=spear.FRotator(Yaw=17.0 * i, Roll=3.0 * i))
            bodies.append(actor)
    with instance.end_frame():
        pass
    for frame in range(120):
        with instance.begin_frame():
            if frame == 30:
                bodies[2].StaticMeshComponent.AddImpulse(Impulse=spear.FVector(2, -1, 0))
            if frame < 60:
                bodies[5].StaticMeshComponent.AddForce(Force=spear.FVector(0, 3, 0))
        with instance.end_frame():
            pass
    with instance.begin_frame():
        poses = []
        for actor in bodies:
            t = actor.GetActorTransform()
            poses.append((t.Translation.X, t.Translation.Y, t.Translation.Z,
                          t.Rotation.X, t.Rotation.Y, t.Rotation.Z, t.Rotation.W))
    instance.close()
    return poses


def test_two_identical_scripts_give_bit_identical_poses() -> None:
    first = run_scripted_scene()
    second = run_scripted_scene()
    assert first == second  # exact float equality, not approx
    assert len({p[2] for p in first}) > 1  # something actually happened


def test_line_trace_hits_the_closest_body(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        floor = spawn_floor(game)
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box", location=spear.FVector(2, 0, 1))
        box.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
        # Traces see bodies right after spawning, without a physics step.
        result = game.line_trace_single(start=spear.FVector(2, 0, 10), end=spear.FVector(2, 0, -10))
        assert result.ReturnValue and result.hit.bBlockingHit
        assert result.actor == box and result.component == box.StaticMeshComponent
        assert result.hit.Location.Z == pytest.approx(1.5, abs=1e-9)
        assert result.hit.ImpactNormal.Z == pytest.approx(1.0, abs=1e-9)
        assert result.hit.Distance == pytest.approx(8.5, abs=1e-9)
        assert result.hit.Time == pytest.approx(8.5 / 20, abs=1e-9)

        down = game.line_trace_single(start=spear.FVector(-2, 0, 10), end=spear.FVector(-2, 0, -10))
        assert down.actor == floor and down.hit.Location.Z == pytest.approx(0.0, abs=1e-9)

        miss = game.line_trace_single(start=spear.FVector(0, 0, 10), end=spear.FVector(0, 0, 20))
        assert not miss.ReturnValue and miss.actor is None and miss.component is None
        assert miss.hit.Location == spear.FVector(0, 0, 20) and miss.hit.Distance == pytest.approx(10.0)

        # Moving a movable (kinematic) component moves its body; destroying the actor removes it.
        box.SetActorLocation(NewLocation=spear.FVector(5, 0, 1))
        moved = game.line_trace_single(start=spear.FVector(5, 0, 10), end=spear.FVector(5, 0, -10))
        assert moved.actor == box
        game.destroy_actor(actor=box)
        gone = game.line_trace_single(start=spear.FVector(5, 0, 10), end=spear.FVector(5, 0, -10))
        assert gone.actor == floor


def test_collision_primitive_overrides_the_mesh_shape(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball")
        ball.StaticMeshComponent.SetStaticMesh(NewMesh=SPHERE)
        corner_start, corner_end = spear.FVector(0.45, 0.45, 10), spear.FVector(0.45, 0.45, -10)
        assert not game.line_trace_single(start=corner_start, end=corner_end).ReturnValue  # sphere: misses
        ball.StaticMeshComponent.CollisionPrimitive = spear.ECollisionPrimitive.Box
        assert game.line_trace_single(start=corner_start, end=corner_end).ReturnValue
        ball.StaticMeshComponent.CollisionPrimitive = spear.ECollisionPrimitive.NoCollision
        assert not game.line_trace_single(start=spear.FVector(Z=10), end=spear.FVector(Z=-10)).ReturnValue


def test_forces_impulses_and_velocities(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        cube = spawn_body(game, "Cube", CUBE, spear.FVector(0, 0, 50))
        mesh = cube.StaticMeshComponent
        mesh.SetMassOverrideInKg(MassInKg=2.0)
        assert mesh.GetMass() == 2.0 and mesh.MassInKg == 2.0
        mesh.AddImpulse(Impulse=spear.FVector(4, 0, 0))  # 4 N s / 2 kg = 2 m/s
        assert mesh.GetPhysicsLinearVelocity().X == pytest.approx(2.0)
        mesh.AddImpulse(Impulse=spear.FVector(0, 1, 0), bVelChange=True)
        assert mesh.GetPhysicsLinearVelocity().Y == pytest.approx(1.0)
        mesh.SetPhysicsLinearVelocity(NewVel=spear.FVector(0, 0, 0))
        mesh.SetPhysicsAngularVelocityInDegrees(NewAngVel=spear.FVector(0, 0, 90))
        assert mesh.GetPhysicsAngularVelocityInDegrees().Z == pytest.approx(90.0)
        mesh.AddForce(Force=spear.FVector(0, 0, 2 * 9.81))  # cancels gravity for this frame
    with instance.end_frame():
        assert mesh.GetPhysicsLinearVelocity().Z == pytest.approx(0.0, abs=1e-9)
        assert cube.GetActorRotation().Yaw == pytest.approx(90.0 / 60.0, abs=1e-6)


def test_static_and_non_simulated_components_are_clear_errors(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        floor = spawn_floor(game)
        mesh = floor.StaticMeshComponent
        with pytest.raises(spear.InvalidStateError, match=r"USceneComponent.SetRelative\w+\(\): .* is static"):
            floor.SetActorLocation(NewLocation=spear.FVector(Z=1))
        with pytest.raises(spear.InvalidStateError, match=r"SetSimulatePhysics\(\): .*'StaticMeshComponent' is not Movable"):
            mesh.SetSimulatePhysics(bSimulate=True)
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box")
        box.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
        with pytest.raises(spear.InvalidStateError, match=r"UPrimitiveComponent.AddForce\(\): .* is not simulating physics"):
            box.StaticMeshComponent.AddForce(Force=spear.FVector(1, 0, 0))
        with pytest.raises(spear.InvalidArgumentError, match=r"SetMassOverrideInKg\(\): MassInKg -1 must be > 0"):
            box.StaticMeshComponent.SetMassOverrideInKg(MassInKg=-1.0)
        plane = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Plane")
        plane.StaticMeshComponent.SetStaticMesh(NewMesh=PLANE)
        with pytest.raises(spear.InvalidStateError, match="collides as a plane"):
            plane.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
        empty = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Empty")
        with pytest.raises(spear.InvalidStateError, match="has no collision"):
            empty.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
        assert not empty.StaticMeshComponent.IsSimulatingPhysics()


def test_a_simulated_body_stops_when_simulation_is_turned_off(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        cube = spawn_body(game, "Cube", CUBE, spear.FVector(0, 0, 10))
    with instance.end_frame():
        pass
    instance.step(num_frames=10)
    with instance.begin_frame():
        cube.StaticMeshComponent.SetSimulatePhysics(bSimulate=False)
        held = cube.GetActorLocation()
        assert held.Z < 10
    with instance.end_frame():
        pass
    instance.step(num_frames=10)
    with instance.begin_frame():
        assert cube.GetActorLocation() == held
        assert not cube.StaticMeshComponent.IsSimulatingPhysics()


def write_obj(path: Path, vertices: list[tuple[float, float, float]], faces: list[tuple[int, ...]]) -> str:
    lines = [f"v {x} {y} {z}" for x, y, z in vertices] + ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def test_mesh_files_collide_as_convex_hulls_when_simulated_and_as_triangles_otherwise(
        instance: spear.Instance, tmp_path: Path) -> None:
    # An octahedron (vertices at +-0.3 on each axis) falls onto a static ground made of two triangles.
    octahedron = write_obj(tmp_path / "octahedron.obj",
                           [(0.3, 0, 0), (-0.3, 0, 0), (0, 0.3, 0), (0, -0.3, 0), (0, 0, 0.3), (0, 0, -0.3)],
                           [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)])
    ground = write_obj(tmp_path / "ground.obj", [(-5, -5, 0), (5, -5, 0), (5, 5, 0), (-5, 5, 0)], [(0, 1, 2), (0, 2, 3)])
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground", location=spear.FVector(Z=1.0))
        assert floor.StaticMeshComponent.SetStaticMesh(NewMesh=ground)
        floor.StaticMeshComponent.SetMobility(NewMobility=spear.EComponentMobility.Static)
        body = spawn_body(game, "Octahedron", octahedron, spear.FVector(Z=2.0))
        extent = body.GetActorBounds(bOnlyCollidingComponents=True).BoxExtent  # from the file's vertices (float32)
        assert (extent.X, extent.Y, extent.Z) == pytest.approx((0.3, 0.3, 0.3), abs=1e-6)
        with pytest.raises(spear.NotFoundError, match=r"UStaticMeshComponent.SetStaticMesh\(\): mesh file '.*missing.obj' "
                                                      r"not found$"):
            body.StaticMeshComponent.SetStaticMesh(NewMesh=str(tmp_path / "missing.obj"))
        assert body.StaticMeshComponent.StaticMesh == octahedron  # kept
    with instance.end_frame():
        pass
    instance.step(num_frames=180)
    with instance.begin_frame():
        # Resting on a vertex (a corner is the lowest point however it lands), so between 1 + 0.3/sqrt(3)
        # (a face down) and 1 + 0.3 (a vertex down); a hull of the mesh, not its bounding box.
        z = body.GetActorLocation().Z
        assert 1.0 + 0.3 / 3 ** 0.5 - 2e-3 <= z <= 1.0 + 0.3 + 2e-3
        assert not body.StaticMeshComponent.IsAnyRigidBodyAwake()
        hit = game.line_trace_single(start=spear.FVector(3, 3, 5), end=spear.FVector(3, 3, -5))
        assert hit.ReturnValue and hit.actor == floor and abs(hit.hit.Location.Z - 1.0) < 1e-6
    with instance.end_frame():
        pass


def test_add_forces_pushes_many_components_as_add_force_does_one_at_a_time(instance: spear.Instance) -> None:
    # Two rows of cubes in two worlds: one row pushed by AddForce each, the other by one add_forces call.
    game = instance.get_game()
    other = instance.create_world(name="Other")
    forces = np.array([[3.0, 0.0, 0.0], [0.0, -2.0, 1.0], [1.5, 1.5, 0.0]])
    with instance.begin_frame():
        rows = []
        for world in (game, other):
            spawn_floor(world)
            rows.append([spawn_body(world, f"Cube{i}", CUBE, spear.FVector(3.0 * i, 0, 0.5)).StaticMeshComponent
                         for i in range(3)])
    with instance.end_frame():
        pass
    for frame in range(20):
        with instance.begin_frame():
            for component, force in zip(rows[0], forces * (frame + 1)):
                component.AddForce(Force=spear.FVector(*force), bAccelChange=frame % 2 == 1)
            # Across worlds: the engine's worlds take one call.
            game.add_forces(components=rows[1], forces=forces * (frame + 1), bAccelChange=frame % 2 == 1)
        with instance.end_frame():
            pass
    with instance.begin_frame():
        one_by_one = [c.GetComponentLocation() for c in rows[0]]
        batched = [c.GetComponentLocation() for c in rows[1]]
    with instance.end_frame():
        pass
    assert one_by_one == batched  # the same operations: bit for bit
    assert one_by_one[0].X > 0.1 and one_by_one[1].Y < -0.1


def test_add_forces_is_all_or_nothing_naming_the_component(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        spawn_floor(game)
        pushed = spawn_body(game, "Pushed", CUBE, spear.FVector(0, 0, 0.5)).StaticMeshComponent
        resting = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Resting")
        resting.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
        with pytest.raises(spear.InvalidStateError,
                           match=r"^UWorld\.add_forces\(\): components\[1\]: UPrimitiveComponent\.AddForce\(\): "
                                 r"UStaticMeshComponent .StaticMeshComponent. is not simulating physics"):
            game.add_forces(components=[pushed, resting.StaticMeshComponent], forces=np.full((2, 3), 100.0))
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^UWorld\.add_forces\(\): forces must have shape \(1, 3\), got \(3,\)$"):
            game.add_forces(components=[pushed], forces=np.zeros(3))
    with instance.end_frame():
        velocity = pushed.GetPhysicsLinearVelocity()  # resting: nothing pushed it (100 N would give 1.7 m/s)
        assert max(abs(velocity.X), abs(velocity.Y), abs(velocity.Z)) < 1e-3
