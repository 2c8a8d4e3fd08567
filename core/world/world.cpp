#include "core/world/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include "core/base/error.h"
#include "core/reflect/registry.h"
#include "core/world/input_component.h"
#include "core/world/new_object.h"
#include "core/world/physics_subsystem.h"

namespace {

// Milliseconds between laps, for FFrameTimings.
class Stopwatch {
  public:
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        return ms;
    }

  private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// The stage a subsystem's time is counted in, by its tick order (see sp::world::tick_order).
double& stageOf(FFrameTimings& timings, int tickOrder) {
    if (tickOrder == sp::world::tick_order::kPhysics)
        return timings.PhysicsMs;
    if (tickOrder == sp::world::tick_order::kRendering)
        return timings.RenderingMs;
    return timings.OtherMs;
}

} // namespace

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

void UWorld::addSubsystem(std::type_index type, int tickOrder,
                          std::unique_ptr<sp::world::WorldSubsystem> subsystem) {
    sp::world::WorldSubsystem& added = *subsystem;
    auto it = std::find_if(subsystems_.begin(), subsystems_.end(),
                           [&](const SubsystemEntry& entry) { return entry.tickOrder > tickOrder; });
    subsystems_.insert(it, SubsystemEntry{type, tickOrder, std::move(subsystem)});
    // What began play before the subsystem existed, in the world's order. By index, as a callback may add
    // to the lists; an incoming actor already moved into actors_ is left empty there.
    auto tell = [&](const std::vector<std::unique_ptr<AActor>>& actors) {
        for (std::size_t i = 0; i < actors.size(); ++i) {
            AActor* actor = actors[i].get();
            if (!actor || !actor->HasBegunPlay())
                continue;
            added.OnActorBeginPlay(*actor);
            const auto& components = actor->GetComponentList();
            for (std::size_t c = 0; c < components.size(); ++c)
                if (components[c]->HasBegunPlay())
                    added.OnComponentBeginPlay(*components[c]);
        }
    };
    tell(actors_);
    if (incoming_)
        tell(*incoming_);
}

void UWorld::NotifyActorBeginPlay(AActor& actor) {
    notifySubsystems([&](sp::world::WorldSubsystem& subsystem) { subsystem.OnActorBeginPlay(actor); });
}

void UWorld::NotifyActorEndPlay(AActor& actor) {
    notifySubsystems([&](sp::world::WorldSubsystem& subsystem) { subsystem.OnActorEndPlay(actor); });
}

void UWorld::NotifyComponentBeginPlay(UActorComponent& component) {
    notifySubsystems(
        [&](sp::world::WorldSubsystem& subsystem) { subsystem.OnComponentBeginPlay(component); });
}

