#pragma once
// Golden case: a plugin module. Its classes derive from engine classes and its API uses engine structs;
// the engine's declarations are seen here (through the includes) but belong to the engine module, so the
// outputs import them (spear._engine.api / .rpc, generated/engine/cpp/engine_bindings.gen.h) instead.
// Generated with --package plugin_actor, as a plugin outside the spear package would be.

#include <cstdint>
#include <string>
#include <vector>

#include "core/reflect/macros.h"
#include "core/world/actor.h"
#include "core/world/math.h"

/// How a plugin actor reacts to its neighbours.
SPENUM()
enum class EPluginMood : uint8_t {
    /// Keeps its distance.
    Shy = 0,
    /// Comes closer.
    Friendly = 1,
};

/// A plugin struct holding an engine struct.
SPSTRUCT()
struct FPluginSettings {
    SP_GENERATED_BODY()

    /// Where it rests.
    SPPROPERTY()
    FVector Home{0.0, 0.0, 1.0};
    /// How it reacts.
    SPPROPERTY()
    EPluginMood Mood = EPluginMood::Friendly;
};

/// An actor defined by a plugin.
SPCLASS()
class APluginActor : public AActor {
    SP_GENERATED_BODY()
public:
    /// Its radius in metres.
    SPPROPERTY()
    float Radius = 1.0f;
    /// Its settings.
    SPPROPERTY()
    FPluginSettings Settings;
    /// Another actor it follows, or None.
    SPPROPERTY()
    AActor* Leader = nullptr;

    /// Returns its location moved by Delta.
    SPFUNCTION()
    FVector Offset(const FVector& Delta) const;

    /// Returns the actors within Radius.
    SPFUNCTION()
    std::vector<AActor*> Neighbours() const;

    /// Sets its mood, returning the previous one.
    SPFUNCTION()
    EPluginMood SetMood(EPluginMood Mood = EPluginMood::Shy);
};

/// A plugin class derived from a plugin class: its parent is local, its grandparent the engine's.
SPCLASS()
class APluginChild : public APluginActor {
    SP_GENERATED_BODY()
public:
    /// A name.
    SPPROPERTY()
    std::string Nickname;
};
