#include <gtest/gtest.h>

#include <cmath>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/world/static_mesh_actor.h"

namespace {
struct WorldTest : ::testing::Test {
    sp::engine::Engine engine;
    UWorld& world = engine.GetGameWorld();
};

void expectNear(const FVector& a, const FVector& b, double tol = 1e-9) {
    EXPECT_NEAR(a.X, b.X, tol);
    EXPECT_NEAR(a.Y, b.Y, tol);
    EXPECT_NEAR(a.Z, b.Z, tol);
}
} // namespace

TEST_F(WorldTest, SpawnNamesAreUniqueAndQueriesFollowTheHierarchy) {
    AActor* a = world.spawn_actor(&AActor::StaticClass());
    AActor* m = world.spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "", {"tag"});
    EXPECT_EQ(a->GetName(), "Actor_0");
    EXPECT_EQ(m->GetName(), "StaticMeshActor_0");
    EXPECT_EQ(world.find_actors_by_class(&AActor::StaticClass()).size(), 2u);
    EXPECT_EQ(world.find_actors_by_class(&AStaticMeshActor::StaticClass()), std::vector<AActor*>{m});
    EXPECT_EQ(world.find_actors_by_tag("tag"), std::vector<AActor*>{m});
    EXPECT_THROW(world.spawn_actor(&AActor::StaticClass(), {}, {}, "Actor_0"), sp::InvalidArgument);
    EXPECT_THROW(world.spawn_actor(&UObject::StaticClass()), sp::InvalidArgument); // TSubclassOf check
}

TEST_F(WorldTest, DestroyInvalidatesActorAndComponentHandles) {
    auto* m = static_cast<AStaticMeshActor*>(world.spawn_actor(&AStaticMeshActor::StaticClass()));
    auto actorHandle = m->GetHandle();
    auto componentHandle = m->StaticMeshComponent->GetHandle();
    world.destroy_actor(m);
    EXPECT_EQ(sp::reflect::ObjectTable::find(actorHandle), nullptr);
    EXPECT_EQ(sp::reflect::ObjectTable::find(componentHandle), nullptr);
    EXPECT_EQ(world.get_actor_count(), 0);
}

TEST_F(WorldTest, RotatorMatchesTheDocumentedConvention) {
    FRotator yaw{0, 90, 0};
    Eigen::Vector3d x = yaw.toQuaternion() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(x.y(), 1.0, 1e-12); // Yaw turns X toward Y
    FRotator pitch{30, 0, 0};
    x = pitch.toQuaternion() * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(x.z(), 0.5, 1e-12); // Pitch raises X toward Z
    FRotator any{10, 20, 30};
    FRotator back = FRotator::fromQuaternion(any.toQuaternion());
    EXPECT_NEAR(back.Pitch, 10, 1e-9);
    EXPECT_NEAR(back.Yaw, 20, 1e-9);
    EXPECT_NEAR(back.Roll, 30, 1e-9);
}

TEST_F(WorldTest, AttachmentComposesTransforms) {
    AActor* parent = world.spawn_actor(&AStaticMeshActor::StaticClass(), {1, 0, 0}, {0, 90, 0});
    AActor* child = world.spawn_actor(&AStaticMeshActor::StaticClass());
    child->RootComponent->AttachToComponent(parent->RootComponent, false);
    child->RootComponent->SetRelativeLocation({1, 0, 0});
    expectNear(child->GetActorLocation(), {1, 1, 0}); // rotated by the parent's yaw
    parent->SetActorScale3D({2, 2, 2});
    expectNear(child->GetActorLocation(), {1, 2, 0});
    child->RootComponent->DetachFromComponent(true);
    expectNear(child->GetActorLocation(), {1, 2, 0});
}

TEST_F(WorldTest, ActorsDestroyedDuringATickGoAwayAfterIt) {
    AActor* a = world.spawn_actor(&AActor::StaticClass());
    engine.beginFrame();
    engine.executeFrame();
    world.destroy_actor(a);
    EXPECT_EQ(world.get_actor_count(), 0);
}

namespace {
// A subsystem that writes down what the world tells it: "+Actor", "+Actor.Component", "-...".
struct Recorder : sp::world::WorldSubsystem {
    static constexpr int kTickOrder = 1000;
    explicit Recorder(UWorld&) {}
    std::vector<std::string> events;
    void OnActorBeginPlay(AActor& actor) override { events.push_back("+" + actor.GetName()); }
    void OnActorEndPlay(AActor& actor) override { events.push_back("-" + actor.GetName()); }
    void OnComponentBeginPlay(UActorComponent& component) override {
        events.push_back("+" + component.GetOwner()->GetName() + "." + component.GetName());
    }
    void OnComponentEndPlay(UActorComponent& component) override {
        events.push_back("-" + component.GetOwner()->GetName() + "." + component.GetName());
    }
};
} // namespace

TEST_F(WorldTest, SubsystemsMirrorTheWorldByRegistration) {
    world.spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "A");
    // Made late: told first of what already plays, in the world's order.
    Recorder& recorder = world.GetSubsystem<Recorder>();
    EXPECT_EQ(recorder.events, (std::vector<std::string>{"+A", "+A.StaticMeshComponent"}));

    recorder.events.clear();
    AActor* b = world.spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "B");
    UActorComponent* extra = b->CreateComponent(UStaticMeshComponent::StaticClass(), "Extra");
    b->DestroyComponent(extra);
    world.destroy_actor(b);
    EXPECT_EQ(recorder.events, (std::vector<std::string>{"+B", "+B.StaticMeshComponent", "+B.Extra",
                                                         "-B.Extra", "-B.StaticMeshComponent", "-B"}));
}

namespace {
// Makes a Recorder while an actor ends play.
struct MakesRecorderOnEnd : sp::world::WorldSubsystem {
    static constexpr int kTickOrder = 900;
    explicit MakesRecorderOnEnd(UWorld& world) : world_(world) {}
    void OnActorEndPlay(AActor&) override { world_.GetSubsystem<Recorder>(); }
    UWorld& world_;
};

// Refuses every component (as physics refuses settings Bullet cannot take).
struct Refuses : sp::world::WorldSubsystem {
    static constexpr int kTickOrder = 900;
    explicit Refuses(UWorld&) {}
    void OnComponentBeginPlay(UActorComponent& component) override {
        SP_THROW(sp::InvalidArgument, "refused ", component.GetName());
    }
};
} // namespace

TEST_F(WorldTest, ASubsystemMadeDuringAnEndNoticeIsNotToldOfTheEndingActor) {
    AActor* a = world.spawn_actor(&AActor::StaticClass(), {}, {}, "A");
    world.spawn_actor(&AActor::StaticClass(), {}, {}, "B");
    world.GetSubsystem<MakesRecorderOnEnd>();
    world.destroy_actor(a);
    const Recorder* recorder = world.FindSubsystem<Recorder>();
    ASSERT_NE(recorder, nullptr);
    EXPECT_EQ(recorder->events, std::vector<std::string>{"+B"});
}

TEST_F(WorldTest, EverySubsystemHearsANoticeOneOfThemRefuses) {
    Recorder& recorder = world.GetSubsystem<Recorder>();
    world.GetSubsystem<Refuses>(); // told first (lower tick order)
    EXPECT_THROW(world.spawn_actor(&AStaticMeshActor::StaticClass(), {}, {}, "M"), sp::InvalidArgument);
    EXPECT_EQ(recorder.events, (std::vector<std::string>{"+M", "+M.StaticMeshComponent"}));
}
