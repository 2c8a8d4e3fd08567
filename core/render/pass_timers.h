#pragma once
// Per-pass timings of the renderer: GL timer queries (GL_TIME_ELAPSED) around each pass, collected
// without stalling once the driver has the result (a frame or more later), plus the CPU time spent
// issuing the pass. On a GPU the query is the pass's execution time; on Mesa's llvmpipe it is the time
// the rasteriser threads spent on it. The readback is timed on the CPU alone (timedOnGpu()). Needs a
// current context.

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

namespace sp::render {

// Occlusion: the screen-space ambient occlusion's passes (screen_occlusion.h), before the surface pass.
enum class Pass : std::uint8_t { Shadow, Surface, Attribute, Readback, Occlusion };
inline constexpr std::size_t kPassCount = 5;

// Whether a pass gets a timer query. The readback does not: it is work the calling thread waits for (a
// glReadPixels into the caller's memory, or a copy out of a mapped buffer), which its CPU time measures
// whole; and on llvmpipe a query makes the rasteriser threads run a scene of their own around the read
// (woken, timestamped, joined): 0.22 ms of a 0.43 ms 1920x1080 final_color read.
constexpr bool timedOnGpu(Pass pass) {
    return pass != Pass::Readback;
}

struct PassTime {
    double gpuMs = 0.0;        // sum of timer-query results collected so far (0 where !timedOnGpu())
    double cpuMs = 0.0;        // sum of the time spent issuing the pass (readback: waiting and copying)
    std::uint64_t samples = 0; // timer-query results collected (those longer than the time since the pass
                               // began are dropped: llvmpipe answers a new context's first query with the
                               // time since boot)
};

class PassTimers {
  public:
    PassTimers() = default;
    ~PassTimers();
    PassTimers(const PassTimers&) = delete;
    PassTimers& operator=(const PassTimers&) = delete;

    // Brackets one pass; passes must not overlap.
    void begin(Pass pass);
    void end();
    // Adds the results of finished queries to the totals (non-blocking).
    void collect();
    const std::array<PassTime, kPassCount>& totals() const { return totals_; }
    void reset();

  private:
    struct Pending {
        unsigned query;
        Pass pass;
        std::chrono::steady_clock::time_point begun;
    };
    std::vector<unsigned> free_;
    std::vector<Pending> pending_;
    std::array<PassTime, kPassCount> totals_{};
    bool open_ = false;
    bool openQuery_ = false; // the open pass has a timer query
    Pass openPass_ = Pass::Shadow;
    std::chrono::steady_clock::time_point start_;
};

} // namespace sp::render
