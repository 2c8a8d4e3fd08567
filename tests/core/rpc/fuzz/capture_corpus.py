"""Captures the seed corpus of spear_rpc_fuzz: the request bodies a typical client session sends to a
launched spear-server (hello, frames, spawning, properties, calls, static calls, batches, arrays, camera reads,
describe, scene save and load, cars, characters and AI moves, triggers, splines, streaming levels, batched
forces, stacked camera reads, a frame's posted end), one file per request, in the order sent.

    PYTHONPATH=python /usr/bin/python3 tests/core/rpc/fuzz/capture_corpus.py tests/core/rpc/fuzz/corpus

The fuzzer replays them in order first (so that the handles they name exist), then mutates them.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

import spear
from spear._rpc_client import RpcConnection


def main(out: Path) -> int:
    bodies: list[bytes] = []
    original = RpcConnection._send

    def recording(self: RpcConnection, frame: bytes) -> None:
        # Every message sent, the posted ones (a frame's end sent without waiting) included.
        bodies.append(frame[4:])  # without the 4-byte length
        original(self, frame)

    RpcConnection._send = recording  # type: ignore[method-assign]
    instance = spear.Instance(server="launch")
    game = instance.get_game()
    # Scene files first: loading one replaces every actor, and the handles of those spawned below must stay
    # valid after the replay for the mutated requests to reach the engine's functions.
    with instance.begin_frame():
        game.save_scene(path="fuzz_scene.json")
        game.load_scene(path="fuzz_scene.json")
        Path("fuzz_scene.json").unlink()
    with instance.end_frame():
        pass
    with instance.begin_frame():
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box", location=spear.FVector(0.0, 0.0, 1.0))
        mesh = box.StaticMeshComponent
        mesh.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        mesh.SetMassOverrideInKg(MassInKg=2.0)
        mesh.SetSimulatePhysics(bSimulate=True)
        mesh.Friction = 0.7
        camera_actor = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                        location=spear.FVector(-3.0, 0.0, 1.5))
        camera = camera_actor.CameraSensor
        camera.Width, camera.Height = 32, 24
        camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
        mesh.send_async.AddForce(Force=spear.FVector(1.0, 0.0, 0.0))
        box.send_async.K2_SetActorLocationAndRotation(NewLocation=spear.FVector(0.0, 0.1, 1.0),
                                                      NewRotation=spear.FRotator(Pitch=0.0, Yaw=10.0, Roll=0.0))
        assert game.find_actor_by_name(name="Box") is not None
        game.spawn_actor(uclass=spear.BP_Crate, name="Crate")
        box.GetActorLocation()
        box.Tags = ["a", "b"]
    with instance.end_frame():
        camera.read_pixels()
        box.is_valid()
        camera.GetRenderStats()
    instance.step(num_frames=2)
    with instance.begin_frame():
        doomed = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Doomed")
        game.destroy_actor(actor=doomed)
        found = game.find_actor_by_name(name="Box")
        assert found is not None
        found.SetActorScale3D(NewScale3D=spear.FVector(1.0, 1.0, 2.0))
        # Static functions: requests that name a class instead of an object.
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        player.SetControlRotation(NewRotation=spear.FRotator(Pitch=0.0, Yaw=45.0, Roll=0.0))
        spear.UGameplayStatics.GetAllActorsOfClass(WorldContextObject=game, ActorClass=spear.APawn)
        # The gameplay world: a car, a character moved by an AI controller, a trigger, a spline, levels.
        car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name="Car", location=spear.FVector(5.0, 0.0, 1.0))
        car.MaxSteerAngle = 30.0
        game.inject_input_for_actor(actor=car, input_action_name="Throttle", value=spear.FVector(X=1.0))
        walker = game.spawn_actor(uclass=spear.ACharacter, name="Walker", location=spear.FVector(-5.0, 0.0, 1.0))
        walker.CharacterMovement.MaxWalkSpeed = 2.0
        ai = game.spawn_actor(uclass=spear.AAIController, name="AI")
        ai.Possess(InPawn=walker)
        ai.MoveToLocation(Dest=spear.FVector(-5.0, 3.0, 1.0), AcceptanceRadius=0.2)
        trigger = game.spawn_actor(uclass=spear.ATriggerBox, name="Trigger")
        trigger.CollisionComponent.BoxExtent = spear.FVector(2.0, 2.0, 2.0)
        trigger.GetOverlappingActors(ClassFilter=spear.AActor)
        spline = game.spawn_actor(uclass=spear.ASplineActor, name="Path").SplineComponent
        spline.SetSplinePoints(Points=[spear.FVector(), spear.FVector(X=2.0), spear.FVector(X=2.0, Y=2.0)],
                               CoordinateSpace=spear.ESplineCoordinateSpace.Local)
        spline.SetTangentAtSplinePoint(PointIndex=1, InTangent=spear.FVector(X=1.0, Y=1.0),
                                       CoordinateSpace=spear.ESplineCoordinateSpace.World)
        spline.GetLocationsAtDistances(Distances=np.linspace(0.0, 4.0, 5),
                                       CoordinateSpace=spear.ESplineCoordinateSpace.World)
        spear.UGameplayStatics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen")
    with instance.end_frame():
        car.GetWheelState(WheelIndex=0)
        trigger.CollisionComponent.GetBeginOverlaps()
    with instance.begin_frame():  # many bodies pushed in one call; cameras read together
        game.send_async.add_forces(components=[mesh], forces=np.array([[0.0, 1.0, 0.0]]))
        game.add_forces(components=[mesh], forces=np.array([[1.0, 0.0, 0.0]]), bAccelChange=True)
    with instance.end_frame():
        camera.read_pixels_stacked(Cameras=[camera])
    connection: Any = instance._backend  # the dynamic API and the transport's diagnostics, by hand
    client = getattr(connection, "connection", None)
    if client is not None:
        client.request("echo", value={"list": [1, 2.5, "x", None, True], "array": np.arange(12, dtype=np.float32)})
    instance.close()
    RpcConnection._send = original  # type: ignore[method-assign]

    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.msgpack"):
        old.unlink()
    for i, body in enumerate(bodies):
        (out / f"{i:03d}.msgpack").write_bytes(body)
    print(f"capture_corpus: {len(bodies)} requests written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
