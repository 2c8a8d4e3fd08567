#include "core/procedural/pcg_component.h"

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

#include "core/base/error.h"
#include "core/base/progress.h"
#include "core/procedural/pcg_layout.h"
#include "core/world/world.h"

namespace {

namespace pcg = sp::procedural::pcg;

// Splines are followed through points this far apart along them (world space), or through at most
// kMaxSplineSegments + 1 points for very long ones.
constexpr double kSplineStep = 0.25;
constexpr int kMaxSplineSegments = 100'000;
// The most placements one generation may lay out.
constexpr double kMaxPlacements = 1e6;

Eigen::AlignedBox2d flat(const Eigen::AlignedBox3d& box) {
    return {box.min().head<2>(), box.max().head<2>()};
}

// The splines of the spline actors tagged `tag`, in spawn order.
std::vector<pcg::Polyline> splinesTagged(const UWorld& world, const std::string& tag) {
    std::vector<pcg::Polyline> lines;
    for (AActor* actor : world.find_actors_by_tag(tag))
        if (auto* spline = dynamic_cast<ASplineActor*>(actor))
            lines.push_back(spline->SplineComponent->worldPolyline(kSplineStep, kMaxSplineSegments));
    return lines;
}

double lengthOf(const pcg::Polyline& line) {
    double length = 0.0;
    for (size_t i = 0; i + 1 < line.size(); ++i)
        length += (line[i + 1] - line[i]).norm();
    return length;
}

Eigen::AlignedBox3d boundsOf(const AActor& actor) {
    FVector origin, extent;
    actor.GetActorBounds(false, origin, extent);
    return {origin.toEigen() - extent.toEigen(), origin.toEigen() + extent.toEigen()};
}

} // namespace

void UPCGComponent::check(const char* function) const {
    auto require = [&](bool ok, const char* property, const char* range, double value) {
        SP_CHECK(ok, sp::InvalidArgument, function, ": ", property, " = ", value, " must be ", range);
    };
    SP_CHECK(ActorClass.Get(), sp::InvalidArgument, function, ": ActorClass is None");
    switch (GenerationMode) {
    case EPCGGenerationMode::Scatter:
        require(MaxCount >= 0, "MaxCount", ">= 0", MaxCount);
        [[fallthrough]];
    case EPCGGenerationMode::AlongSpline:
        require(std::isfinite(Spacing) && Spacing > 0.0, "Spacing", "a finite number > 0", Spacing);
        require(std::isfinite(MinScale) && MinScale > 0.0, "MinScale", "a finite number > 0", MinScale);
        require(std::isfinite(MaxScale) && MaxScale >= MinScale, "MaxScale", ">= MinScale", MaxScale);
        require(std::isfinite(SplineOffset), "SplineOffset", "finite", SplineOffset);
        break;
    case EPCGGenerationMode::CityBlocks:
        require(std::isfinite(BlockSize) && BlockSize > 0.0, "BlockSize", "a finite number > 0", BlockSize);
        require(std::isfinite(StreetWidth) && StreetWidth >= 0.0, "StreetWidth", "a finite number >= 0",
                StreetWidth);
        require(LotsPerSide >= 1 && LotsPerSide <= 64, "LotsPerSide", "in [1, 64]", LotsPerSide);
        require(std::isfinite(MinHeight) && MinHeight > 0.0, "MinHeight", "a finite number > 0", MinHeight);
        require(std::isfinite(MaxHeight) && MaxHeight >= MinHeight, "MaxHeight", ">= MinHeight", MaxHeight);
        require(std::isfinite(RoadWidth) && RoadWidth >= 0.0, "RoadWidth", "a finite number >= 0", RoadWidth);
        break;
    }
}

void UPCGComponent::checkScale(const Eigen::AlignedBox3d& box, const char* function) const {
    // Counted in doubles before anything is allocated: rules that would lay out millions are refused.
    const Eigen::Vector3d size = box.sizes();
    if (GenerationMode == EPCGGenerationMode::Scatter) {
        // The work and memory follow MaxCount (scatter() stores only the cells it fills); the cells along an
        // axis must fit its 64-bit cell keys.
        const double cell = Spacing / std::sqrt(2.0);
        SP_CHECK(MaxCount <= kMaxPlacements, sp::InvalidArgument, function, ": MaxCount = ", MaxCount,
                 " asks for more than ", kMaxPlacements, " placements");
        SP_CHECK(size.x() / cell <= 2147483648.0 && size.y() / cell <= 2147483648.0, sp::InvalidArgument,
                 function, ": Spacing = ", Spacing, " over a ", size.x(), " x ", size.y(),
                 " m box makes more than 2^31 cells along a side");
    }
    if (GenerationMode == EPCGGenerationMode::CityBlocks) {
        const double pitch = BlockSize + StreetWidth;
        const double lots = (std::floor(size.x() / pitch) + 1) * (std::floor(size.y() / pitch) + 1) *
                            double(LotsPerSide) * double(LotsPerSide);
        SP_CHECK(lots <= kMaxPlacements, sp::InvalidArgument, function, ": BlockSize = ", BlockSize,
                 " and StreetWidth = ", StreetWidth, " over a ", size.x(), " x ", size.y(), " m box make ",
                 lots, " lots, more than ", kMaxPlacements);
    }
}

