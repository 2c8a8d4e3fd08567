"""ALaneFollowingController: AI drivers that take Bullet-simulated cars along the world's lanes through the
cars' throttle, steering and brake. A car keeps to its lane round a closed road, stops behind a parked car,
cars from four sides take turns through a junction without touching, a player takes a car over, settings are
checked, and a car with no lane to follow stops. Both transports."""

from __future__ import annotations

import math
import re

import pytest

import spear
from spear.errors import InvalidArgumentError


def _ground(game: spear.UWorld) -> None:
    plane = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    plane.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    plane.SetActorScale3D(NewScale3D=spear.FVector(300.0, 300.0, 1.0))


def _road(game: spear.UWorld, name: str, points: list[tuple[float, float]], closed: bool = False) -> None:
    road = game.spawn_actor(uclass=spear.ASplineActor, name=name, tags=["Road"])
    road.SplineComponent.SetSplinePoints(Points=[spear.FVector(x, y, 0.0) for x, y in points],
                                         CoordinateSpace=spear.ESplineCoordinateSpace.World)
    if closed:
        road.SplineComponent.SetClosedLoop(bInClosedLoop=True)


def _car_on_lane(game: spear.UWorld, name: str, near: tuple[float, float],
                 driver: bool = True) -> tuple[spear.AWheeledVehiclePawn, spear.ALaneFollowingController | None]:
    """A car on the driving lane nearest `near`, facing the way it runs, and (by default) a driver for it."""
    lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
    at = lanes.FindNearestLaneLocationByName(Location=spear.FVector(near[0], near[1], 0.0), TagName="Driving")
    assert at.LaneIndex >= 0
    yaw = math.degrees(math.atan2(at.Direction.Y, at.Direction.X))
    car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name=name,
                           location=spear.FVector(at.Position.X, at.Position.Y, 0.9), rotation=spear.FRotator(Yaw=yaw))
    if not driver:
        return car, None
    controller = game.spawn_actor(uclass=spear.ALaneFollowingController, name=name + "Driver")
    controller.Possess(InPawn=car)
    return car, controller


