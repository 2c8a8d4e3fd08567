#include "core/sensors/camera_sensor_component.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/base/error.h"
#include "core/render/camera.h"
#include "core/render/modality.h"
#include "core/render/tone.h"
#include "core/sensors/render_subsystem.h"
#include "core/world/actor.h"
#include "core/world/world.h"

namespace {

sp::sensors::RenderSubsystem& subsystemOf(const UCameraSensorComponent& camera, const char* function) {
    UWorld* world = camera.GetWorld();
    SP_CHECK(world, sp::InvalidState, "UCameraSensorComponent.", function, "(): ", camera.GetDebugName(),
             " is not in a world");
    return world->GetSubsystem<sp::sensors::RenderSubsystem>();
}

} // namespace

void UCameraSensorComponent::BeginPlay() {
    // The world's renderer exists from the first camera on; it starts EGL on the first rendered frame.
    if (GetWorld())
        GetWorld()->GetSubsystem<sp::sensors::RenderSubsystem>();
}

void UCameraSensorComponent::SetWidth(int32_t NewWidth) {
    sp::checkSetting(NewWidth >= 1 && NewWidth <= 16384, "UCameraSensorComponent", "Width", "in [1, 16384]",
                     NewWidth);
    Width = NewWidth;
}
void UCameraSensorComponent::SetHeight(int32_t NewHeight) {
    sp::checkSetting(NewHeight >= 1 && NewHeight <= 16384, "UCameraSensorComponent", "Height",
                     "in [1, 16384]", NewHeight);
    Height = NewHeight;
}
void UCameraSensorComponent::SetFOV(double NewFOV) {
    sp::checkSetting(NewFOV > 0.0 && NewFOV < 180.0, "UCameraSensorComponent", "FOV", "in (0, 180) degrees",
                     NewFOV);
    FOV = NewFOV;
}
void UCameraSensorComponent::SetNearClip(double NewNearClip) {
    sp::checkSetting(NewNearClip > 0.0 && std::isfinite(NewNearClip), "UCameraSensorComponent", "NearClip",
                     "> 0 and finite", NewNearClip);
    NearClip = NewNearClip;
}
void UCameraSensorComponent::SetFarClip(double NewFarClip) {
    sp::checkSetting(NewFarClip > 0.0 && std::isfinite(NewFarClip), "UCameraSensorComponent", "FarClip",
                     "> 0 and finite", NewFarClip);
    FarClip = NewFarClip;
}
void UCameraSensorComponent::SetExposure(float NewExposure) {
    sp::checkSetting(NewExposure > 0.0f && std::isfinite(NewExposure), "UCameraSensorComponent", "Exposure",
                     "> 0 and finite", NewExposure);
    Exposure = NewExposure;
}
void UCameraSensorComponent::SetAutoExposureBias(float NewBias) {
    sp::checkSetting(NewBias >= -15.0f && NewBias <= 15.0f, "UCameraSensorComponent", "AutoExposureBias",
                     "in [-15, 15] f-stops", NewBias);
    AutoExposureBias = NewBias;
}
void UCameraSensorComponent::SetAutoExposureMinBrightness(float NewMinBrightness) {
    sp::checkSetting(NewMinBrightness >= -20.0f && NewMinBrightness <= 40.0f, "UCameraSensorComponent",
                     "AutoExposureMinBrightness", "in [-20, 40] EV100", NewMinBrightness);
    AutoExposureMinBrightness = NewMinBrightness;
}
void UCameraSensorComponent::SetAutoExposureMaxBrightness(float NewMaxBrightness) {
    sp::checkSetting(NewMaxBrightness >= -20.0f && NewMaxBrightness <= 40.0f, "UCameraSensorComponent",
                     "AutoExposureMaxBrightness", "in [-20, 40] EV100", NewMaxBrightness);
    AutoExposureMaxBrightness = NewMaxBrightness;
}
void UCameraSensorComponent::SetAutoExposureSpeedUp(float NewSpeed) {
    sp::checkSetting(NewSpeed > 0.0f && NewSpeed <= 100.0f, "UCameraSensorComponent", "AutoExposureSpeedUp",
                     "in (0, 100] f-stops per second", NewSpeed);
    AutoExposureSpeedUp = NewSpeed;
}
void UCameraSensorComponent::SetAutoExposureSpeedDown(float NewSpeed) {
    sp::checkSetting(NewSpeed > 0.0f && NewSpeed <= 100.0f, "UCameraSensorComponent", "AutoExposureSpeedDown",
                     "in (0, 100] f-stops per second", NewSpeed);
    AutoExposureSpeedDown = NewSpeed;
}
void UCameraSensorComponent::SetAutoExposureLowPercent(float NewPercent) {
    sp::checkSetting(NewPercent >= 0.0f && NewPercent < 100.0f, "UCameraSensorComponent",
                     "AutoExposureLowPercent", "in [0, 100)", NewPercent);
    AutoExposureLowPercent = NewPercent;
}
void UCameraSensorComponent::SetAutoExposureHighPercent(float NewPercent) {
    sp::checkSetting(NewPercent > 0.0f && NewPercent <= 100.0f, "UCameraSensorComponent",
                     "AutoExposureHighPercent", "in (0, 100]", NewPercent);
    AutoExposureHighPercent = NewPercent;
}
void UCameraSensorComponent::ResetAutoExposure() {
    subsystemOf(*this, "ResetAutoExposure").resetAutoExposure(*this);
}
void UCameraSensorComponent::SetSensorWidth(double NewSensorWidth) {
    sp::checkSetting(NewSensorWidth > 0.0 && std::isfinite(NewSensorWidth), "UCameraSensorComponent",
                     "SensorWidth", "> 0 and finite", NewSensorWidth);
    SensorWidth = NewSensorWidth;
}
void UCameraSensorComponent::SetFocalLength(double FocalLength) {
    sp::checkSetting(FocalLength > 0.0 && std::isfinite(FocalLength), "UCameraSensorComponent", "FocalLength",
                     "> 0 and finite", FocalLength);
    SetFOV(2.0 * std::atan(SensorWidth / (2.0 * FocalLength)) * 180.0 / M_PI);
}
double UCameraSensorComponent::GetFocalLength() const {
    return SensorWidth / (2.0 * std::tan(0.5 * FOV * M_PI / 180.0));
}
void UCameraSensorComponent::SetExposureValue(double EV100) {
    sp::checkSetting(std::isfinite(EV100) && EV100 > -60.0 && EV100 < 60.0, "UCameraSensorComponent", "EV100",
                     "in (-60, 60)", EV100);
    SetExposure(float(1.0 / (1.2 * std::exp2(EV100))));
}
void UCameraSensorComponent::SetPhysicalExposure(double FNumber, double ShutterSeconds, double ISO) {
    sp::checkSetting(FNumber > 0.0 && std::isfinite(FNumber), "UCameraSensorComponent", "FNumber",
                     "> 0 and finite", FNumber);
    sp::checkSetting(ShutterSeconds > 0.0 && std::isfinite(ShutterSeconds), "UCameraSensorComponent",
                     "ShutterSeconds", "> 0 and finite", ShutterSeconds);
    sp::checkSetting(ISO > 0.0 && std::isfinite(ISO), "UCameraSensorComponent", "ISO", "> 0 and finite", ISO);
    SetExposureValue(std::log2(FNumber * FNumber / ShutterSeconds * 100.0 / ISO));
}
void UCameraSensorComponent::SetShadowResolution(int32_t NewShadowResolution) {
    sp::checkSetting(NewShadowResolution == 0 || (NewShadowResolution >= 16 && NewShadowResolution <= 8192),
                     "UCameraSensorComponent", "ShadowResolution", "0 or in [16, 8192]", NewShadowResolution);
    ShadowResolution = NewShadowResolution;
}
void UCameraSensorComponent::SetLatency(int32_t NewLatency) {
    sp::checkSetting(NewLatency >= 0 && NewLatency <= 2, "UCameraSensorComponent", "Latency", "0, 1 or 2",
                     NewLatency);
    Latency = NewLatency;
}

