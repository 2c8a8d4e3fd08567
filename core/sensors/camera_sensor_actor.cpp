#include "core/sensors/camera_sensor_actor.h"

#include <cmath>
#include <numbers>

#include "core/base/error.h"

AStereoCameraRig::AStereoCameraRig() {
    CreateDefaultSubobject<USceneComponent>("Root"); // the first scene component is the root
    LeftCamera = CreateDefaultSubobject<UCameraSensorComponent>("LeftCamera");
    RightCamera = CreateDefaultSubobject<UCameraSensorComponent>("RightCamera");
    SetBaseline(Baseline);
}

void AStereoCameraRig::SetBaseline(double NewBaseline) {
    SP_CHECK(NewBaseline > 0.0 && std::isfinite(NewBaseline), sp::InvalidArgument,
             "AStereoCameraRig.SetBaseline(): NewBaseline must be > 0 metres, got ", NewBaseline);
    Baseline = NewBaseline;
    // Relative placement is not a move of a static body: the rig itself may be static.
    LeftCamera->RelativeLocation = FVector{0.0, 0.5 * Baseline, 0.0};
    RightCamera->RelativeLocation = FVector{0.0, -0.5 * Baseline, 0.0};
}

AMultiViewCameraRig::AMultiViewCameraRig() {
    CreateDefaultSubobject<USceneComponent>("Root"); // the first scene component is the root
    SetRing(4, Radius);
}

void AMultiViewCameraRig::SetRing(int32_t NumViews, double NewRadius) {
    SP_CHECK(NumViews >= 1 && NumViews <= 64, sp::InvalidArgument,
             "AMultiViewCameraRig.SetRing(): NumViews must be in [1, 64], got ", NumViews);
    SP_CHECK(NewRadius > 0.0 && std::isfinite(NewRadius), sp::InvalidArgument,
             "AMultiViewCameraRig.SetRing(): NewRadius must be > 0 metres, got ", NewRadius);
    for (UCameraSensorComponent* camera : Cameras)
        DestroyComponent(camera);
    Cameras.clear();
    Radius = NewRadius;
    for (int32_t i = 0; i < NumViews; ++i) {
        // Names never repeat, so a handle to a removed camera can never be confused with a new one.
        auto* camera =
            CreateDefaultSubobject<UCameraSensorComponent>("Camera" + std::to_string(nextCamera_++));
        const double yawDeg = 360.0 * i / NumViews;
        const double yaw = yawDeg * std::numbers::pi / 180.0;
        // Camera i sits at angle yaw + 180 degrees and looks back at the origin along yaw.
        camera->RelativeLocation = FVector{-Radius * std::cos(yaw), -Radius * std::sin(yaw), 0.0};
        camera->RelativeRotation = FRotator{0.0, yawDeg, 0.0};
        Cameras.push_back(camera);
    }
}

void AMultiViewCameraRig::ConfigureCameras(int32_t Width, int32_t Height,
                                           const std::vector<ECameraModality>& Modalities) {
    // Checked before any camera changes: a refused size leaves every camera as it was.
    SP_CHECK(Width >= 1 && Width <= 16384, sp::InvalidArgument,
             "AMultiViewCameraRig.ConfigureCameras(): Width must be in [1, 16384], got ", Width);
    SP_CHECK(Height >= 1 && Height <= 16384, sp::InvalidArgument,
             "AMultiViewCameraRig.ConfigureCameras(): Height must be in [1, 16384], got ", Height);
    for (UCameraSensorComponent* camera : Cameras) {
        camera->SetWidth(Width);
        camera->SetHeight(Height);
        camera->Modalities = Modalities;
    }
}
