"""Negative typing case: misuse of the gameplay framework and of static functions called on their class.
Every marked line must be rejected by mypy --strict (`# E:`) and by pyright (`# P: rule: message`)."""

# pyright: standard
# (negative cases are checked as most pyright and Pylance users run it; strict reports more)

from __future__ import annotations

import spear


def misuse(instance: spear.Instance) -> None:
    game = instance.get_game()
    spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex="0")  # E: Argument "PlayerIndex" to "GetPlayerController" of "UGameplayStatics" has incompatible type "str"; expected "int"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['0']" cannot be assigned to parameter "PlayerIndex" of type "int" in function "GetPlayerController" / "Literal['0']" is not assignable to "int"
    spear.UGameplayStatics.GetPlayerController(WorldContextObject="game", PlayerIndex=0)  # E: Argument "WorldContextObject" to "GetPlayerController" of "UGameplayStatics" has incompatible type "str"; expected "UObject"  [arg-type]  # P: reportArgumentType: Argument of type "Literal['game']" cannot be assigned to parameter "WorldContextObject" of type "UObject" in function "GetPlayerController" / "Literal['game']" is not assignable to "UObject"
    spear.UGameplayStatics.GetPlayerControler(WorldContextObject=game, PlayerIndex=0)  # E: "Type[UGameplayStatics]" has no attribute "GetPlayerControler"  [attr-defined]  # P: reportAttributeAccessIssue: Cannot access attribute "GetPlayerControler" for class "type[UGameplayStatics]" / Attribute "GetPlayerControler" is unknown
    pc = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
    pc.K2_GetPawn()  # E: Item "None" of "Optional[APlayerController]" has no attribute "K2_GetPawn"  [union-attr]  # P: reportOptionalMemberAccess: "K2_GetPawn" is not a known attribute of "None"
    spear.UGameplayStatics.GetNumPlayerControllers(game)  # E: Too many positional arguments for "GetNumPlayerControllers" of "UGameplayStatics"  [misc]  # P: reportCallIssue: Expected 0 positional arguments
    mode = game.spawn_actor(uclass=spear.AGameModeBase)
    mode.DefaultPawnClass = spear.AStaticMeshActor  # E: Incompatible types in assignment (expression has type "Type[AStaticMeshActor]", variable has type "Optional[Type[APawn]]")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "DefaultPawnClass" for class "AGameModeBase" / Type "type[AStaticMeshActor]" is not assignable to type "type[APawn] | None" / "type[AStaticMeshActor]" is not assignable to "type[APawn]" / Type "type[AStaticMeshActor]" is not assignable to type "type[APawn]" / Type is not assignable to "None"
    ai = game.spawn_actor(uclass=spear.AAIController)
    ai.Possess(InPawn=mode)  # E: Argument "InPawn" to "Possess" of "AController" has incompatible type "AGameModeBase"; expected "APawn"  [arg-type]  # P: reportArgumentType: Argument of type "AGameModeBase" cannot be assigned to parameter "InPawn" of type "APawn" in function "Possess" / "AGameModeBase" is not assignable to "APawn"
    walker = game.spawn_actor(uclass=spear.ACharacter)
    walker.Jump(Height=2.0)  # E: Unexpected keyword argument "Height" for "Jump" of "ACharacter"  [call-arg]  # P: reportCallIssue: No parameter named "Height"
    walker.CharacterMovement.MaxWalkSpeed = None  # E: Incompatible types in assignment (expression has type "None", variable has type "float")  [assignment]  # P: reportAttributeAccessIssue: Cannot assign to attribute "MaxWalkSpeed" for class "UCharacterMovementComponent" / "None" is not assignable to "float"
    ai.MoveToLocation(Dest=(1.0, 2.0, 0.0))  # E: Argument "Dest" to "MoveToLocation" of "AAIController" has incompatible type "Tuple[float, float, float]"; expected "FVector"  [arg-type]  # P: reportArgumentType: Argument of type "tuple[float, float, float]" cannot be assigned to parameter "Dest" of type "FVector" in function "MoveToLocation" / "tuple[float, float, float]" is not assignable to "FVector"