void UWorld::NotifyComponentEndPlay(UActorComponent& component) {
    notifySubsystems([&](sp::world::WorldSubsystem& subsystem) { subsystem.OnComponentEndPlay(component); });
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
    SP_CHECK(type.canCreate(), sp::InvalidArgument, "UWorld.spawn_actor(): class '", type.name,
             "' is abstract and cannot be spawned");
    SP_CHECK(name.empty() || !find_actor_by_name(name), sp::InvalidArgument, "UWorld.spawn_actor(): name '",
             name, "' is already used in this world");
    std::unique_ptr<AActor> actor = NewActorDeferred(type, name.empty() ? uniqueActorName(type) : name);
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

std::unique_ptr<AActor> UWorld::NewActorDeferred(const UClass& type, std::string name) {
    SP_CHECK(type.isChildOf(AActor::StaticClass()) && type.canCreate(), sp::InvalidArgument,
             "UWorld: class '", type.name, "' is not an actor class that can be created");
    return std::unique_ptr<AActor>(
        static_cast<AActor*>(sp::world::newObject(type, std::move(name), this).release()));
}

namespace {

// Begins the play of every actor; when one fails, those that began end play again and the error names
// the actor. Checks what construction and property values could not (physics settings Bullet refuses, a
// plugin component's own checks) before the world changes.
void beginPlayAll(const std::vector<std::unique_ptr<AActor>>& actors) {
    size_t begun = 0;
    try {
        for (; begun < actors.size(); ++begun)
            actors[begun]->BeginPlay();
    } catch (...) {
        for (size_t i = std::min(begun + 1, actors.size()); i-- > 0;)
            if (actors[i]->HasBegunPlay())
                actors[i]->EndPlay();
        sp::rethrowWithPrefix("actor '" + actors[begun]->GetName() + "': ");
    }
}

// Marks a batch as incoming (UWorld::incoming_) until the scope ends, then restores the outer batch.
class IncomingActors {
  public:
    using Actors = std::vector<std::unique_ptr<AActor>>;
    IncomingActors(const Actors*& slot, const Actors& actors) : slot_(slot), outer_(slot) { slot_ = &actors; }
    ~IncomingActors() { slot_ = outer_; }
    IncomingActors(const IncomingActors&) = delete;
    IncomingActors& operator=(const IncomingActors&) = delete;

  private:
    const Actors*& slot_;
    const Actors* outer_;
};

} // namespace

void UWorld::ReplaceActors(std::vector<std::unique_ptr<AActor>> actors) {
    SP_CHECK(!ticking_, sp::InvalidState, "UWorld: the actors cannot be replaced while the world ticks");
    // The incoming actors begin play while the old ones are still here, so that a scene that fails there
    // leaves the world as it was; the old actors are only destroyed once every new one has begun.
    const IncomingActors incoming(incoming_, actors);
    beginPlayAll(actors);
    for (AActor* actor : find_actors())
        destroy_actor(actor);
    for (auto& actor : actors)
        actors_.push_back(std::move(actor));
}

void UWorld::AddActors(std::vector<std::unique_ptr<AActor>> actors) {
    SP_CHECK(!ticking_, sp::InvalidState, "UWorld: actors cannot be added while the world ticks");
    const IncomingActors incoming(incoming_, actors);
    beginPlayAll(actors);
    for (auto& actor : actors)
        actors_.push_back(std::move(actor));
}

sp::world::WorldHost& UWorld::assetHost(const char* function) const {
    SP_CHECK(host_, sp::InvalidState, "UWorld.", function, "(): ", GetName(),
             " belongs to no engine, which reads and writes scene files");
    return *host_;
}

void UWorld::load_scene(const std::string& path) {
    assetHost("load_scene").loadScene(*this, path, "UWorld.load_scene()");
}

void UWorld::save_scene(const std::string& path) const {
    assetHost("save_scene").saveScene(*this, path, "UWorld.save_scene()");
}

sp::world::WorldHost& UWorld::editorHost(const char* function) const {
    SP_CHECK(isEditorWorld_ && host_, sp::InvalidState, "UWorld.", function, "(): ", GetName(),
             " is not an editor world; only instance.get_editor() can ", function);
    return *host_;
}

void UWorld::play() {
    editorHost("play").play();
}

void UWorld::stop() {
    editorHost("stop").stop();
}

bool UWorld::is_playing() const {
    return isEditorWorld_ && host_ && host_->IsPlaying();
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
    return actor->FindComponentByName(component_name);
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
    SP_CHECK(type.canCreate(), sp::InvalidArgument, "UWorld.get_default_object(): class '", type.name,
             "' is abstract and has no default object");
    auto& object = defaultObjects_[&type];
    if (!object)
        object = sp::world::newObject(type, "Default__" + type.name, nullptr);
    return object.get();
}

void UWorld::ReleaseDefaultObjects(bool (*test)(const UClass&)) {
    std::erase_if(defaultObjects_, [&](const auto& entry) {
        if (!test(*entry.first))
            return false;
        sp::reflect::ObjectTable::rememberName(*entry.second);
        return true;
    });
}

const UClass* UWorld::load_class(TSubclassOf<UObject> uclass, const std::string& name) {
    const char* function = "UWorld.load_class()";
    SP_CHECK(uclass, sp::InvalidArgument, function, ": uclass is None");
    SP_CHECK(!name.empty(), sp::InvalidArgument, function, ": name is empty");
    const UClass* type = sp::reflect::Registry::get().findType(name);
    if (!type || type->kind != UClass::Kind::Class || name.ends_with(".json"))
        type = &sp::reflect::Registry::get().loadClass(name, function);
    SP_CHECK(type->isChildOf(*uclass.Get()), sp::InvalidArgument, function, ": class '", type->name,
             "' (from '", name, "') does not derive from ", uclass->name);
    return type;
}

bool UWorld::line_trace_single(const FVector& start, const FVector& end, FHitResult& hit, AActor*& actor,
                               UPrimitiveComponent*& component) {
    component = GetSubsystem<sp::world::PhysicsSubsystem>().lineTrace(start, end, hit);
    actor = component ? component->GetOwner() : nullptr;
    return hit.bBlockingHit;
}

void UWorld::inject_input_for_actor(AActor* actor, const std::string& input_action_name,
                                    const FVector& value) {
    SP_CHECK(actor, sp::InvalidArgument, "UWorld.inject_input_for_actor(): actor is None");
    SP_CHECK(!input_action_name.empty(), sp::InvalidArgument,
             "UWorld.inject_input_for_actor(): input_action_name is empty");
    // Refused here rather than in the next tick, where a pawn would fail to move by it.
    SP_CHECK(value.isFinite(), sp::InvalidArgument, "UWorld.inject_input_for_actor(): value (", value.X, ", ",
             value.Y, ", ", value.Z, ") of action '", input_action_name, "' is not finite");
    auto* input = static_cast<UInputComponent*>(actor->GetComponentByClass(&UInputComponent::StaticClass()));
    // A controller has no input of its own here: what a player's input moves is its pawn.
    const std::optional<const AActor*> forwardTo = input ? std::nullopt : actor->GetInputForwardTarget();
    if (forwardTo && *forwardTo)
        input =
            static_cast<UInputComponent*>((*forwardTo)->GetComponentByClass(&UInputComponent::StaticClass()));
    SP_CHECK(input, sp::InvalidArgument, "UWorld.inject_input_for_actor(): ", actor->GetDebugName(),
             forwardTo && !*forwardTo ? " possesses no pawn" : " has no UInputComponent",
             " to receive action '", input_action_name, "'");
    input->InjectAction(input_action_name, value);
}

void UWorld::Tick(double deltaSeconds) {
    if (BeginTick(deltaSeconds))
        StepConcurrently(deltaSeconds);
    EndTick(deltaSeconds);
}

bool UWorld::BeginTick(double deltaSeconds) {
    splitAt_ = nullptr;
    ticking_ = true;
    Stopwatch watch;
    try {
        // Index loop: an actor spawned during the tick is appended and ticks from the next frame.
        const size_t count = actors_.size();
        for (size_t i = 0; i < count; ++i)
            if (std::find(pendingDestroy_.begin(), pendingDestroy_.end(), actors_[i].get()) ==
                pendingDestroy_.end())
                actors_[i]->Tick(deltaSeconds);
    } catch (...) {
        ticking_ = false;
        // What the tick destroyed goes now, as after a tick that completes: left pending, an actor the user
        // destroys before the next tick would be destroyed again from here.
        for (AActor* actor : std::exchange(pendingDestroy_, {}))
            destroy_actor(actor);
        throw;
    }
    ticking_ = false;
    for (AActor* actor : std::exchange(pendingDestroy_, {}))
        destroy_actor(actor);
    timings_.ActorsMs += watch.lap();
    // Index loop: a subsystem may create another one while ticking.
    for (size_t i = 0; i < subsystems_.size(); ++i) {
        sp::world::WorldSubsystem& subsystem = *subsystems_[i].subsystem;
        subsystem.Tick(deltaSeconds);
        if (subsystem.HasConcurrentStep()) {
            splitAt_ = &subsystem;
            splitMs_ = watch.lap();
            return true;
        }
        stageOf(timings_, subsystems_[i].tickOrder) += watch.lap();
    }
    return false;
}

void UWorld::StepConcurrently(double deltaSeconds) {
    SP_CHECK(splitAt_, sp::InvalidState, "UWorld::StepConcurrently(): BeginTick() stopped at no step");
    Stopwatch watch;
    splitAt_->StepConcurrently(deltaSeconds);
    splitMs_ += watch.lap();
}

void UWorld::EndTick(double deltaSeconds) {
    Stopwatch watch;
    size_t next = subsystems_.size(); // BeginTick ticked them all, unless a step split the tick
    if (sp::world::WorldSubsystem* split = std::exchange(splitAt_, nullptr)) {
        next = 0;
        while (next < subsystems_.size() && subsystems_[next].subsystem.get() != split)
            ++next;
        SP_CHECK(next < subsystems_.size(), sp::InvalidState,
                 "UWorld::EndTick(): the subsystem whose step split the tick is gone");
        split->FinishTick(deltaSeconds);
        stageOf(timings_, subsystems_[next].tickOrder) += splitMs_ + watch.lap();
        ++next;
    }
    for (size_t i = next; i < subsystems_.size(); ++i) {
        sp::world::WorldSubsystem& subsystem = *subsystems_[i].subsystem;
        subsystem.Tick(deltaSeconds);
        if (subsystem.HasConcurrentStep()) { // only the first one's step runs with other worlds'
            subsystem.StepConcurrently(deltaSeconds);
            subsystem.FinishTick(deltaSeconds);
        }
        stageOf(timings_, subsystems_[i].tickOrder) += watch.lap();
    }
    timeSeconds_ += deltaSeconds;
    ++frameCount_;
    ++timings_.Frames;
    if (host_ == nullptr)
        NotifyWorldsTicked();
}

void UWorld::NotifyWorldsTicked() {
    Stopwatch watch;
    for (size_t i = 0; i < subsystems_.size(); ++i) {
        subsystems_[i].subsystem->OnWorldsTicked();
        stageOf(timings_, subsystems_[i].tickOrder) += watch.lap();
    }
}