void UCameraSensorComponent::SetSamplesPerPixel(int32_t NewSamplesPerPixel) {
    sp::checkSetting(NewSamplesPerPixel >= 1 && NewSamplesPerPixel <= 65536, "UCameraSensorComponent",
                     "SamplesPerPixel", "in [1, 65536]", NewSamplesPerPixel);
    SamplesPerPixel = NewSamplesPerPixel;
}
void UCameraSensorComponent::SetMaxBounces(int32_t NewMaxBounces) {
    sp::checkSetting(NewMaxBounces >= 0 && NewMaxBounces <= 64, "UCameraSensorComponent", "MaxBounces",
                     "in [0, 64]", NewMaxBounces);
    MaxBounces = NewMaxBounces;
}

void UCameraSensorComponent::SetPathTracingMaxPathIntensity(float NewIntensity) {
    sp::checkSetting(std::isfinite(NewIntensity) && NewIntensity >= 0.0f, "UCameraSensorComponent",
                     "PathTracingMaxPathIntensity", ">= 0", NewIntensity);
    PathTracingMaxPathIntensity = NewIntensity;
}

sp::render::LensModel UCameraSensorComponent::lensModel() const {
    // The renderer's own focal length, so that K is the projection the images were made with.
    sp::render::Camera camera;
    camera.params.width = Width;
    camera.params.hfovDeg = FOV;
    sp::render::LensModel lens;
    lens.fx = lens.fy = camera.focalLengthPixels();
    lens.cx = 0.5 * (Width - 1) + PrincipalPointOffset.X;
    lens.cy = 0.5 * (Height - 1) + PrincipalPointOffset.Y;
    lens.k1 = LensDistortion.K1;
    lens.k2 = LensDistortion.K2;
    lens.k3 = LensDistortion.K3;
    lens.p1 = LensDistortion.P1;
    lens.p2 = LensDistortion.P2;
    return lens;
}

