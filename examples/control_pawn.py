"""Control a pawn through the gameplay framework: find player 0 with UGameplayStatics (a static function,
called on the class), fly its pawn through the default apartment with input injected for the player
controller, look through the player's view point with a camera, then hand the player to a second
controller and the pawn to an AI controller, and walk a character (ACharacter) possessed by the player
until the wall stops it. Writes the flight's views as one image strip.

    PYTHONPATH=python /usr/bin/python3 examples/control_pawn.py [--server launch] [--out out/control_pawn.png]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

# By asset name, so the example runs from anywhere (a checkout or the installed package).
APARTMENT = "/Game/scenes/apartment"
WIDTH, HEIGHT = 320, 240


def follow_view(player: spear.APlayerController, camera: spear.ACameraSensorActor) -> None:
    """Puts the camera at the player's view point, looking along the control rotation."""
    view = player.GetPlayerViewPoint()
    camera.K2_SetActorLocationAndRotation(NewLocation=view.Location, NewRotation=view.Rotation)


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--frames", type=int, default=120, help="frames of flight (a view is kept every quarter)")
    parser.add_argument("--out", default="out/control_pawn.png")
    args = parser.parse_args()

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=APARTMENT)
        # Player 0 starts here: the game framework starts on first use and spawns its pawn at this start.
        game.spawn_actor(uclass=spear.APlayerStart, location=spear.FVector(-2.6, -0.6, 1.4))
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        pawn = player.K2_GetPawn()
        assert isinstance(pawn, spear.ADefaultPawn)
        pawn.MaxSpeed = 1.5
        player.AddPitchInput(Val=-12.0)  # look a little down, at the furniture
        start = pawn.GetActorLocation()
        print(f"player 0: {player.GetName()} possesses {pawn.GetName()} at ({start.X:.2f}, {start.Y:.2f}, {start.Z:.2f})")
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="PlayerCamera")
        camera.CameraSensor.Width, camera.CameraSensor.Height, camera.CameraSensor.FOV = WIDTH, HEIGHT, 80.0
        camera.CameraSensor.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
        follow_view(player, camera)
    with instance.end_frame():
        pass

    views: list[NDArray[np.uint8]] = []
    keep_every = max(1, args.frames // 4)
    for frame in range(1, args.frames + 1):
        with instance.begin_frame():
            # Input for the controller moves its pawn: forward along the view, turning left as it goes.
            game.inject_input_for_actor(actor=player, input_action_name="MoveForward", value=spear.FVector(X=0.8))
            game.inject_input_for_actor(actor=player, input_action_name="Turn", value=spear.FVector(X=0.5))
            follow_view(player, camera)
        with instance.end_frame():
            if frame % keep_every == 0:
                pixels = camera.CameraSensor.read_pixels()
                if "final_color" not in pixels:
                    raise spear.InvalidStateError("control_pawn: the camera rendered no final_color")
                views.append(pixels["final_color"][:, :, :3].copy())
                location, yaw = pawn.GetActorLocation(), player.GetControlRotation().Yaw
                print(f"frame {frame}/{args.frames}: pawn at ({location.X:.2f}, {location.Y:.2f}), yaw {yaw:.1f} deg")

    with instance.begin_frame():
        mode = spear.UGameplayStatics.GetGameMode(WorldContextObject=game)
        assert mode is not None
        second = game.spawn_actor(uclass=spear.APlayerController, name="SecondController")
        mode.SwapPlayerControllers(OldPC=player, NewPC=second)
        now = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert now is not None
        print(f"after SwapPlayerControllers: player 0 is {now.GetName()}, possessing {pawn.GetName()}: "
              f"{now.K2_GetPawn() == pawn}")
        ai = game.spawn_actor(uclass=spear.AAIController, name="AI")
        ai.Possess(InPawn=pawn)
        print(f"after AI Possess: {pawn.GetName()} is player-controlled: {pawn.IsPlayerControlled()}, "
              f"player 0 has a pawn: {now.K2_GetPawn() is not None}")
        # A character walks on the floor: player 0 possesses it and walks it along -Y, past the table and the
        # ball, towards the east wall.
        walker = game.spawn_actor(uclass=spear.ACharacter, name="Walker", location=spear.FVector(0.6, 0.2, 1.0),
                                  rotation=spear.FRotator(Yaw=-90.0))
        walker.CharacterMovement.MaxWalkSpeed = 1.5
        now.Possess(InPawn=walker)
    with instance.end_frame():
        pass
    for _ in range(120):  # 2 s at 1.5 m/s would take it 3 m, through the wall (its face at y = -2.5)
        with instance.begin_frame():
            game.inject_input_for_actor(actor=now, input_action_name="MoveForward", value=spear.FVector(X=1.0))
        with instance.end_frame():
            pass
    with instance.begin_frame():
        at = walker.GetActorLocation()
        print(f"character {walker.GetName()} walked from (0.60, 0.20) to ({at.X:.2f}, {at.Y:.2f}), "
              f"standing {at.Z:.2f} m up, on the ground: {walker.CharacterMovement.IsMovingOnGround()}")
    with instance.end_frame():
        pass
    instance.close()

    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    strip = np.concatenate(views, axis=1)
    Image.fromarray(strip).save(out)
    print(f"wrote {out} ({len(views)} views of {WIDTH}x{HEIGHT})")


if __name__ == "__main__":
    main()