Eigen::AlignedBox3d UPCGComponent::volume(const char* function) const {
    const AActor* owner = GetOwner();
    SP_CHECK(owner && GetWorld(), sp::InvalidState, function, ": ", GetDebugName(),
             " is not on an actor in a world");
    const auto* box =
        dynamic_cast<const UBoxComponent*>(owner->GetComponentByClass(&UBoxComponent::StaticClass()));
    SP_CHECK(box, sp::InvalidState, function, ": ", owner->GetDebugName(),
             " has no UBoxComponent to generate in (use an APCGVolume)");
    return box->worldBox();
}

std::string UPCGComponent::tag() const {
    return "PCG:" + (GetOwner() ? GetOwner()->GetName() : std::string());
}

UPCGComponent::Inputs UPCGComponent::gather(const char* function) const {
    Inputs inputs;
    inputs.box = volume(function);
    if (GenerationMode == EPCGGenerationMode::AlongSpline)
        inputs.lines = splinesTagged(*GetWorld(), SplineTag);
    if (GenerationMode == EPCGGenerationMode::CityBlocks)
        inputs.lines = splinesTagged(*GetWorld(), RoadTag);
    if (GenerationMode == EPCGGenerationMode::Scatter && !ExclusionTag.empty())
        for (AActor* excluded : GetWorld()->find_actors_by_tag(ExclusionTag))
            inputs.exclusions.push_back(flat(boundsOf(*excluded)));
    return inputs;
}

std::string UPCGComponent::generationKey(const Inputs& inputs) const {
    std::ostringstream key;
    key.precision(17);
    key << int(GenerationMode) << ' ' << Seed << ' ' << ActorClass.Get()->name << ' ' << StaticMesh << ' '
        << Spacing << ' ' << MaxCount << ' ' << MinScale << ' ' << MaxScale << ' ' << bRandomYaw << ' '
        << bProjectToGround << ' ' << ExclusionTag << ' ' << SplineOffset << ' ' << bBothSides << ' '
        << bAlignToSpline << ' ' << BlockSize << ' ' << StreetWidth << ' ' << LotsPerSide << ' ' << MinHeight
        << ' ' << MaxHeight << ' ' << RoadTag << ' ' << RoadWidth << " box " << inputs.box.min().transpose()
        << ' ' << inputs.box.max().transpose() << " materials";
    for (const std::string& material : Materials)
        key << ' ' << material;
    for (const pcg::Polyline& line : inputs.lines) {
        key << " line";
        for (const Eigen::Vector3d& p : line)
            key << ' ' << p.x() << ' ' << p.y() << ' ' << p.z();
    }
    for (const Eigen::AlignedBox2d& excluded : inputs.exclusions)
        key << " exclude " << excluded.min().transpose() << ' ' << excluded.max().transpose();
    return key.str();
}

std::vector<AActor*> UPCGComponent::GetGeneratedActors() const {
    if (!GetWorld() || !GetOwner())
        return {};
    return GetWorld()->find_actors_by_tag(tag());
}

void UPCGComponent::Cleanup() {
    for (AActor* actor : GetGeneratedActors())
        GetWorld()->destroy_actor(actor);
    cachedKey_.clear();
}

void UPCGComponent::FlushCache() {
    cachedKey_.clear();
}