sp::reflect::SpArray<double> UCameraSensorComponent::GetIntrinsicMatrix() const {
    const sp::render::LensModel lens = lensModel();
    sp::reflect::SpArray<double> k("K");
    k.resize({3, 3});
    const double values[9] = {lens.fx, 0.0, lens.cx, 0.0, lens.fy, lens.cy, 0.0, 0.0, 1.0};
    std::copy(values, values + 9, k.data());
    return k;
}

void UCameraSensorComponent::SetApertureFNumber(double NewApertureFNumber) {
    sp::checkSetting(NewApertureFNumber == 0.0 ||
                         (NewApertureFNumber >= 0.5 && std::isfinite(NewApertureFNumber)),
                     "UCameraSensorComponent", "ApertureFNumber", "0 (a pinhole) or a finite f-number >= 0.5",
                     NewApertureFNumber);
    ApertureFNumber = NewApertureFNumber;
}

void UCameraSensorComponent::SetFocusDistance(double NewFocusDistance) {
    sp::checkSetting(NewFocusDistance > 0.0 && std::isfinite(NewFocusDistance), "UCameraSensorComponent",
                     "FocusDistance", "> 0 and finite", NewFocusDistance);
    FocusDistance = NewFocusDistance;
}

void UCameraSensorComponent::SetMSAASampleCount(int32_t NewMSAASampleCount) {
    sp::checkSetting(NewMSAASampleCount == 2 || NewMSAASampleCount == 4 || NewMSAASampleCount == 8,
                     "UCameraSensorComponent", "MSAASampleCount", "2, 4 or 8", NewMSAASampleCount);
    MSAASampleCount = NewMSAASampleCount;
}

void UCameraSensorComponent::SetSpatialSampleCount(int32_t NewSpatialSampleCount) {
    const bool ok = NewSpatialSampleCount == 1 || NewSpatialSampleCount == 2 || NewSpatialSampleCount == 4 ||
                    NewSpatialSampleCount == 8 || NewSpatialSampleCount == 16;
    sp::checkSetting(ok, "UCameraSensorComponent", "SpatialSampleCount", "1, 2, 4, 8 or 16",
                     NewSpatialSampleCount);
    SpatialSampleCount = NewSpatialSampleCount;
}

void UCameraSensorComponent::SetMaxAnisotropy(int32_t NewMaxAnisotropy) {
    sp::checkSetting(NewMaxAnisotropy >= 0 && NewMaxAnisotropy <= 16, "UCameraSensorComponent",
                     "MaxAnisotropy", "0 (the renderer's default) or in [1, 16]", NewMaxAnisotropy);
    MaxAnisotropy = NewMaxAnisotropy;
}

void UCameraSensorComponent::SetMipMapLODBias(float NewMipMapLODBias) {
    sp::checkSetting(NewMipMapLODBias >= -2.0f && NewMipMapLODBias <= 2.0f, "UCameraSensorComponent",
                     "MipMapLODBias", "[-2, 2]", NewMipMapLODBias);
    MipMapLODBias = NewMipMapLODBias;
}

void UCameraSensorComponent::SetAmbientOcclusionIntensity(float NewAmbientOcclusionIntensity) {
    sp::checkSetting(NewAmbientOcclusionIntensity >= 0.0f && NewAmbientOcclusionIntensity <= 1.0f,
                     "UCameraSensorComponent", "AmbientOcclusionIntensity", "in [0, 1]",
                     NewAmbientOcclusionIntensity);
    AmbientOcclusionIntensity = NewAmbientOcclusionIntensity;
}

