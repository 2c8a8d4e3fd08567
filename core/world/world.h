#pragma once
// UWorld: owns the actors of one world and offers SPEAR's world services (spawn, destroy, find by name,
// tag or class, components by name or class). Service functions keep SPEAR's snake_case names and, like
// every reflected function, take keyword arguments in Python.

#include <exception>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <typeindex>

#include "core/reflect/class_ref.h"
#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "core/world/frame_timings.h"
#include "core/world/hit_result.h"
#include "core/world/primitive_component.h"
#include "core/world/world_host.h"
#include "core/world/world_subsystem.h"

/// A world: the actors that exist together, and the services to create and find them.
SPCLASS()
class UWorld : public UObject {
    SP_GENERATED_BODY()
  public:
    UWorld();
    ~UWorld() override;

    /// Spawns an actor of class uclass at location and rotation; name must be unique in the world (empty:
    /// generated).
    SPFUNCTION(DeterminesOutputType = uclass, NotNull)
    AActor* spawn_actor(TSubclassOf<AActor> uclass, const FVector& location = FVector(),
                        const FRotator& rotation = FRotator(), const std::string& name = "",
                        const std::vector<std::string>& tags = {});

    /// Destroys actor and its components; its handles become invalid.
    SPFUNCTION()
    void destroy_actor(AActor* actor);

    /// Returns the actor called name, or None.
    SPFUNCTION()
    AActor* find_actor_by_name(const std::string& name) const;

    /// Returns every actor that has tag, in spawn order.
    SPFUNCTION()
    std::vector<AActor*> find_actors_by_tag(const std::string& tag) const;

    /// Returns the first actor of class uclass or a subclass of it, or None.
    SPFUNCTION(DeterminesOutputType = uclass)
    AActor* find_actor_by_class(TSubclassOf<AActor> uclass) const;

    /// Returns every actor of class uclass or a subclass of it, in spawn order.
    SPFUNCTION(DeterminesOutputType = uclass)
    std::vector<AActor*> find_actors_by_class(TSubclassOf<AActor> uclass) const;

    /// Returns every actor of class uclass or a subclass of it, by name.
    SPFUNCTION(DeterminesOutputType = uclass)
    std::map<std::string, AActor*> find_actors_by_class_as_dict(TSubclassOf<AActor> uclass) const;

    /// Returns every actor in the world, in spawn order.
    SPFUNCTION()
    std::vector<AActor*> find_actors() const;

    /// Returns the component of actor called component_name, or None.
    SPFUNCTION()
    UActorComponent* get_component_by_name(AActor* actor, const std::string& component_name) const;

    /// Returns the components of actor of class uclass or a subclass of it.
    SPFUNCTION(DeterminesOutputType = uclass)
    std::vector<UActorComponent*> get_components_by_class(AActor* actor,
                                                          TSubclassOf<UActorComponent> uclass) const;

    /// Returns the components of actor of class uclass or a subclass of it, by name.
    SPFUNCTION(DeterminesOutputType = uclass)
    std::map<std::string, UActorComponent*>
    get_components_by_class_as_dict(AActor* actor, TSubclassOf<UActorComponent> uclass) const;

    /// Loads the blueprint asset at path name (a JSON file, see core/scene/blueprint.h) once and returns its
    /// class, named after the file ("BP_Axes"), which must derive from uclass; name may also name a class.
    SPFUNCTION(DeterminesOutputType = uclass, NotNull)
    const UClass* load_class(TSubclassOf<UObject> uclass, const std::string& name);

    /// Returns the class default object of uclass: an instance outside the world holding the class defaults.
    SPFUNCTION(DeterminesOutputType = uclass, NotNull)
    UObject* get_default_object(TSubclassOf<UObject> uclass);

    // Destroys the default objects of the classes `test` accepts (a plugin's, before it is unloaded).
    void ReleaseDefaultObjects(bool (*test)(const UClass&));

    /// Returns the world-space locations of actors as an (N, 3) float64 array, rows in the order given. The
    /// actors may be in any of the engine's worlds: one actor per world gives a leading world axis.
    SPFUNCTION()
    sp::reflect::SpArray<double> get_actor_locations(const std::vector<AActor*>& actors) const;

    /// Moves each actor to the matching row of locations, an (N, 3) float64 array (one call for many actors,
    /// in any of the engine's worlds).
    SPFUNCTION()
    void set_actor_locations(const std::vector<AActor*>& actors,
                             const sp::reflect::SpArray<double>& locations);

