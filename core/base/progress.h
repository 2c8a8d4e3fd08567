#pragma once
// Progress of long work (importing a mesh, loading a scene, building navigation), for the user to watch: the
// work reports how far it is, the host shows it (a terminal bar in Python, spear/_progress.py). Reports are
// throttled: nothing at all for work done within half a second, then at most ten a second, then the end, so
// reporting from an inner loop is cheap.
//
//   sp::base::Progress progress("UWorld.load_scene(): apartment.json", actors.size());
//   for (...) { ...; progress.advance(); }

#include <chrono>
#include <functional>
#include <string>
#include <string_view>

namespace sp::base {

// Where reports go: the engine module's sink hands them to Python; without one they are written to stderr as
// "[spear-progress] <done> <total> <finished> <task>" lines, which a client that launched the server reads
// (spear/_logging.py). `finished` is true once, last.
using ProgressSink = void (*)(std::string_view task, double done, double total, bool finished);
void setProgressSink(ProgressSink sink);
// Who else hears reports besides the sink (the inspector's browsers), as log listeners hear lines (log.h).
using ProgressListener = std::function<void(std::string_view task, double done, double total, bool finished)>;
int addProgressListener(ProgressListener listener);
void removeProgressListener(int id);

// What the host does while long work keeps its thread: called from Progress::set() on the thread that made
// the Progress, once the work has run for a second, then every 50 ms (`seconds`: how long it has run). A
// server answers its other clients there ("busy") instead of letting them wait unanswered
// (core/rpc/server.cpp). Null: nothing. One hook per process, set and cleared by the thread that runs the
// work.
using BusyHook = void (*)(void* context, std::string_view task, double seconds);
void setBusyHook(BusyHook hook, void* context);

// A request to stop the process (a server's SIGTERM): long work that can be cut short checks stopRequested()
// in its inner loops (every few milliseconds) and ends, leaving nothing half written, by throwing
// sp::InvalidState. requestStop() is async-signal-safe.
void requestStop();
bool stopRequested();

class Progress {
  public:
    Progress(std::string task, double total);
    ~Progress(); // reports the end, also when the work was cut short by an exception
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(double amount = 1.0) { set(done_ + amount); }
    void set(double done);

  private:
    using Clock = std::chrono::steady_clock;
    void report(bool finished);

    std::string task_;
    double total_;
    double done_ = 0.0;
    Clock::time_point start_;
    Clock::time_point last_;
    Clock::time_point lastBusy_;
    bool reported_ = false;
};

} // namespace sp::base
