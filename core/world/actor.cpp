#include "core/world/actor.h"

#include <algorithm>
#include <cctype>

#include "core/base/error.h"
#include "core/world/primitive_component.h"
#include "core/world/world.h"

AActor::AActor() = default;

AActor::~AActor() {
    // Children first, so that no component outlives the one it is attached to during teardown.
    RootComponent = nullptr;
    while (!components_.empty()) {
        sp::reflect::ObjectTable::rememberName(*components_.back());
        components_.pop_back();
    }
}

void AActor::adoptComponent(std::unique_ptr<UActorComponent> component, std::string name,
                            std::string_view function) {
    for (const auto& existing : components_)
        SP_CHECK(existing->GetName() != name, sp::InvalidArgument, function, ": ", GetDebugName(),
                 " already has a component named '", name, "'");
    component->InitObject(std::move(name), GetWorld());
    component->SetOwner(this);
    if (auto* scene = dynamic_cast<USceneComponent*>(component.get())) {
        if (!RootComponent)
            RootComponent = scene;
        else
            scene->AttachToComponent(RootComponent, false);
    }
    UActorComponent* raw = component.get();
    components_.push_back(std::move(component));
    if (begunPlay_)
        beginComponentPlay(*raw);
}

void AActor::beginComponentPlay(UActorComponent& component) {
    if (component.HasBegunPlay()) // began already: created during its actor's BeginPlay
        return;
    component.BeginPlay();
    component.SetBegunPlay(true);
    if (UWorld* world = GetWorld())
        world->NotifyComponentBeginPlay(component);
}

void AActor::endComponentPlay(UActorComponent& component) {
    if (component.HasBegunPlay()) {
        component.SetBegunPlay(false);
        if (UWorld* world = GetWorld())
            world->NotifyComponentEndPlay(component);
    }
    component.EndPlay();
}

UActorComponent* AActor::CreateComponent(const UClass& type, std::string name, std::string_view function) {
    SP_CHECK(type.isChildOf(UActorComponent::StaticClass()) && type.create, sp::InvalidArgument, function,
             ": class '", type.name, "' is not a component class that can be created");
    std::unique_ptr<UActorComponent> component(static_cast<UActorComponent*>(type.create()));
    UActorComponent* raw = component.get();
    adoptComponent(std::move(component), std::move(name), function);
    return raw;
}

UActorComponent* AActor::AddComponentByClass(TSubclassOf<UActorComponent> ComponentClass,
                                             const FTransform& RelativeTransform, const std::string& Name,
                                             const std::string& AttachParent) {
    constexpr std::string_view kFunction = "AActor.AddComponentByClass()";
    const UClass* type = ComponentClass.Get();
    SP_CHECK(type, sp::InvalidArgument, kFunction, ": ComponentClass is None");
    USceneComponent* parent = nullptr;
    if (!AttachParent.empty()) {
        parent = dynamic_cast<USceneComponent*>(FindComponentByName(AttachParent));
        SP_CHECK(parent, sp::InvalidArgument, kFunction, ": AttachParent '", AttachParent,
                 "' is not a scene component of ", GetDebugName());
    }
    std::string name = Name;
    if (name.empty()) { // UE's names: the class's without its prefix letter, numbered after the first
        const bool prefixed =
            type->name.size() > 1 && std::isupper(static_cast<unsigned char>(type->name[1]));
        const std::string base = prefixed ? type->name.substr(1) : type->name;
        name = base;
        for (int n = 1; FindComponentByName(name); ++n)
            name = base + "_" + std::to_string(n);
    }
    UActorComponent* component = CreateComponent(*type, std::move(name), kFunction);
    if (auto* scene = dynamic_cast<USceneComponent*>(component)) {
        if (parent && scene != RootComponent)
            scene->AttachToComponent(parent, false);
        scene->SetRelativeTransform(RelativeTransform);
    }
    return component;
}

void AActor::K2_DestroyComponent(UActorComponent* Component) {
    SP_CHECK(Component, sp::InvalidArgument, "AActor.K2_DestroyComponent(): Component is None");
    DestroyComponent(Component);
}

UActorComponent* AActor::FindComponentByName(std::string_view name) const {
    for (const auto& component : components_)
        if (component->GetName() == name)
            return component.get();
    return nullptr;
}

void AActor::DestroyComponent(UActorComponent* component) {
    auto it = std::find_if(components_.begin(), components_.end(),
                           [&](const auto& owned) { return owned.get() == component; });
    SP_CHECK(it != components_.end(), sp::InvalidArgument,
             "AActor.DestroyComponent(): ", component->GetDebugName(), " is not a component of ",
             GetDebugName());
    SP_CHECK(component != RootComponent, sp::InvalidArgument,
             "AActor.DestroyComponent(): ", component->GetDebugName(), " is the root component of ",
             GetDebugName());
    if (begunPlay_)
        endComponentPlay(*component);
    sp::reflect::ObjectTable::rememberName(*component);
    components_.erase(it);
}

void AActor::SetWorldForComponents() {
    for (const auto& component : components_)
        component->InitObject(component->GetName(), GetWorld());
}

void AActor::SetRootComponent(USceneComponent* NewRootComponent) {
    SP_CHECK(NewRootComponent && NewRootComponent->GetOwner() == this, sp::InvalidArgument,
             "AActor.SetRootComponent(): the new root must be a component of ", GetDebugName());
    NewRootComponent->DetachFromComponent(true);
    if (RootComponent && RootComponent != NewRootComponent)
        RootComponent->AttachToComponent(NewRootComponent, true);
    RootComponent = NewRootComponent;
}

