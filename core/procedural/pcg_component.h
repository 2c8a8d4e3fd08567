#pragma once
// Procedural generation, in the spirit of UE's PCG component: a UPCGComponent fills the box of its
// actor's UBoxComponent (an APCGVolume's) with actors by rules — scattered at a minimum spacing, along a
// spline, or as city blocks of buildings of random heights kept off road splines — deterministically for a
// Seed. Generated actors are ordinary actors (findable, physical, rendered, saved with scenes), tagged
// "PCG:<owner name>", which is how the component finds them again after a scene is loaded.
//
// Generate() does nothing when the rules, the seed and the splines they read are what the last generation
// used (UE's caching); FlushCache() forgets that, so the next Generate() builds afresh. Placement rules
// live in core/procedural/pcg_layout.h.

#include <string>
#include <utility>
#include <vector>

#include "core/procedural/pcg_layout.h"
#include "core/procedural/spline_component.h"
#include "core/reflect/class_ref.h"
#include "core/world/actor.h"
#include "core/world/actor_component.h"
#include "core/world/shape_components.h"
#include "core/world/static_mesh_actor.h"

/// How a UPCGComponent places actors.
SPENUM()
enum class EPCGGenerationMode : uint8_t {
    /// Scattered over the volume, at least Spacing apart, outside actors tagged ExclusionTag.
    Scatter = 0,
    /// Every Spacing metres along each spline actor tagged SplineTag, SplineOffset to its side.
    AlongSpline = 1,
    /// City blocks of buildings (BlockSize, StreetWidth, LotsPerSide, MinHeight, MaxHeight), none within
    /// RoadWidth / 2 of a spline actor tagged RoadTag.
    CityBlocks = 2,
};

/// Generates actors in its owner's box by rules.
SPCLASS()
class UPCGComponent : public UActorComponent {
    SP_GENERATED_BODY()
  public:
    /// How actors are placed.
    SPPROPERTY()
    EPCGGenerationMode GenerationMode = EPCGGenerationMode::Scatter;
    /// Seed of the placement's random draws: the same seed gives the same actors.
    SPPROPERTY()
    int Seed = 0;
    /// The class spawned (AStaticMeshActor and its subclasses take StaticMesh and Materials).
    SPPROPERTY()
    TSubclassOf<AActor> ActorClass = &AStaticMeshActor::StaticClass();
    /// The mesh of spawned static mesh actors.
    SPPROPERTY()
    std::string StaticMesh = "/Engine/BasicShapes/Cube";
    /// Materials drawn from for each spawned static mesh actor (empty: the mesh's own).
    SPPROPERTY()
    std::vector<std::string> Materials;
    /// Scatter: the least distance between two actors; AlongSpline: the distance between them along it.
    SPPROPERTY()
    double Spacing = 2.0;
    /// Scatter: at most this many actors.
    SPPROPERTY()
    int MaxCount = 100;
    /// Scatter and AlongSpline: each actor's uniform scale is drawn from [MinScale, MaxScale].
    SPPROPERTY()
    double MinScale = 1.0;
    SPPROPERTY()
    double MaxScale = 1.0;
    /// Scatter and AlongSpline (unaligned): turn each actor to a random yaw.
    SPPROPERTY()
    bool bRandomYaw = true;
    /// Drop each actor onto the geometry below it (a line trace down the box, before anything is spawned);
    /// where nothing is below, the actor is not placed. Otherwise actors stand on the box's floor.
    SPPROPERTY()
    bool bProjectToGround = true;
    /// Scatter: actors with this tag keep generated actors out of their bounds ("" for none).
    SPPROPERTY()
    std::string ExclusionTag;
    /// AlongSpline: spline actors with this tag are followed, in spawn order. (A tag, not an actor reference:
    /// a generation outlives the actors it read, and scenes save it as it is.)
    SPPROPERTY()
    std::string SplineTag = "PCGSpline";
    /// AlongSpline: the sideways distance from the spline (positive: its left).
    SPPROPERTY()
    double SplineOffset = 0.0;
    /// AlongSpline: place on both sides.
    SPPROPERTY()
    bool bBothSides = false;
    /// AlongSpline: face along the spline.
    SPPROPERTY()
    bool bAlignToSpline = true;
    /// CityBlocks: the side of a block, metres.
    SPPROPERTY()
    double BlockSize = 24.0;
    /// CityBlocks: the street between blocks, metres.
    SPPROPERTY()
    double StreetWidth = 8.0;
    /// CityBlocks: buildings along a block's side (LotsPerSide^2 per block).
    SPPROPERTY()
    int LotsPerSide = 2;
    /// CityBlocks: building heights are drawn from [MinHeight, MaxHeight] metres.
    SPPROPERTY()
    double MinHeight = 6.0;
    SPPROPERTY()
    double MaxHeight = 30.0;
    /// CityBlocks: spline actors with this tag are roads.
    SPPROPERTY()
    std::string RoadTag = "Road";
    /// CityBlocks: the width kept free along roads, metres.
    SPPROPERTY()
    double RoadWidth = 8.0;

    /// Generates: removes the actors of the last generation and spawns new ones, unless nothing the rules
    /// read changed since (bForce: regardless).
    SPFUNCTION()
    void Generate(bool bForce = false);

    /// Destroys the generated actors.
    SPFUNCTION()
    void Cleanup();

    /// Forgets what the last generation was made from, so the next Generate() builds afresh.
    SPFUNCTION()
    void FlushCache();

    /// Returns the generated actors, in generation order.
    SPFUNCTION()
    std::vector<AActor*> GetGeneratedActors() const;

    /// Returns whether generated actors exist.
    SPFUNCTION()
    bool IsGenerated() const { return !GetGeneratedActors().empty(); }

    /// Returns the seconds the last generation took.
    SPFUNCTION()
    double GetLastGenerationSeconds() const { return lastSeconds_; }

  private:
    // What a generation reads from the world, gathered once: its box, the splines it follows (AlongSpline)
    // or keeps off (CityBlocks), the boxes it keeps out of (Scatter).
    struct Inputs {
        Eigen::AlignedBox3d box;
        std::vector<sp::procedural::pcg::Polyline> lines;
        std::vector<Eigen::AlignedBox2d> exclusions;
    };
    Inputs gather(const char* function) const;
    // Everything a generation reads, as text: equal text, equal result.
    std::string generationKey(const Inputs& inputs) const;
    std::string tag() const;
    Eigen::AlignedBox3d volume(const char* function) const;
    void check(const char* function) const;
    void checkScale(const Eigen::AlignedBox3d& box, const char* function) const;
    // Spawns an actor per (placement, base height).
    void spawn(const std::vector<std::pair<sp::procedural::pcg::Placement, double>>& grounded,
               const char* function);

    std::string cachedKey_;
    double lastSeconds_ = 0.0;
};

/// A box to generate in: its BoxComponent (which collides with nothing) bounds the UPCGComponent's work.
SPCLASS()
class APCGVolume : public AActor {
    SP_GENERATED_BODY()
  public:
    APCGVolume();

    /// The generation's box (the root component).
    SPPROPERTY(ReadOnly, NotNull)
    UBoxComponent* BoxComponent = nullptr;

    /// The generator.
    SPPROPERTY(ReadOnly, NotNull)
    UPCGComponent* PCGComponent = nullptr;
};