void UCameraSensorComponent::SetAmbientOcclusionRadius(float NewAmbientOcclusionRadius) {
    sp::checkSetting(NewAmbientOcclusionRadius > 0.0f && NewAmbientOcclusionRadius <= 100.0f,
                     "UCameraSensorComponent", "AmbientOcclusionRadius", "in (0, 100] metres",
                     NewAmbientOcclusionRadius);
    AmbientOcclusionRadius = NewAmbientOcclusionRadius;
}

void UCameraSensorComponent::SetVignetteIntensity(float NewVignetteIntensity) {
    sp::checkSetting(NewVignetteIntensity >= 0.0f && NewVignetteIntensity <= 1.0f, "UCameraSensorComponent",
                     "VignetteIntensity", "in [0, 1]", NewVignetteIntensity);
    VignetteIntensity = NewVignetteIntensity;
}

void UCameraSensorComponent::SetWhiteBalanceTemperature(double NewWhiteBalanceTemperature) {
    sp::checkSetting(NewWhiteBalanceTemperature >= 2000.0 && NewWhiteBalanceTemperature <= 25000.0,
                     "UCameraSensorComponent", "WhiteBalanceTemperature", "in [2000, 25000] kelvin",
                     NewWhiteBalanceTemperature);
    WhiteBalanceTemperature = NewWhiteBalanceTemperature;
}

sp::reflect::SpArray<double> UCameraSensorComponent::GetWhiteBalanceGains() const {
    const Eigen::Vector3f gains = sp::render::whiteBalanceGains(WhiteBalanceTemperature);
    sp::reflect::SpArray<double> result("white_balance_gains");
    result.resize({3});
    for (int c = 0; c < 3; ++c)
        result.data()[c] = gains[c];
    return result;
}

void UCameraSensorComponent::SetLensDistortion(const FLensDistortion& NewLensDistortion) {
    const FLensDistortion& d = NewLensDistortion;
    for (const auto& [name, value] :
         {std::pair{"K1", d.K1}, {"K2", d.K2}, {"K3", d.K3}, {"P1", d.P1}, {"P2", d.P2}})
        sp::checkSetting(std::isfinite(value), "UCameraSensorComponent",
                         std::string("LensDistortion.") + name, "finite", value);
    LensDistortion = NewLensDistortion;
}

void UCameraSensorComponent::SetPrincipalPointOffset(const FVector2D& NewPrincipalPointOffset) {
    sp::checkSetting(std::isfinite(NewPrincipalPointOffset.X), "UCameraSensorComponent",
                     "PrincipalPointOffset.X", "finite", NewPrincipalPointOffset.X);
    sp::checkSetting(std::isfinite(NewPrincipalPointOffset.Y), "UCameraSensorComponent",
                     "PrincipalPointOffset.Y", "finite", NewPrincipalPointOffset.Y);
    PrincipalPointOffset = NewPrincipalPointOffset;
}

sp::reflect::SpArray<double> UCameraSensorComponent::GetDistortionCoefficients() const {
    sp::reflect::SpArray<double> coefficients("distortion_coefficients");
    coefficients.resize({5});
    const double values[5] = {LensDistortion.K1, LensDistortion.K2, LensDistortion.P1, LensDistortion.P2,
                              LensDistortion.K3};
    std::copy(values, values + 5, coefficients.data());
    return coefficients;
}

namespace {

// Points (N, 2) mapped one by one by `map`, as an (N, 2) array.
template <typename Map>
sp::reflect::SpArray<double> mapPixels(const sp::reflect::SpArray<double>& points, const char* function,
                                       Map map) {
    points.checkShape({-1, 2}, std::string("UCameraSensorComponent.") + function + "(): array 'Points'");
    sp::reflect::SpArray<double> result("points");
    const int64_t count = points.getShape()[0];
    result.resize({count, 2});
    for (int64_t i = 0; i < count; ++i) {
        const Eigen::Vector2d mapped = map(Eigen::Vector2d(points.data()[2 * i], points.data()[2 * i + 1]));
        result.data()[2 * i] = mapped.x();
        result.data()[2 * i + 1] = mapped.y();
    }
    return result;
}

} // namespace

sp::reflect::SpArray<double>
UCameraSensorComponent::DistortPixels(const sp::reflect::SpArray<double>& Points) const {
    const sp::render::LensModel lens = lensModel();
    return mapPixels(Points, "DistortPixels", [&](const Eigen::Vector2d& p) { return lens.distortPixel(p); });
}

sp::reflect::SpArray<double>
UCameraSensorComponent::UndistortPixels(const sp::reflect::SpArray<double>& Points) const {
    const sp::render::LensModel lens = lensModel();
    return mapPixels(Points, "UndistortPixels",
                     [&](const Eigen::Vector2d& p) { return lens.undistortPixel(p); });
}

