"""Positive typing case: splines, their coordinate spaces and bulk evaluation."""

from __future__ import annotations

from typing import assert_type

import numpy as np
from numpy.typing import NDArray

import spear


def road(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        spline = game.spawn_actor(uclass=spear.ASplineActor).SplineComponent
        spline.AddSplinePoint(Position=spear.FVector(X=5.0), CoordinateSpace=spear.ESplineCoordinateSpace.World)
        assert_type(spline.GetSplineLength(), float)
        assert_type(spline.GetLocationAtDistanceAlongSpline(Distance=1.0,
                                                            CoordinateSpace=spear.ESplineCoordinateSpace.Local),
                    spear.FVector)
        points = spline.GetLocationsAtDistances(Distances=np.linspace(0.0, 5.0, 6),
                                                CoordinateSpace=spear.ESplineCoordinateSpace.World)
        assert_type(points, NDArray[np.float64])
        assert_type(spline.SplinePoints, list[spear.FVector])
    with instance.end_frame():
        pass
