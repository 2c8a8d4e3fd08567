#pragma once
// AActor: an object placed in a world, made of components. Its transform is its root component's.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/reflect/class_ref.h"
#include "core/world/actor_component.h"
#include "core/world/scene_component.h"

/// An object that can be placed in a world.
SPCLASS()
class AActor : public UObject {
    SP_GENERATED_BODY()
  public:
    AActor();
    ~AActor() override;

    /// Tags for finding this actor.
    SPPROPERTY()
    std::vector<std::string> Tags;

    /// The component that defines the actor's transform.
    SPPROPERTY(ReadOnly)
    USceneComponent* RootComponent = nullptr;

    /// Makes NewRootComponent (one of this actor's components) the root.
    SPFUNCTION()
    void SetRootComponent(USceneComponent* NewRootComponent);

    /// Returns the world-space location of the root component.
    SPFUNCTION()
    FVector GetActorLocation() const;

    /// Moves the actor; returns true when it moved.
    SPFUNCTION()
    bool SetActorLocation(const FVector& NewLocation);

    /// Returns the world-space rotation of the root component.
    SPFUNCTION()
    FRotator GetActorRotation() const;

    /// Rotates the actor; returns true when it rotated.
    SPFUNCTION()
    bool SetActorRotation(const FRotator& NewRotation);

    /// Moves and rotates the actor (bSweep is accepted for UE compatibility; sweeps are not supported).
    SPFUNCTION()
    bool K2_SetActorLocationAndRotation(const FVector& NewLocation, const FRotator& NewRotation,
                                        bool bSweep = false, bool bTeleport = true);

    /// Returns the world-space scale of the root component.
    SPFUNCTION()
    FVector GetActorScale3D() const;

    /// Sets the world-space scale of the root component.
    SPFUNCTION()
    void SetActorScale3D(const FVector& NewScale3D);

    /// Returns the world-space transform of the root component.
    SPFUNCTION()
    FTransform GetActorTransform() const;

    /// Sets the world-space transform of the root component.
    SPFUNCTION()
    bool SetActorTransform(const FTransform& NewTransform);

    /// Returns the unit vector along the actor's X axis.
    SPFUNCTION()
    FVector GetActorForwardVector() const;

    /// Returns the world-space bounds of the actor's primitives as centre Origin and half size BoxExtent.
    SPFUNCTION()
    void GetActorBounds(bool bOnlyCollidingComponents, FVector& Origin, FVector& BoxExtent) const;

    /// Returns true when Tags contains Tag.
    SPFUNCTION()
    bool ActorHasTag(const std::string& Tag) const;

    /// Returns the other actors (of class ClassFilter or a subclass) that overlap any of this actor's
    /// components now (see UPrimitiveComponent.GetOverlappingComponents).
    SPFUNCTION(DeterminesOutputType = ClassFilter)
    std::vector<AActor*> GetOverlappingActors(TSubclassOf<AActor> ClassFilter) const;

    /// Returns true when a component of Other overlaps a component of this actor now.
    SPFUNCTION()
    bool IsOverlappingActor(const AActor* Other) const;

    /// Returns the name of the streaming level that loaded this actor ("" for the persistent level).
    SPFUNCTION()
    std::string GetStreamingLevelName() const { return streamingLevel_; }

    /// Returns all components of this actor, in creation order.
    SPFUNCTION()
    std::vector<UActorComponent*> K2_GetComponents() const;

    /// Returns the first component of class ComponentClass (or a subclass), or None.
    SPFUNCTION(DeterminesOutputType = ComponentClass)
    UActorComponent* GetComponentByClass(TSubclassOf<UActorComponent> ComponentClass) const;

    /// Adds a component of class ComponentClass to this actor at run time (UE's AddComponentByClass): a
    /// camera on a spawned robot, a light on a car. Name "" names it after its class
    /// ("CameraSensorComponent", then "CameraSensorComponent_1", ...). A scene component is attached to the
    /// component called AttachParent ("" for the root; the root itself when the actor has none) at
    /// RelativeTransform. It begins play at once when the actor has. Returns it, typed as ComponentClass;
    /// raises InvalidArgumentError for a class that is not a component one or cannot be created, a Name taken
    /// or an AttachParent that is not one of this actor's scene components.
    SPFUNCTION(DeterminesOutputType = ComponentClass)
    UActorComponent* AddComponentByClass(TSubclassOf<UActorComponent> ComponentClass,
                                         const FTransform& RelativeTransform = FTransform(),
                                         const std::string& Name = "", const std::string& AttachParent = "");

    /// Destroys one of this actor's components (UE's K2_DestroyComponent); its handle is refused afterwards.
    /// The root component cannot be destroyed while the actor lives.
    SPFUNCTION()
    void K2_DestroyComponent(UActorComponent* Component);

    // Creates a component owned by this actor. The first scene component becomes the root; later ones
    // are attached to the root. Use in constructors (like UE's CreateDefaultSubobject) or at run time.
    template <typename T> T* CreateDefaultSubobject(std::string name) {
        static_assert(std::is_base_of_v<UActorComponent, T>);
        auto component = std::make_unique<T>();
        T* raw = component.get();
        adoptComponent(std::move(component), std::move(name), "AActor.CreateComponent()");
        return raw;
    }
    // `function` names the caller in errors (a class that is no creatable component, a name taken).
    UActorComponent* CreateComponent(const UClass& type, std::string name,
                                     std::string_view function = "AActor.CreateComponent()");
    void DestroyComponent(UActorComponent* component);
    const std::vector<std::unique_ptr<UActorComponent>>& GetComponentList() const { return components_; }
    // The component called `name`, or null.
    UActorComponent* FindComponentByName(std::string_view name) const;

    // Engine hooks.
    virtual void BeginPlay();
    virtual void Tick(double deltaSeconds);
    virtual void EndPlay();
    // Just before and just after every physics step, for actors registered with sp::world::PhysicsHooks.
    virtual void PrePhysicsTick() {}
    virtual void PostPhysicsTick() {}
    // Where input injected into this actor goes when it has no UInputComponent of its own
    // (UWorld.inject_input_for_actor): nullopt for nowhere; a controller names the pawn it possesses, null
    // when it possesses none. Virtual because the gameplay framework sits above this library.
    virtual std::optional<const AActor*> GetInputForwardTarget() const { return std::nullopt; }
    bool HasBegunPlay() const { return begunPlay_; }
    void SetWorldForComponents();
    // Set by UWorld when a streaming level loads the actor.
    void SetStreamingLevelName(std::string level) { streamingLevel_ = std::move(level); }
    // Names the streaming level too, so that a handle into an unloaded level says where it came from.
    std::string GetDebugName() const override;

  private:
    void adoptComponent(std::unique_ptr<UActorComponent> component, std::string name,
                        std::string_view function);
    // A component's BeginPlay()/EndPlay(), and the world's subsystems told of it.
    void beginComponentPlay(UActorComponent& component);
    void endComponentPlay(UActorComponent& component);

    std::vector<std::unique_ptr<UActorComponent>> components_;
    bool begunPlay_ = false;
    std::string streamingLevel_;
};