sp::reflect::SpArray<double> UCameraSensorComponent::GetWorldToCamera() const {
    // The component's frame looks along +X with +Y left and +Z up; OpenCV's looks along +z with x right, y
    // down.
    Eigen::Matrix4d bodyToOpenCv = Eigen::Matrix4d::Zero();
    bodyToOpenCv(0, 1) = -1.0;
    bodyToOpenCv(1, 2) = -1.0;
    bodyToOpenCv(2, 0) = 1.0;
    bodyToOpenCv(3, 3) = 1.0;
    const Eigen::Matrix4d worldToCamera =
        bodyToOpenCv * GetComponentTransform().toIsometry().inverse().matrix();
    sp::reflect::SpArray<double> t("world_to_camera");
    t.resize({4, 4});
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column)
            t.data()[4 * row + column] = worldToCamera(row, column);
    return t;
}

FCameraPixels UCameraSensorComponent::read_pixels() {
    return subsystemOf(*this, "read_pixels").readPixels(*this);
}

void UCameraSensorComponent::RenderNow() {
    subsystemOf(*this, "RenderNow").renderNow(*this);
}

FCameraPixels
UCameraSensorComponent::read_pixels_stacked(const std::vector<UCameraSensorComponent*>& Cameras) {
    return sp::sensors::RenderSubsystem::readPixelsStacked(Cameras,
                                                           "UCameraSensorComponent.read_pixels_stacked()");
}

void UCameraSensorComponent::SetModalityNames(const std::vector<std::string>& Names) {
    std::vector<ECameraModality> modalities;
    for (const std::string& name : Names) {
        std::optional<ECameraModality> found;
        std::string known;
        for (std::size_t i = 0; i < sp::render::kModalityCount; ++i) {
            const std::string_view candidate = sp::render::modalityName(static_cast<sp::render::Modality>(i));
            if (candidate == name)
                found = static_cast<ECameraModality>(i);
            known += (i ? ", " : "") + std::string(candidate);
        }
        SP_CHECK(found, sp::InvalidArgument, "UCameraSensorComponent.SetModalityNames(): unknown modality '",
                 name, "' (valid: ", known, ")");
        modalities.push_back(*found);
    }
    Modalities = std::move(modalities);
}

std::vector<std::string> UCameraSensorComponent::GetModalityNames() const {
    std::vector<std::string> names;
    for (ECameraModality modality : Modalities)
        names.emplace_back(sp::render::modalityName(static_cast<sp::render::Modality>(modality)));
    return names;
}

bool UCameraSensorComponent::GetObjectIdInfo(int64_t ObjectId, AActor*& Actor,
                                             UPrimitiveComponent*& Component, int32_t& MaterialSlot,
                                             std::string& MaterialName) const {
    Actor = nullptr;
    Component = nullptr;
    MaterialSlot = -1;
    MaterialName.clear();
    if (ObjectId <= 0 || ObjectId > int64_t(UINT32_MAX))
        return false;
    auto info = subsystemOf(*this, "GetObjectIdInfo").objectIdInfo(uint32_t(ObjectId));
    if (!info)
        return false;
    // A primitive's pixels, a spline's debug line (whose component is no primitive: Component stays None), or
    // the drawn roads of an AZoneGraphData (an actor: no component).
    sp::reflect::ObjectBase* object = sp::reflect::ObjectTable::find(info->component);
    if (auto* actor = dynamic_cast<AActor*>(object)) {
        Actor = actor;
    } else if (auto* component = dynamic_cast<UActorComponent*>(object)) {
        Component = dynamic_cast<UPrimitiveComponent*>(component);
        Actor = component->GetOwner();
    } else {
        return false;
    }
    MaterialSlot = info->slot;
    MaterialName = info->materialName;
    return true;
}

int64_t UCameraSensorComponent::GetObjectId(UPrimitiveComponent* Component, int32_t MaterialSlot) const {
    SP_CHECK(Component, sp::InvalidArgument, "UCameraSensorComponent.GetObjectId(): Component is None");
    return subsystemOf(*this, "GetObjectId").objectId(Component->GetHandle(), MaterialSlot);
}

int64_t UCameraSensorComponent::GetMaterialId(const std::string& Name) const {
    return subsystemOf(*this, "GetMaterialId").materialId(Name);
}

FRenderDeviceInfo UCameraSensorComponent::get_render_device_info() {
    return subsystemOf(*this, "get_render_device_info").deviceInfo();
}

FRenderStats UCameraSensorComponent::GetRenderStats() const {
    return subsystemOf(*this, "GetRenderStats").stats();
}