    /// Pushes each component with the matching row of forces, an (N, 3) float64 array in newtons in the world
    /// frame, for this frame, as AddForce does one component at a time (bAccelChange: the rows are
    /// accelerations, scaled by each component's mass). The components may be in any of the engine's worlds.
    /// All or none: a component that cannot take a force (None, not in play, not simulating physics) is an
    /// error naming its index, and no force is applied.
    SPFUNCTION()
    void add_forces(const std::vector<UPrimitiveComponent*>& components,
                    const sp::reflect::SpArray<double>& forces, bool bAccelChange = false);

    /// Returns the number of actors in the world.
    SPFUNCTION()
    int get_actor_count() const { return int(actors_.size()); }

    /// Returns the simulated time of this world in seconds.
    SPFUNCTION()
    double get_time_seconds() const { return timeSeconds_; }

    /// Returns the number of frames this world has ticked.
    SPFUNCTION()
    int64_t get_frame_count() const { return frameCount_; }

    /// Returns the CPU time this world's frames took by stage (actors, physics, rendering, the rest), summed
    /// since it began: subtract two readings for a span of frames.
    SPFUNCTION()
    FFrameTimings get_frame_timings() const { return timings_; }

    /// Traces the segment start -> end against every collision body; returns true on a hit, with the hit,
    /// and the actor and component that were hit (None when nothing was hit).
    SPFUNCTION()
    bool line_trace_single(const FVector& start, const FVector& end, FHitResult& hit, AActor*& actor,
                           UPrimitiveComponent*& component);

    /// Routes a continuous input action with the given value to actor's UInputComponent for the next tick.
    SPFUNCTION()
    void inject_input_for_actor(AActor* actor, const std::string& input_action_name, const FVector& value);

    /// Replaces every actor of this world by those of the scene file at path (see core/scene/scene_io.h).
    SPFUNCTION()
    void load_scene(const std::string& path);

    /// Writes every actor and component of this world, with every reflected property, to a scene file.
    SPFUNCTION()
    void save_scene(const std::string& path) const;

    /// Returns true for the persistent world of an editor instance.
    SPFUNCTION()
    bool is_editor_world() const { return isEditorWorld_; }

    /// Returns true for a world that plays (a standalone instance's world, or the editor's play world).
    SPFUNCTION()
    bool is_game_world() const { return !isEditorWorld_; }

    /// Editor world only: starts play in a new game world copied from this one (instance.get_game()).
    SPFUNCTION()
    void play();

    /// Editor world only: ends play and destroys the game world; its objects' handles become stale.
    SPFUNCTION()
    void stop();

    /// Editor world only: returns true while a game world copied from this one is playing.
    SPFUNCTION()
    bool is_playing() const;

    // Advances every actor by one fixed step, then the subsystems; a world without a host then tells them
    // that the frame's worlds ticked (WorldSubsystem::OnWorldsTicked), as the host does after all its worlds.
    void Tick(double deltaSeconds);
    // The same in three parts, for a host stepping several worlds' physics at once: BeginTick() ticks the
    // actors and the subsystems up to the one with a concurrent step (WorldSubsystem::HasConcurrentStep),
    // its Tick() included, and returns whether it stopped there; StepConcurrently() runs that step (touching
    // only this world, so worlds may run it on several threads at once); EndTick() finishes that subsystem
    // and ticks the rest. After a part throws, the frame of this world is over (the later parts are not run).
    bool BeginTick(double deltaSeconds);
    void StepConcurrently(double deltaSeconds);
    void EndTick(double deltaSeconds);
    void NotifyWorldsTicked();

    // The world's subsystem of type T (constructed as T(UWorld&) on first use).
    template <typename T> T& GetSubsystem() {
        for (const auto& entry : subsystems_)
            if (entry.type == std::type_index(typeid(T)))
                return static_cast<T&>(*entry.subsystem);
        auto subsystem = std::make_unique<T>(*this);
        T& raw = *subsystem;
        addSubsystem(std::type_index(typeid(T)), T::kTickOrder, std::move(subsystem));
        return raw;
    }
    template <typename T> T* FindSubsystem() const {
        for (const auto& entry : subsystems_)
            if (entry.type == std::type_index(typeid(T)))
                return static_cast<T*>(entry.subsystem.get());
        return nullptr;
    }