void UPCGComponent::Generate(bool bForce) {
    constexpr const char* kFunction = "UPCGComponent.Generate()";
    check(kFunction);
    const Inputs inputs = gather(kFunction);
    const std::string key = generationKey(inputs);
    if (!bForce && key == cachedKey_ && IsGenerated())
        return;
    const auto start = std::chrono::steady_clock::now();
    Cleanup();
    UWorld& world = *GetWorld();
    const Eigen::AlignedBox3d& box = inputs.box;
    checkScale(box, kFunction);
    std::mt19937_64 rng{uint64_t(uint32_t(Seed))};
    const int variants = std::max(1, int(Materials.size()));

    std::vector<pcg::Placement> placements;
    switch (GenerationMode) {
    case EPCGGenerationMode::Scatter:
        placements = pcg::scatter(flat(box), {Spacing, MaxCount, MinScale, MaxScale, bRandomYaw, variants},
                                  inputs.exclusions, rng);
        break;
    case EPCGGenerationMode::AlongSpline: {
        const std::vector<pcg::Polyline>& splines = inputs.lines;
        SP_CHECK(!splines.empty(), sp::InvalidArgument, kFunction, ": no ASplineActor has SplineTag '",
                 SplineTag, "' (AlongSpline follows them)");
        double length = 0.0;
        for (const pcg::Polyline& line : splines)
            length += lengthOf(line);
        SP_CHECK(length / Spacing <= kMaxPlacements, sp::InvalidArgument, kFunction, ": Spacing = ", Spacing,
                 " along ", length, " m of spline makes more than ", kMaxPlacements, " placements");
        for (const pcg::Polyline& line : splines) {
            const auto along = pcg::alongPolyline(
                line,
                {Spacing, SplineOffset, bBothSides, bAlignToSpline, bRandomYaw, MinScale, MaxScale, variants},
                rng);
            placements.insert(placements.end(), along.begin(), along.end());
        }
        break;
    }
    case EPCGGenerationMode::CityBlocks:
        placements = pcg::cityBlocks(
            flat(box), {BlockSize, StreetWidth, LotsPerSide, MinHeight, MaxHeight, RoadWidth, variants},
            inputs.lines, rng);
        break;
    }

    // The bases first (the box's floor, or the ground under each placement), so that no trace meets an
    // actor of this generation.
    std::vector<std::pair<pcg::Placement, double>> grounded;
    for (const pcg::Placement& placement : placements) {
        double base = box.min().z();
        if (bProjectToGround) {
            FHitResult hit;
            AActor* hitActor = nullptr;
            UPrimitiveComponent* hitComponent = nullptr;
            const FVector top{placement.location.x(), placement.location.y(), box.max().z()};
            const FVector bottom{placement.location.x(), placement.location.y(), box.min().z()};
            if (!world.line_trace_single(top, bottom, hit, hitActor, hitComponent))
                continue; // nothing to stand on
            base = hit.ImpactPoint.Z;
        }
        if (box.contains(Eigen::Vector3d(placement.location.x(), placement.location.y(), base)))
            grounded.emplace_back(placement, base); // a spline may leave the box
    }
    try {
        spawn(grounded, kFunction);
    } catch (...) {
        Cleanup(); // no half generation is left behind
        throw;
    }
    cachedKey_ = key;
    lastSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void UPCGComponent::spawn(const std::vector<std::pair<sp::procedural::pcg::Placement, double>>& grounded,
                          const char* function) {
    UWorld& world = *GetWorld();
    sp::base::Progress progress(std::string(function) + ": spawning " + std::to_string(grounded.size()) +
                                    " actors",
                                double(grounded.size()));
    int index = 0;
    for (const auto& [placement, base] : grounded) {
        progress.advance();
        std::string name = GetOwner()->GetName() + "_" + std::to_string(index);
        if (world.find_actor_by_name(name))
            name.clear(); // taken by someone else: a generated name
        AActor* actor =
            world.spawn_actor(ActorClass.Get(), FVector{placement.location.x(), placement.location.y(), base},
                              FRotator{0.0, placement.yawDegrees, 0.0}, name, {tag()});
        if (auto* mesh = dynamic_cast<AStaticMeshActor*>(actor)) {
            try {
                mesh->StaticMeshComponent->SetStaticMesh(StaticMesh);
            } catch (const sp::NotFound& error) { // said in this function's words, with the mesh's reason
                SP_THROW(sp::NotFound, function, ": StaticMesh '", StaticMesh,
                         "' could not be loaded: ", error.what());
            } catch (const sp::InvalidArgument& error) {
                SP_THROW(sp::InvalidArgument, function, ": StaticMesh '", StaticMesh,
                         "' could not be loaded: ", error.what());
            }
            if (!Materials.empty())
                mesh->StaticMeshComponent->SetMaterial(0, Materials[size_t(placement.variant)]);
        }
        actor->SetActorScale3D(FVector::fromEigen(placement.scale));
        // Stand it on its base: its bounds' bottom at the base height.
        const Eigen::AlignedBox3d bounds = boundsOf(*actor);
        if (!bounds.isEmpty()) {
            FVector location = actor->GetActorLocation();
            location.Z += base - bounds.min().z();
            actor->SetActorLocation(location);
        }
        if (actor->RootComponent)
            actor->RootComponent->SetMobility(EComponentMobility::Static);
        ++index;
    }
}

APCGVolume::APCGVolume() {
    BoxComponent = CreateDefaultSubobject<UBoxComponent>("BoxComponent");
    BoxComponent->BoxExtent = FVector{10.0, 10.0, 5.0};
    BoxComponent->CollisionPrimitive = ECollisionPrimitive::NoCollision; // a region, not an obstacle
    BoxComponent->bGenerateOverlapEvents = false;
    BoxComponent->bCanEverAffectNavigation = false;
    PCGComponent = CreateDefaultSubobject<UPCGComponent>("PCGComponent");
}
