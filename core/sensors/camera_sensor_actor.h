#pragma once
// Ready-made camera actors: one camera, a stereo pair, and a ring of cameras (multi-view capture).

#include <vector>

#include "core/sensors/camera_sensor_component.h"
#include "core/world/actor.h"

/// An actor whose root is a camera sensor.
SPCLASS()
class ACameraSensorActor : public AActor {
    SP_GENERATED_BODY()
  public:
    ACameraSensorActor() { CameraSensor = CreateDefaultSubobject<UCameraSensorComponent>("CameraSensor"); }

    /// The camera (also the root component); it looks along the actor's forward axis.
    SPPROPERTY(ReadOnly, NotNull)
    UCameraSensorComponent* CameraSensor = nullptr;
};

/// Two parallel cameras Baseline metres apart along the rig's Y axis, looking along its forward axis.
SPCLASS()
class AStereoCameraRig : public AActor {
    SP_GENERATED_BODY()
  public:
    AStereoCameraRig();

    /// Distance between the two optical centres in metres (> 0); the left camera is at +Y.
    SPPROPERTY(Setter = SetBaseline)
    double Baseline = 0.12;

    /// The left camera (at +Baseline/2 on the rig's Y axis, which points left).
    SPPROPERTY(ReadOnly, NotNull)
    UCameraSensorComponent* LeftCamera = nullptr;

    /// The right camera (at -Baseline/2 on the rig's Y axis).
    SPPROPERTY(ReadOnly, NotNull)
    UCameraSensorComponent* RightCamera = nullptr;

    /// Sets the baseline in metres (> 0) and moves both cameras.
    SPFUNCTION()
    void SetBaseline(double NewBaseline);
};

/// A ring of cameras around the rig's origin in its XY plane, all looking at the origin.
SPCLASS()
class AMultiViewCameraRig : public AActor {
    SP_GENERATED_BODY()
  public:
    AMultiViewCameraRig();

    /// The cameras, counter-clockwise from the rig's -X side (camera 0 looks along +X).
    SPPROPERTY(ReadOnly)
    std::vector<UCameraSensorComponent*> Cameras;

    /// Ring radius in metres.
    SPPROPERTY(ReadOnly)
    double Radius = 2.0;

    /// Replaces the cameras by NumViews (in [1, 64]) cameras on a ring of Radius metres (> 0).
    SPFUNCTION()
    void SetRing(int32_t NumViews, double NewRadius);

    /// Sets Width, Height and Modalities of every camera of the ring.
    SPFUNCTION()
    void ConfigureCameras(int32_t Width, int32_t Height, const std::vector<ECameraModality>& Modalities);

  private:
    int nextCamera_ = 0;
};