    // Creates an actor that belongs to this world but is not in it yet (no BeginPlay, not found by queries);
    // ReplaceActors puts it in. Used to build a whole scene before the world changes.
    std::unique_ptr<AActor> NewActorDeferred(const UClass& type, std::string name);
    // Destroys every actor, then adds `actors` (from NewActorDeferred) in order and begins their play.
    void ReplaceActors(std::vector<std::unique_ptr<AActor>> actors);
    // Adds `actors` (from NewActorDeferred) after the others once every one has begun play; when one
    // fails to, none is added.
    void AddActors(std::vector<std::unique_ptr<AActor>> actors);

    // Streaming levels: sub-scenes that a scene file declares (its "levels" list) and that
    // UGameplayStatics.LoadStreamLevel / UnloadStreamLevel add to and remove from the world in play.
    struct StreamingLevel {
        std::string name;
        std::string declaredPath; // as the scene file wrote it
        std::string path;         // the file read: declaredPath from the scene file's folder
        bool loaded = false;
        bool operator==(const StreamingLevel&) const = default;
    };
    // What loads and unloads them reads scene files: sp::scene::loadStreamLevel
    // (core/scene/streaming_levels.h).
    const std::vector<StreamingLevel>& GetStreamingLevels() const { return levels_; }
    std::vector<StreamingLevel>& GetStreamingLevels() { return levels_; }
    void SetStreamingLevels(std::vector<StreamingLevel> levels) { levels_ = std::move(levels); }

    void SetEditorWorld(bool isEditorWorld) { isEditorWorld_ = isEditorWorld; }
    // Called by actors as they and their components begin and end play; tells every subsystem (see
    // sp::world::WorldSubsystem::OnActorBeginPlay).
    void NotifyActorBeginPlay(AActor& actor);
    void NotifyActorEndPlay(AActor& actor);
    void NotifyComponentBeginPlay(UActorComponent& component);
    void NotifyComponentEndPlay(UActorComponent& component);

    // The engine that owns this world; null for a world made on its own (tests).
    void SetHost(sp::world::WorldHost* host) { host_ = host; }
    sp::world::WorldHost* GetHost() const { return host_; }

  private:
    struct SubsystemEntry {
        std::type_index type;
        int tickOrder;
        std::unique_ptr<sp::world::WorldSubsystem> subsystem;
    };
    void addSubsystem(std::type_index type, int tickOrder,
                      std::unique_ptr<sp::world::WorldSubsystem> subsystem);
    // Calls `notify` on each subsystem there is now (one made meanwhile was told of the world when made).
    // Every subsystem hears it even when one throws; the first error is rethrown after.
    template <typename Notify> void notifySubsystems(const Notify& notify) const {
        std::vector<sp::world::WorldSubsystem*> current;
        current.reserve(subsystems_.size());
        for (const auto& entry : subsystems_)
            current.push_back(entry.subsystem.get());
        std::exception_ptr first;
        for (sp::world::WorldSubsystem* subsystem : current) {
            try {
                notify(*subsystem);
            } catch (...) {
                if (!first)
                    first = std::current_exception();
            }
        }
        if (first)
            std::rethrow_exception(first);
    }
    std::string uniqueActorName(const UClass& type) const;
    sp::world::WorldHost& editorHost(const char* function) const;
    sp::world::WorldHost& assetHost(const char* function) const;

    std::vector<SubsystemEntry> subsystems_; // sorted by tick order; destroyed after the actors

    sp::world::WorldHost* host_ = nullptr;
    std::vector<std::unique_ptr<AActor>> actors_; // spawn order: keeps queries and ticks deterministic
    // Actors beginning play before they join actors_ (ReplaceActors, AddActors; set until they have joined,
    // an outer batch's restored after a nested one): a subsystem made meanwhile is told of those that began,
    // after actors_.
    const std::vector<std::unique_ptr<AActor>>* incoming_ = nullptr;
    std::vector<StreamingLevel> levels_; // declaration order
    std::map<const UClass*, std::unique_ptr<UObject>> defaultObjects_;
    mutable std::map<std::string, int> nameCounters_; // per name prefix; never reused
    double timeSeconds_ = 0.0;
    int64_t frameCount_ = 0;
    FFrameTimings timings_;
    // BeginTick -> EndTick: the subsystem whose concurrent step split the tick, and the time spent so far in
    // it.
    sp::world::WorldSubsystem* splitAt_ = nullptr;
    double splitMs_ = 0.0;
    bool ticking_ = false;
    bool isEditorWorld_ = false;
    std::vector<AActor*> pendingDestroy_;
};