def test_a_car_keeps_to_its_lane_round_a_closed_road(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _ground(game)
        _road(game, "Ring", [(40.0 * math.cos(a * math.pi / 24), 40.0 * math.sin(a * math.pi / 24)) for a in range(48)],
              closed=True)
        car, driver = _car_on_lane(game, "Car", (41.75, 0.0))
        assert driver is not None
        driver.TargetSpeed = 8.0
    with instance.end_frame():
        pass
    worst, speeds, lanes_seen = 0.0, [], set()
    start = None
    travelled = 0.0
    for frame in range(2100):  # 35 simulated seconds: more than a lap of the 262 m lane
        instance.step()
        if frame % 15:
            continue
        with instance.begin_frame():
            lateral, location = driver.GetLateralOffset(), driver.GetLaneLocation()
            speed, position = car.GetForwardSpeed(), car.GetActorLocation()
        with instance.end_frame():
            pass
        if start is not None:
            travelled += math.hypot(position.X - start.X, position.Y - start.Y)
        start = position
        if frame >= 120:  # once it is under way
            worst = max(worst, abs(lateral))
            speeds.append(speed)
        lanes_seen.add(location.LaneIndex)
    # Within half a lane width (1.75 m of the 3.5 m lane) of the lane's centre all the way round, with room to
    # spare (under half of that), at its speed, on its own lane.
    assert worst < 1.75 / 2
    assert travelled > 262.0
    assert sum(speeds) / len(speeds) == pytest.approx(8.0, abs=0.8)
    assert len(lanes_seen) == 1 and -1 not in lanes_seen


def test_a_car_stops_behind_a_parked_car_at_its_gap(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _ground(game)
        _road(game, "Main", [(0.0, 0.0), (200.0, 0.0)])
        parked, _ = _car_on_lane(game, "Parked", (90.0, -1.75), driver=False)
        car, driver = _car_on_lane(game, "Car", (10.0, -1.75))
        assert driver is not None
        driver.TargetSpeed = 12.0
        assert driver.GetGapAhead() == -1.0  # nothing seen yet: it has not driven
    with instance.end_frame():
        pass
    closest = math.inf
    for frame in range(1500):
        instance.step()
        if frame % 10 == 0:
            with instance.begin_frame():
                a, b = car.GetActorLocation(), parked.GetActorLocation()
            with instance.end_frame():
                pass
            closest = min(closest, b.X - a.X - 4.2)
    with instance.begin_frame():
        assert abs(car.GetForwardSpeed()) < 0.1
        assert driver.GetGapAhead() == pytest.approx(driver.MinGap, abs=0.6)
        assert parked.GetActorLocation().X == pytest.approx(90.0, abs=0.05)  # never touched
    with instance.end_frame():
        pass
    assert closest > 3.0 / 2  # never nearer than half its standstill gap


def test_cars_from_four_sides_take_turns_through_a_junction(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _ground(game)
        for name, end in (("East", (80.0, 0.0)), ("North", (0.0, 80.0)), ("West", (-80.0, 0.0)), ("South", (0.0, -80.0))):
            _road(game, name, [(0.0, 0.0), end])
        pairs = [_car_on_lane(game, f"Car{i}", start)
                 for i, start in enumerate([(30.0, 1.75), (-1.75, 30.0), (-30.0, -1.75), (1.75, -30.0)])]
        cars = [car for car, _ in pairs]
        drivers = [driver for _, driver in pairs if driver is not None]
    with instance.end_frame():
        pass
    closest, waited, through = math.inf, False, [False] * 4
    for frame in range(1800):
        instance.step()
        if frame % 5:
            continue
        with instance.begin_frame():
            positions = [car.GetActorLocation() for car in cars]
            waited = waited or any(driver.IsWaitingAtJunction() for driver in drivers)
        with instance.end_frame():
            pass
        for i, p in enumerate(positions):
            through[i] = through[i] or math.hypot(p.X, p.Y) > 40.0
            for q in positions[i + 1:]:
                closest = min(closest, math.hypot(p.X - q.X, p.Y - q.Y))
    assert waited  # someone gave way
    assert all(through), through  # everyone got through
    assert closest > 2.5  # nobody touched (two cars side by side are 3.5 m apart)


def test_a_player_takes_a_car_over_and_its_driver_lets_go(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _ground(game)
        _road(game, "Main", [(0.0, 0.0), (200.0, 0.0)])
        car, driver = _car_on_lane(game, "Car", (10.0, -1.75))
        assert driver is not None
    with instance.end_frame():
        pass
    instance.step(num_frames=120)
    with instance.begin_frame():
        assert car.GetForwardSpeed() > 2.0
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        player.Possess(InPawn=car)
        assert driver.K2_GetPawn() is None
    with instance.end_frame():
        pass
    for _ in range(120):  # the player brakes: the car stops although its driver would drive on
        with instance.begin_frame():
            game.inject_input_for_actor(actor=player, input_action_name="Brake", value=spear.FVector(X=1.0))
        with instance.end_frame():
            pass
    with instance.begin_frame():
        assert abs(car.GetForwardSpeed()) < 0.1
        assert driver.GetLaneLocation().LaneIndex == -1  # it drives nothing
    with instance.end_frame():
        pass


def test_a_driver_that_is_stopped_or_has_no_lane_holds_its_car(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _ground(game)
        _road(game, "Main", [(0.0, 0.0), (200.0, 0.0)])
        held, holder = _car_on_lane(game, "Held", (10.0, -1.75))
        lost, stray = _car_on_lane(game, "Lost", (10.0, 1.75))
        assert holder is not None and stray is not None
        holder.bDriving = False
        stray.LaneTag = "Tramway"  # no lane has it: the driver waits (the log says why)
    with instance.end_frame():
        pass
    instance.step(num_frames=180)
    with instance.begin_frame():
        for car, driver in ((held, holder), (lost, stray)):
            assert abs(car.GetForwardSpeed()) < 0.05
            assert driver.GetLaneLocation().LaneIndex == -1
        stray.LaneTag = "Driving"
        holder.bDriving = True
    with instance.end_frame():
        pass
    instance.step(num_frames=120)
    with instance.begin_frame():
        assert held.GetForwardSpeed() > 2.0 and lost.GetForwardSpeed() > 2.0
        assert holder.GetLaneLocation().LaneIndex >= 0
    with instance.end_frame():
        pass


@pytest.mark.parametrize("name, value, message", [
    ("TargetSpeed", 0.0, "ALaneFollowingController.TargetSpeed must be > 0 m/s, got 0"),
    ("MinGap", -1.0, "ALaneFollowingController.MinGap must be >= 0 m, got -1"),
    ("TimeGap", float("nan"), "ALaneFollowingController.TimeGap must be >= 0 s, got nan"),
])
def test_bad_settings_are_refused_when_set(instance: spear.Instance, name: str, value: float, message: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        driver = game.spawn_actor(uclass=spear.ALaneFollowingController, name="Driver")
        before = getattr(driver, name)
        with pytest.raises(InvalidArgumentError, match=f"^{re.escape(message)}$"):
            setattr(driver, name, value)
        assert getattr(driver, name) == before
    with instance.end_frame():
        pass
