#include "core/world/world.h"

#include <algorithm>

#include "core/base/error.h"

UWorld::UWorld() {
    InitObject("World", this);
}

UWorld::~UWorld() {
    // Actors first: their components unregister from the subsystems as they go.
    for (auto it = actors_.rbegin(); it != actors_.rend(); ++it) {
        if ((*it)->HasBegunPlay())
            (*it)->EndPlay();
        sp::reflect::ObjectTable::rememberName(**it);
    }
    actors_.clear();
    defaultObjects_.clear();
    while (!subsystems_.empty())
        subsystems_.pop_back();
}

void UWorld::addSubsystem(std::type_index type, int tickOrder, std::unique_ptr<sp::world::WorldSubsystem> subsystem) {
    auto it = std::find_if(subsystems_.begin(), subsystems_.end(),
                           [&](const SubsystemEntry& entry) { return entry.tickOrder > tickOrder; });
    subsystems_.insert(it, SubsystemEntry{type, tickOrder, std::move(subsystem)});
}

std::string UWorld::uniqueActorName(const UClass& type) const {
    // UE style: the class name without its prefix letter, then a counter that never repeats.
    std::string base = type.name.size() > 1 && (type.name[0] == 'A') ? type.name.substr(1) : type.name;
    int& counter = nameCounters_[base];
    std::string name;
    do {
        name = base + "_" + std::to_string(counter++);
    } while (find_actor_by_name(name));
    return name;
}

AActor* UWorld::spawn_actor(TSubclassOf<AActor> uclass, const FVector& location, const FRotator& rotation,
                            const std::string& name, const std::vector<std::string>& tags) {
    SP_CHECK(uclass, sp::InvalidArgument, "UWorld.spawn_actor(): uclass is None");
    const UClass& type = *uclass.Get();
    SP_CHECK(type.create, sp::InvalidArgument, "UWorld.spawn_actor(): class '", type.name,
             "' is abstract and cannot be spawned");
    SP_CHECK(name.empty() || !find_actor_by_name(name), sp::InvalidArgument, "UWorld.spawn_actor(): name '",
             name, "' is already used in this world");
    std::unique_ptr<AActor> actor(static_cast<AActor*>(type.create()));
    actor->InitObject(name.empty() ? uniqueActorName(type) : name, this);
    actor->SetWorldForComponents();
    actor->Tags.insert(actor->Tags.end(), tags.begin(), tags.end());
    if (actor->RootComponent) {
        actor->RootComponent->RelativeLocation = location;
        actor->RootComponent->RelativeRotation = rotation;
    }
    AActor* raw = actor.get();
    actors_.push_back(std::move(actor));
    raw->BeginPlay();
    return raw;
}

void UWorld::destroy_actor(AActor* actor) {
    SP_CHECK(actor, sp::InvalidArgument, "UWorld.destroy_actor(): actor is None");
    auto it =
        std::find_if(actors_.begin(), actors_.end(), [&](const auto& owned) { return owned.get() == actor; });
    SP_CHECK(it != actors_.end(), sp::InvalidArgument, "UWorld.destroy_actor(): ", actor->GetDebugName(),
             " is not in this world");
    if (ticking_) { // an actor destroyed during a tick goes away after the tick
        if (std::find(pendingDestroy_.begin(), pendingDestroy_.end(), actor) == pendingDestroy_.end())
            pendingDestroy_.push_back(actor);
        return;
    }
    if (actor->HasBegunPlay())
        actor->EndPlay();
    sp::reflect::ObjectTable::rememberName(*actor);
    actors_.erase(it);
}

AActor* UWorld::find_actor_by_name(const std::string& name) const {
    for (const auto& actor : actors_)
        if (actor->GetName() == name)
            return actor.get();
    return nullptr;
}

std::vector<AActor*> UWorld::find_actors_by_tag(const std::string& tag) const {
    std::vector<AActor*> result;
    for (const auto& actor : actors_)
        if (actor->ActorHasTag(tag))
            result.push_back(actor.get());
    return result;
}

