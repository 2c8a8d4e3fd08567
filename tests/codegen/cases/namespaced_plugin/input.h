#pragma once
// Golden case: a plugin whose classes live in a namespace, one deriving from another, with enum and struct
// defaults spelled as they read inside the namespace, and static functions. The generated C++ is outside
// the namespace, so every name it takes from here must be spelled in full (test_generator.py also compiles
// it). Generated with --package namespaced_plugin.

#include <cstdint>
#include <string>

#include "core/reflect/macros.h"
#include "core/world/actor.h"
#include "core/world/math.h"

namespace acme::robots {

/// How a robot moves.
SPENUM()
enum class EGait : uint8_t {
    /// Steps.
    Walk = 0,
    /// Runs.
    Run = 1,
};

/// A robot's tuning.
SPSTRUCT()
struct FGaitSettings {
    SP_GENERATED_BODY()

    /// Stride in metres.
    SPPROPERTY()
    double Stride = 0.5;
    /// The gait it starts in.
    SPPROPERTY()
    EGait Gait = EGait::Walk;
};

/// A robot.
SPCLASS()
class ABaseBot : public AActor {
    SP_GENERATED_BODY()
  public:
    /// Speed in metres per second.
    SPPROPERTY()
    double Speed = 1.0;

    /// Sets the gait (running unless told).
    SPFUNCTION()
    void SetGait(EGait Gait = EGait::Run, const FGaitSettings& Settings = FGaitSettings()) {
        gait_ = Gait;
        settings_ = Settings;
    }

    /// Returns the gait.
    SPFUNCTION()
    EGait GetGait() const { return gait_; }

    /// Returns how many robots a fleet of Count has, plus Spares.
    SPFUNCTION()
    static int32_t FleetSize(int32_t Count, int32_t Spares = 0) { return Count + Spares; }

  private:
    EGait gait_ = EGait::Walk;
    FGaitSettings settings_;
};

/// A robot that walks on legs.
SPCLASS()
class AWalkerBot : public ABaseBot {
    SP_GENERATED_BODY()
  public:
    /// Number of legs.
    SPPROPERTY()
    int32_t Legs = 2;

    /// Returns the robot it follows, or None.
    SPFUNCTION()
    ABaseBot* GetLeader() const { return leader_; }

  private:
    ABaseBot* leader_ = nullptr;
};

} // namespace acme::robots
