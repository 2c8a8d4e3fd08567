#pragma once
// Golden case: every type and feature the generator supports, in one header. UE spellings are used on
// purpose (UCLASS, UPROPERTY, UFUNCTION, GENERATED_BODY) to check that they are aliases.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/reflect/class_ref.h"
#include "core/reflect/macros.h"
#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "core/world/math.h"

/// A colour channel.
UENUM()
enum class EChannel : uint8_t {
    /// Red.
    Red = 1,
    /// Green.
    Green = 2,
    /// Blue.
    Blue = 4,
};

/// A sample with nested struct, enum and container fields.
USTRUCT()
struct FSample {
    GENERATED_BODY()

    /// Where it was taken.
    UPROPERTY()
    FVector Where{1.0, 2.0, 3.0};
    /// Which channel.
    UPROPERTY()
    EChannel Channel = EChannel::Green;
    /// Raw values.
    UPROPERTY()
    std::vector<double> Values;
    /// A count.
    UPROPERTY()
    int32_t Count = 7;
};

/// Images keyed by name; only the ones produced are present.
USTRUCT(TypedDict, Partial)
struct FImages {
    GENERATED_BODY()

    /// Colour, (H, W, 4).
    UPROPERTY()
    sp::reflect::SpArray<uint8_t> color;
    /// Depth in metres, (H, W).
    UPROPERTY()
    sp::reflect::SpArray<float> depth;
};

/// Measurements of a point cloud; a complete TypedDict: every entry is always produced.
USTRUCT(TypedDict)
struct FCloudStats {
    GENERATED_BODY()

    /// Distance of each point from the origin, (N,).
    UPROPERTY()
    sp::reflect::SpArray<float> distances;
    /// How many points there were.
    UPROPERTY()
    int64_t count = 0;
};

/// An actor whose API uses every supported type.
UCLASS()
class AAllTypes : public AActor {
    GENERATED_BODY()
public:
    /// A flag.
    UPROPERTY(EditAnywhere)
    bool bFlag = true;
    /// A small unsigned integer.
    UPROPERTY()
    uint8_t Small = 3;
    /// A 64-bit integer.
    UPROPERTY()
    int64_t Big = -5;
    /// A float.
    UPROPERTY()
    float Ratio = 0.5f;
    /// A name.
    UPROPERTY()
    std::string Label = "none";
    /// A reference to another actor.
    UPROPERTY()
    AActor* Target = nullptr;
    /// Named weights.
    UPROPERTY()
    std::map<std::string, float> Weights;
    /// Visible but not writable from Python.
    UPROPERTY(VisibleAnywhere)
    int32_t Counter = 0;
    /// Written through its setter.
    UPROPERTY(Setter = SetSpeed)
    double Speed = 1.0;

    /// Sets Speed, clamped to be non-negative.
    UFUNCTION(BlueprintCallable)
    void SetSpeed(double NewSpeed);

    /// Returns a scaled copy of the sample.
    UFUNCTION()
    FSample Scale(const FSample& Sample, double Factor = 2.0, EChannel Channel = EChannel::Red) const;

    /// Splits a string, with out-parameters.
    UFUNCTION()
    bool Split(const std::string& Text, std::string& Head, std::vector<std::string>& Rest);

    /// Returns the actors of a class, typed by it.
    UFUNCTION(meta = (DeterminesOutputType = "ActorClass"))
    std::vector<AActor*> Collect(TSubclassOf<AActor> ActorClass, const std::vector<AActor*>& Candidates = {});

    /// Returns the class of an object, or None.
    UFUNCTION()
    const UClass* ClassOf(UObject* Object = nullptr) const;

    /// Normalises points (N, 3) in place and returns their lengths (N,).
    UFUNCTION()
    sp::reflect::SpArray<float> Normalise(const sp::reflect::SpArray<float>& Points);

    /// Returns a histogram of byte values.
    UFUNCTION()
    static std::map<std::string, int64_t> Histogram(const sp::reflect::SpArray<uint8_t>& Bytes, int Bins = 16);

    /// Renders the requested images.
    UFUNCTION()
    FImages Render(const std::vector<std::string>& Names);
    /// Measures a cloud of (N, 3) points.
    UFUNCTION()
    FCloudStats Measure(const sp::reflect::SpArray<float>& Points);

    /// Never returns None.
    UFUNCTION(NotNull)
    AActor* Self();
};