AActor* UWorld::find_actor_by_class(TSubclassOf<AActor> uclass) const {
    SP_CHECK(uclass, sp::InvalidArgument, "UWorld.find_actor_by_class(): uclass is None");
    for (const auto& actor : actors_)
        if (actor->IsA(*uclass.Get()))
            return actor.get();
    return nullptr;
}

std::vector<AActor*> UWorld::find_actors_by_class(TSubclassOf<AActor> uclass) const {
    SP_CHECK(uclass, sp::InvalidArgument, "UWorld.find_actors_by_class(): uclass is None");
    std::vector<AActor*> result;
    for (const auto& actor : actors_)
        if (actor->IsA(*uclass.Get()))
            result.push_back(actor.get());
    return result;
}

std::map<std::string, AActor*> UWorld::find_actors_by_class_as_dict(TSubclassOf<AActor> uclass) const {
    std::map<std::string, AActor*> result;
    for (AActor* actor : find_actors_by_class(uclass))
        result.emplace(actor->GetName(), actor);
    return result;
}

std::vector<AActor*> UWorld::find_actors() const {
    std::vector<AActor*> result;
    for (const auto& actor : actors_)
        result.push_back(actor.get());
    return result;
}

UActorComponent* UWorld::get_component_by_name(AActor* actor, const std::string& component_name) const {
    SP_CHECK(actor, sp::InvalidArgument, "UWorld.get_component_by_name(): actor is None");
    for (const auto& component : actor->GetComponentList())
        if (component->GetName() == component_name)
            return component.get();
    return nullptr;
}

std::vector<UActorComponent*> UWorld::get_components_by_class(AActor* actor,
                                                              TSubclassOf<UActorComponent> uclass) const {
    SP_CHECK(actor, sp::InvalidArgument, "UWorld.get_components_by_class(): actor is None");
    SP_CHECK(uclass, sp::InvalidArgument, "UWorld.get_components_by_class(): uclass is None");
    std::vector<UActorComponent*> result;
    for (const auto& component : actor->GetComponentList())
        if (component->IsA(*uclass.Get()))
            result.push_back(component.get());
    return result;
}

std::map<std::string, UActorComponent*>
UWorld::get_components_by_class_as_dict(AActor* actor, TSubclassOf<UActorComponent> uclass) const {
    std::map<std::string, UActorComponent*> result;
    for (UActorComponent* component : get_components_by_class(actor, uclass))
        result.emplace(component->GetName(), component);
    return result;
}

UObject* UWorld::get_default_object(TSubclassOf<UObject> uclass) {
    SP_CHECK(uclass, sp::InvalidArgument, "UWorld.get_default_object(): uclass is None");
    const UClass& type = *uclass.Get();
    SP_CHECK(type.create, sp::InvalidArgument, "UWorld.get_default_object(): class '", type.name,
             "' is abstract and has no default object");
    auto& object = defaultObjects_[&type];
    if (!object) {
        object.reset(static_cast<UObject*>(type.create()));
        object->InitObject("Default__" + type.name, nullptr);
    }
    return object.get();
}

void UWorld::Tick(double deltaSeconds) {
    ticking_ = true;
    try {
        // Index loop: an actor spawned during the tick is appended and ticks from the next frame.
        const size_t count = actors_.size();
        for (size_t i = 0; i < count; ++i)
            if (std::find(pendingDestroy_.begin(), pendingDestroy_.end(), actors_[i].get()) ==
                pendingDestroy_.end())
                actors_[i]->Tick(deltaSeconds);
    } catch (...) {
        ticking_ = false;
        throw;
    }
    ticking_ = false;
    for (AActor* actor : std::exchange(pendingDestroy_, {}))
        destroy_actor(actor);
    // Index loop: a subsystem may create another one while ticking.
    for (size_t i = 0; i < subsystems_.size(); ++i)
        subsystems_[i].subsystem->Tick(deltaSeconds);
    timeSeconds_ += deltaSeconds;
    ++frameCount_;
}