FVector AActor::GetActorLocation() const {
    return RootComponent ? RootComponent->GetComponentLocation() : FVector{};
}

bool AActor::SetActorLocation(const FVector& NewLocation) {
    if (!RootComponent)
        return false;
    RootComponent->SetWorldLocation(NewLocation);
    return true;
}

FRotator AActor::GetActorRotation() const {
    return RootComponent ? RootComponent->GetComponentRotation() : FRotator{};
}

bool AActor::SetActorRotation(const FRotator& NewRotation) {
    if (!RootComponent)
        return false;
    RootComponent->SetWorldRotation(NewRotation);
    return true;
}

bool AActor::K2_SetActorLocationAndRotation(const FVector& NewLocation, const FRotator& NewRotation, bool,
                                            bool) {
    if (!RootComponent)
        return false;
    FTransform world = RootComponent->GetComponentTransform();
    world.Translation = NewLocation;
    world.Rotation = FQuat::fromEigen(NewRotation.toQuaternion());
    RootComponent->SetWorldTransform(world);
    return true;
}

FVector AActor::GetActorScale3D() const {
    return RootComponent ? RootComponent->GetComponentScale() : FVector{1.0, 1.0, 1.0};
}

void AActor::SetActorScale3D(const FVector& NewScale3D) {
    if (!RootComponent)
        return;
    FTransform world = RootComponent->GetComponentTransform();
    world.Scale3D = NewScale3D;
    RootComponent->SetWorldTransform(world);
}

FTransform AActor::GetActorTransform() const {
    return RootComponent ? RootComponent->GetComponentTransform() : FTransform{};
}

bool AActor::SetActorTransform(const FTransform& NewTransform) {
    if (!RootComponent)
        return false;
    RootComponent->SetWorldTransform(NewTransform);
    return true;
}

FVector AActor::GetActorForwardVector() const {
    return RootComponent ? RootComponent->GetForwardVector() : FVector{1.0, 0.0, 0.0};
}

void AActor::GetActorBounds(bool /*bOnlyCollidingComponents*/, FVector& Origin, FVector& BoxExtent) const {
    // Collision is not modelled separately from geometry yet, so both modes use every primitive.
    Eigen::AlignedBox3d bounds;
    for (const auto& component : components_)
        if (const auto* primitive = dynamic_cast<const UPrimitiveComponent*>(component.get()))
            bounds.extend(primitive->GetWorldBounds());
    Origin = bounds.isEmpty() ? GetActorLocation() : FVector::fromEigen(bounds.center());
    BoxExtent = bounds.isEmpty() ? FVector{} : FVector::fromEigen(bounds.sizes() / 2.0);
}

bool AActor::ActorHasTag(const std::string& Tag) const {
    return std::find(Tags.begin(), Tags.end(), Tag) != Tags.end();
}

std::vector<UActorComponent*> AActor::K2_GetComponents() const {
    std::vector<UActorComponent*> result;
    for (const auto& component : components_)
        result.push_back(component.get());
    return result;
}

UActorComponent* AActor::GetComponentByClass(TSubclassOf<UActorComponent> ComponentClass) const {
    SP_CHECK(ComponentClass, sp::InvalidArgument, "AActor.GetComponentByClass(): ComponentClass is None");
    for (const auto& component : components_)
        if (component->IsA(*ComponentClass.Get()))
            return component.get();
    return nullptr;
}

void AActor::BeginPlay() {
    begunPlay_ = true;
    if (UWorld* world = GetWorld())
        world->NotifyActorBeginPlay(*this);
    // By index: a component's BeginPlay may create another (which begins at once, and is skipped here).
    for (std::size_t i = 0; i < components_.size(); ++i)
        beginComponentPlay(*components_[i]);
}

void AActor::Tick(double deltaSeconds) {
    for (const auto& component : components_)
        if (component->bTickEnabled)
            component->TickComponent(deltaSeconds);
}

void AActor::EndPlay() {
    for (const auto& component : components_)
        endComponentPlay(*component);
    // Not playing before the notice: a subsystem made during it must not be told this actor plays.
    const bool wasPlaying = begunPlay_;
    begunPlay_ = false;
    if (wasPlaying)
        if (UWorld* world = GetWorld())
            world->NotifyActorEndPlay(*this);
}

std::vector<AActor*> AActor::GetOverlappingActors(TSubclassOf<AActor> ClassFilter) const {
    SP_CHECK(ClassFilter, sp::InvalidArgument,
             "AActor.GetOverlappingActors(): ClassFilter is None (pass AActor for every actor)");
    std::vector<AActor*> actors;
    for (UActorComponent* component : K2_GetComponents()) {
        const auto* primitive = dynamic_cast<const UPrimitiveComponent*>(component);
        if (!primitive || !primitive->bGenerateOverlapEvents)
            continue;
        for (AActor* actor : primitive->GetOverlappingActors(ClassFilter))
            if (std::find(actors.begin(), actors.end(), actor) == actors.end())
                actors.push_back(actor);
    }
    return actors;
}

bool AActor::IsOverlappingActor(const AActor* Other) const {
    SP_CHECK(Other, sp::InvalidArgument, "AActor.IsOverlappingActor(): Other is None");
    for (UActorComponent* component : K2_GetComponents()) {
        const auto* primitive = dynamic_cast<const UPrimitiveComponent*>(component);
        if (primitive && primitive->bGenerateOverlapEvents && primitive->IsOverlappingActor(Other))
            return true;
    }
    return false;
}

std::string AActor::GetDebugName() const {
    const std::string name = UObject::GetDebugName();
    return streamingLevel_.empty() ? name : name + " of streaming level '" + streamingLevel_ + "'";
}
