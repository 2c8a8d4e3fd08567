#pragma once
// The reflected value types of the engine, with UE's names and fields. Conventions: right-handed,
// Z up, X forward, Y left (as ROS REP-103), metres, angles in degrees.
// FRotator: Yaw turns X toward Y about +Z, Pitch raises X toward +Z, Roll turns Y toward Z about +X;
// the rotation matrix is Rz(Yaw) * Ry(-Pitch) * Rx(Roll).
// Inside the engine, math happens in Eigen; these structs are what crosses the boundary.

#include <Eigen/Geometry>

#include "core/reflect/macros.h"

/// A vector in 3-D space (metres for positions).
SPSTRUCT()
struct FVector {
    SP_GENERATED_BODY()

    /// X component (forward).
    SPPROPERTY()
    double X = 0.0;
    /// Y component (left).
    SPPROPERTY()
    double Y = 0.0;
    /// Z component (up).
    SPPROPERTY()
    double Z = 0.0;

    Eigen::Vector3d toEigen() const { return {X, Y, Z}; }
    static FVector fromEigen(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
    bool isFinite() const { return toEigen().allFinite(); }
    friend bool operator==(const FVector&, const FVector&) = default;
};

/// A vector in 2-D space.
SPSTRUCT()
struct FVector2D {
    SP_GENERATED_BODY()

    /// X component.
    SPPROPERTY()
    double X = 0.0;
    /// Y component.
    SPPROPERTY()
    double Y = 0.0;

    friend bool operator==(const FVector2D&, const FVector2D&) = default;
};

/// An orientation as Euler angles in degrees.
SPSTRUCT()
struct FRotator {
    SP_GENERATED_BODY()

    /// Rotation that raises the X axis toward +Z, in degrees.
    SPPROPERTY()
    double Pitch = 0.0;
    /// Rotation about +Z, in degrees.
    SPPROPERTY()
    double Yaw = 0.0;
    /// Rotation about +X, in degrees.
    SPPROPERTY()
    double Roll = 0.0;

    Eigen::Quaterniond toQuaternion() const;
    static FRotator fromQuaternion(const Eigen::Quaterniond& q);
    friend bool operator==(const FRotator&, const FRotator&) = default;
};

/// A unit quaternion.
SPSTRUCT()
struct FQuat {
    SP_GENERATED_BODY()

    /// X component.
    SPPROPERTY()
    double X = 0.0;
    /// Y component.
    SPPROPERTY()
    double Y = 0.0;
    /// Z component.
    SPPROPERTY()
    double Z = 0.0;
    /// W (scalar) component.
    SPPROPERTY()
    double W = 1.0;

    Eigen::Quaterniond toEigen() const { return {W, X, Y, Z}; }
    static FQuat fromEigen(const Eigen::Quaterniond& q) { return {q.x(), q.y(), q.z(), q.w()}; }
    friend bool operator==(const FQuat&, const FQuat&) = default;
};

/// Translation, rotation and non-uniform scale, applied as scale, then rotation, then translation.
SPSTRUCT()
struct FTransform {
    SP_GENERATED_BODY()

    /// Translation in metres.
    SPPROPERTY()
    FVector Translation;
    /// Rotation.
    SPPROPERTY()
    FQuat Rotation;
    /// Scale along each local axis.
    SPPROPERTY()
    FVector Scale3D{1.0, 1.0, 1.0};

    // Rigid part only (scale is carried separately).
    Eigen::Isometry3d toIsometry() const;
    // This transform applied after `parent`'s: the world transform of a child whose relative one is *this.
    FTransform composedWith(const FTransform& parent) const;
    // The relative transform that composed with `parent` gives *this.
    FTransform relativeTo(const FTransform& parent) const;
    friend bool operator==(const FTransform&, const FTransform&) = default;
};

/// A linear-space colour with alpha; components usually in [0, 1], HDR values may exceed 1.
SPSTRUCT()
struct FLinearColor {
    SP_GENERATED_BODY()

    /// Red.
    SPPROPERTY()
    float R = 0.0f;
    /// Green.
    SPPROPERTY()
    float G = 0.0f;
    /// Blue.
    SPPROPERTY()
    float B = 0.0f;
    /// Alpha.
    SPPROPERTY()
    float A = 1.0f;

    friend bool operator==(const FLinearColor&, const FLinearColor&) = default;
};
