#pragma once
// Progress of long work (importing a mesh, loading a scene, building navigation), for the user to watch: the
// work reports how far it is, the host shows it (a terminal bar in Python, spear/_progress.py). Reports are
// throttled: nothing at all for work done within half a second, then at most ten a second, then the end, so
// reporting from an inner loop is cheap.
//
//   sp::base::Progress progress("UWorld.load_scene(): apartment.json", actors.size());
//   for (...) { ...; progress.advance(); }

#include <chrono>
#include <string>
#include <string_view>

namespace sp::base {

// Where reports go: the engine module's sink hands them to Python; without one they are written to stderr as
// "[spear-progress] <done> <total> <finished> <task>" lines, which a client that launched the server reads
// (spear/_logging.py). `finished` is true once, last.
using ProgressSink = void (*)(std::string_view task, double done, double total, bool finished);
void setProgressSink(ProgressSink sink);

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
    bool reported_ = false;
};

} // namespace sp::base
