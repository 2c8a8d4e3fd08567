#pragma once
// Engine: owns the worlds and runs the frame loop that SPEAR's programming model is built on:
//
//   begin_frame block   -> user work at the start of a frame
//   executeFrame()      -> the engine ticks every actor (then physics and rendering) once, fixed step
//   end_frame block     -> user work reading results of the same frame
//
// Calls on engine objects are only valid inside the two blocks; the binding layers check that through
// checkInFrame(), so the rule is the same in-process and over RPC.
//
// sp::engine sits above every library with reflected classes (world, sensors, spfunc): it owns the engine
// module's header list (reflected_headers.txt) and registers the module's types; its worlds see it only
// as their sp::world::WorldHost.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/world/world.h"
#include "core/world/world_host.h"

namespace sp::engine {

// Registers every reflected engine type with the registry; idempotent. An Engine registers them when it
// is made; code that uses the registry without an engine (tests, tools) calls it first.
void registerEngineTypes();

class Engine final : public world::WorldHost {
  public:
    enum class FrameState { Idle, BeginFrame, FrameExecuted, EndFrame };

    struct Settings {
        double fixedDeltaSeconds = 1.0 / 60.0;
        // Editor mode: a persistent editor world (never ticked) and, between play() and stop(), a game
        // world copied from it. Standalone mode: one game world for the engine's lifetime.
        bool editor = false;
        // A scene file loaded into the editor world (editor mode) or the game world; empty for none.
        std::string scene{};
        // Threads stepping the worlds' physics at once when the engine has several worlds; 0: the
        // SPEAR_PHYSICS_THREADS environment variable when set, else half the machine's hardware threads. A
        // world's results do not depend on it (each world steps alone on one thread).
        int physicsThreads = 0;
    };

    Engine();
    explicit Engine(Settings settings);
    ~Engine() override;
    Engine(const Engine&) = delete;
    Engine& operator=(const Engine&) = delete;

    // The world that plays; throws InvalidState in an editor that is not playing.
    UWorld& GetGameWorld();
    // The editor world, or nullptr in a standalone engine.
    UWorld* GetEditorWorld() { return editorWorld_.get(); }
    // Editor mode: creates the game world as a reflection copy of the editor world (a scene round trip).
    void play() override;
    // Editor mode: destroys the game world; its objects' handles become stale.
    void stop() override;
    bool IsPlaying() const override { return editorWorld_ && gameWorld_; }
    // One object per key for all of this engine's worlds, alive while a world holds it (WorldHost).
    // Scene files, read and written by sp::scene (WorldHost).
    void loadScene(UWorld& world, const std::string& path, const std::string& function) override;
    void saveScene(const UWorld& world, const std::string& path, const std::string& function) override;
    std::shared_ptr<void> shared(std::string_view key,
                                 const std::function<std::shared_ptr<void>()>& make) override;

    // More worlds beside the game world, each with its own actors, physics and render scene, ticked in
    // the same frame after it (in creation order): many small environments in one process. `name` must
    // be non-empty and not the name of another world of this engine.
    UWorld& CreateWorld(const std::string& name);
    // Destroys a world CreateWorld made; its objects' handles become stale. The game and editor worlds
    // cannot be destroyed this way.
    void DestroyWorld(UWorld& world);
    // The worlds that tick each frame: the game world (when there is one), then the created ones.
    std::vector<UWorld*> GetWorlds() const;
    const Settings& GetSettings() const { return settings_; }

    // Idle -> BeginFrame. Throws InvalidState if a frame is already open.
    void beginFrame();
    // BeginFrame -> FrameExecuted: ticks the world once. If the tick throws, the frame still ends
    // (state FrameExecuted) so that the engine stays usable, and the error propagates.
    void executeFrame();
    // FrameExecuted -> EndFrame.
    void beginEndFrame();
    // EndFrame -> Idle.
    void endFrame();
    // Ends whatever frame is open (used when a user's block raised): runs the tick if it has not run.
    void abortFrame();

    FrameState GetFrameState() const { return state_; }
    bool IsInFrame() const { return state_ == FrameState::BeginFrame || state_ == FrameState::EndFrame; }
    // Throws InvalidState: "<context>: called outside a frame; use 'with instance.begin_frame():' ...",
    // unless an Inspection is open.
    void checkInFrame(std::string_view context) const override;
    // While one is alive, engine objects may be used outside a frame (not while the world ticks): the
    // inspector's reads and edits of a paused simulation, which must not tick the world to look at it.
    class Inspection {
      public:
        explicit Inspection(Engine& engine) : engine_(engine) { ++engine_.inspections_; }
        ~Inspection() { --engine_.inspections_; }
        Inspection(const Inspection&) = delete;
        Inspection& operator=(const Inspection&) = delete;

      private:
        Engine& engine_;
    };
    int64_t GetFrameCount() const { return frameCount_; }

    static std::string_view toString(FrameState state);

  private:
    void expectState(FrameState expected, std::string_view function) const;

    Settings settings_;
    std::map<std::string, std::weak_ptr<void>, std::less<>> shared_; // see shared(); held by the worlds
    std::unique_ptr<UWorld> editorWorld_;
    std::unique_ptr<UWorld> gameWorld_;
    std::vector<std::unique_ptr<UWorld>> createdWorlds_;
    bool ticking_ = false; // inside executeFrame()'s ticks
    int inspections_ = 0;  // open Inspection scopes
    FrameState state_ = FrameState::Idle;
    int64_t frameCount_ = 0;
};

} // namespace sp::engine
