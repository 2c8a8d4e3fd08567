#include "core/engine/engine.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/parallel.h"
#include "core/base/regular_file.h"
#include "core/scene/scene_io.h"
#include "core/scene/streaming_levels.h"

namespace sp::engine {

namespace {

// SPEAR_PHYSICS_THREADS, a whole number >= 1, or half the hardware threads when it is not set: the rest stay
// for the GL driver's threads (all of a software rasteriser's, which the steps would otherwise preempt: on 2
// cores under llvmpipe, 16 worlds stepped on both lost a tenth of their throughput).
int physicsThreadsFromEnvironment() {
    const char* env = std::getenv("SPEAR_PHYSICS_THREADS");
    if (env == nullptr)
        return std::max(1, hardwareThreads() / 2);
    const std::string value = env;
    int threads = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), threads);
    SP_CHECK(error == std::errc() && end == value.data() + value.size() && threads >= 1, InvalidArgument,
             "Engine(): SPEAR_PHYSICS_THREADS must be a whole number >= 1, got '", value, "'");
    return threads;
}

} // namespace

Engine::Engine() : Engine(Settings{}) {}

Engine::Engine(Settings settings) : settings_(settings) {
    SP_CHECK(settings_.fixedDeltaSeconds > 0.0, InvalidArgument,
             "Engine(): fixedDeltaSeconds must be > 0, got ", settings_.fixedDeltaSeconds);
    SP_CHECK(settings_.physicsThreads >= 0, InvalidArgument, "Engine(): physicsThreads must be >= 0, got ",
             settings_.physicsThreads);
    if (settings_.physicsThreads == 0)
        settings_.physicsThreads = physicsThreadsFromEnvironment();
    registerEngineTypes();
    if (settings_.editor) {
        editorWorld_ = std::make_unique<UWorld>();
        editorWorld_->InitObject("EditorWorld", editorWorld_.get());
        editorWorld_->SetEditorWorld(true);
        editorWorld_->SetHost(this);
    } else {
        gameWorld_ = std::make_unique<UWorld>();
        gameWorld_->SetHost(this);
    }
    if (!settings_.scene.empty())
        (editorWorld_ ? *editorWorld_ : *gameWorld_).load_scene(settings_.scene);
}

UWorld& Engine::GetGameWorld() {
    SP_CHECK(
        gameWorld_, InvalidState,
        "get_game(): the editor is not playing; call play() on instance.get_editor() inside a frame first");
    return *gameWorld_;
}

void Engine::play() {
    SP_CHECK(editorWorld_, InvalidState,
             "UWorld.play(): this engine runs standalone and has no editor world");
    SP_CHECK(!gameWorld_, InvalidState, "UWorld.play(): the editor is already playing; call stop() first");
    for (const auto& world : createdWorlds_)
        SP_CHECK(world->GetName() != "GameWorld", InvalidState,
                 "UWorld.play(): a world create_world() made is "
                 "named 'GameWorld', the name of the world play() makes; destroy it first");
    auto game = std::make_unique<UWorld>();
    game->InitObject("GameWorld", game.get());
    game->SetHost(this);
    // The copy goes through the same reflection code as scene files, so play starts from exactly what
    // save_scene would write.
    // Streaming levels keep the files the editor world resolved (a relative path in the scene means its
    // folder, which the copy does not know), and those loaded in the editor are loaded in play.
    const std::string context = "UWorld.play(): copying the editor world";
    scene::SceneJson scene = scene::saveScene(*editorWorld_);
    scene.erase("levels");
    scene::loadScene(*game, scene, context, "");
    std::vector<UWorld::StreamingLevel> levels = editorWorld_->GetStreamingLevels();
    for (UWorld::StreamingLevel& level : levels)
        level.loaded = false;
    game->SetStreamingLevels(std::move(levels));
    for (const UWorld::StreamingLevel& level : editorWorld_->GetStreamingLevels())
        if (level.loaded)
            sp::scene::loadStreamLevel(*game, level.name, context);
    gameWorld_ = std::move(game);
}

UWorld& Engine::CreateWorld(const std::string& name) {
    SP_CHECK(!name.empty(), InvalidArgument, "create_world(): name must not be empty");
    bool exists = editorWorld_ && editorWorld_->GetName() == name;
    for (const UWorld* world : GetWorlds())
        exists = exists || world->GetName() == name;
    SP_CHECK(!exists, InvalidArgument, "create_world(): a world named '", name, "' exists already");
    auto world = std::make_unique<UWorld>();
    world->InitObject(name, world.get());
    world->SetHost(this);
    createdWorlds_.push_back(std::move(world));
    return *createdWorlds_.back();
}

void Engine::DestroyWorld(UWorld& world) {
    SP_CHECK(
        !ticking_, InvalidState, "destroy_world(): '", world.GetName(),
        "' cannot be destroyed while the worlds tick; destroy it inside a frame block or between frames");
    for (auto it = createdWorlds_.begin(); it != createdWorlds_.end(); ++it) {
        if (it->get() == &world) {
            createdWorlds_.erase(it);
            return;
        }
    }
    SP_THROW(InvalidArgument, "destroy_world(): '", world.GetName(),
             "' is not a world create_world() made; the game and editor worlds live as long as the engine");
}

std::vector<UWorld*> Engine::GetWorlds() const {
    std::vector<UWorld*> worlds;
    if (gameWorld_)
        worlds.push_back(gameWorld_.get());
    for (const auto& world : createdWorlds_)
        worlds.push_back(world.get());
    return worlds;
}

void Engine::stop() {
    SP_CHECK(editorWorld_, InvalidState,
             "UWorld.stop(): this engine runs standalone and has no editor world");
    SP_CHECK(gameWorld_, InvalidState, "UWorld.stop(): the editor is not playing");
    gameWorld_.reset();
}

Engine::~Engine() = default;

std::string_view Engine::toString(FrameState state) {
    switch (state) {
    case FrameState::Idle:
        return "idle";
    case FrameState::BeginFrame:
        return "inside begin_frame";
    case FrameState::FrameExecuted:
        return "between begin_frame and end_frame";
    case FrameState::EndFrame:
        return "inside end_frame";
    }
    return "unknown";
}

void Engine::expectState(FrameState expected, std::string_view function) const {
    SP_CHECK(state_ == expected, InvalidState, function, ": the engine is ", toString(state_), ", expected ",
             toString(expected));
}

void Engine::beginFrame() {
    SP_CHECK(state_ != FrameState::FrameExecuted, InvalidState,
             "begin_frame(): the previous frame has not been closed; use 'with instance.end_frame():' first");
    expectState(FrameState::Idle, "begin_frame()");
    state_ = FrameState::BeginFrame;
}

void Engine::executeFrame() {
    expectState(FrameState::BeginFrame, "execute_frame()");
    state_ = FrameState::FrameExecuted;
    ++frameCount_;
    // Every world ticks even when one throws, so that a failing environment does not stall the rest: the
    // first error propagates after the others ran, and any further ones are logged. (An editor that is not
    // playing has only the worlds create_world() made.)
    std::exception_ptr failure;
    ticking_ = true;
    const auto each = [&](UWorld* world, auto&& step) {
        try {
            step(world);
        } catch (const std::exception& e) {
            if (failure)
                SP_LOG("execute_frame(): world '", world->GetName(), "' also failed: ", e.what());
            else
                failure = std::current_exception();
        } catch (...) {
            if (!failure)
                failure = std::current_exception();
        }
    };
    const std::vector<UWorld*> worlds = GetWorlds();
    const double dt = settings_.fixedDeltaSeconds;
    if (worlds.size() > 1 && settings_.physicsThreads > 1) {
        // Each world up to its physics step; the steps at once (a world's step touches only its own bodies);
        // then each world's remaining tick. A world whose part failed is done for this frame.
        std::vector<char> begun(worlds.size(), 0);
        std::vector<size_t> steps;
        for (size_t i = 0; i < worlds.size(); ++i)
            each(worlds[i], [&](UWorld* w) {
                if (w->BeginTick(dt))
                    steps.push_back(i);
                begun[i] = 1;
            });
        std::vector<std::exception_ptr> stepFailures(worlds.size());
        parallelFor(int(steps.size()), settings_.physicsThreads, [&](int k) {
            try {
                worlds[steps[size_t(k)]]->StepConcurrently(dt);
            } catch (...) {
                stepFailures[steps[size_t(k)]] = std::current_exception();
            }
        });
        for (size_t i = 0; i < worlds.size(); ++i)
            if (begun[i])
                each(worlds[i], [&](UWorld* w) {
                    if (stepFailures[i])
                        std::rethrow_exception(stepFailures[i]);
                    w->EndTick(dt);
                });
    } else {
        for (UWorld* world : worlds)
            each(world, [&](UWorld* w) { w->Tick(dt); });
    }
    // Then what is done for all worlds at once (one render batch of every world's cameras, say).
    for (UWorld* world : worlds)
        each(world, [](UWorld* w) { w->NotifyWorldsTicked(); });
    ticking_ = false;
    if (failure)
        std::rethrow_exception(failure);
}

void Engine::beginEndFrame() {
    SP_CHECK(state_ != FrameState::Idle, InvalidState,
             "end_frame(): no frame has run; use 'with instance.begin_frame():' first");
    expectState(FrameState::FrameExecuted, "end_frame()");
    state_ = FrameState::EndFrame;
}

void Engine::endFrame() {
    expectState(FrameState::EndFrame, "end_frame()");
    state_ = FrameState::Idle;
}

void Engine::abortFrame() {
    if (state_ == FrameState::BeginFrame) {
        try {
            executeFrame();
        } catch (...) {
            // The frame is over either way; the user's original error is what gets reported.
        }
    }
    state_ = FrameState::Idle;
}

void Engine::loadScene(UWorld& world, const std::string& path, const std::string& function) {
    // Its streaming levels and meshes are relative to the file the name resolved to (core/base/asset_path.h),
    // which may be in an asset folder rather than the working directory.
    scene::loadScene(world, scene::readSceneFile(path, function), function + ": scene '" + path + "'",
                     scene::sceneFolder(path));
}

void Engine::saveScene(const UWorld& world, const std::string& path, const std::string& function) {
    const std::string text = scene::sceneToString(scene::saveScene(world));
    writeRegularFile(path, text, function, "scene file"); // never a FIFO or a device
}

std::shared_ptr<void> Engine::shared(std::string_view key,
                                     const std::function<std::shared_ptr<void>()>& make) {
    auto it = shared_.find(key);
    if (it == shared_.end())
        it = shared_.emplace(std::string(key), std::weak_ptr<void>()).first;
    std::shared_ptr<void> object = it->second.lock();
    if (!object) {
        object = make();
        it->second = object;
    }
    return object;
}

void Engine::checkInFrame(std::string_view context) const {
    SP_CHECK(IsInFrame() || (inspections_ > 0 && !ticking_), InvalidState, context,
             ": called outside a frame; engine objects are used inside 'with instance.begin_frame():' or "
             "'with instance.end_frame():'");
}

} // namespace sp::engine
