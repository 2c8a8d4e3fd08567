#include "core/render/pass_timers.h"

#include <epoxy/gl.h>

namespace sp::render {

PassTimers::~PassTimers() {
    for (const Pending& pending : pending_)
        free_.push_back(pending.query);
    if (!free_.empty())
        glDeleteQueries(GLsizei(free_.size()), free_.data());
}

void PassTimers::begin(Pass pass) {
    open_ = true;
    openPass_ = pass;
    openQuery_ = timedOnGpu(pass);
    if (!openQuery_) {
        start_ = std::chrono::steady_clock::now();
        return;
    }
    GLuint query = 0;
    if (free_.empty()) {
        glGenQueries(1, &query);
    } else {
        query = free_.back();
        free_.pop_back();
    }
    glBeginQuery(GL_TIME_ELAPSED, query);
    start_ = std::chrono::steady_clock::now();
    pending_.push_back({query, pass, start_});
}

void PassTimers::end() {
    if (!open_)
        return;
    if (openQuery_)
        glEndQuery(GL_TIME_ELAPSED);
    totals_[static_cast<std::size_t>(openPass_)].cpuMs +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    open_ = false;
}

void PassTimers::collect() {
    // Results arrive in submission order, so stop at the first that is not ready.
    const auto now = std::chrono::steady_clock::now();
    std::size_t done = 0;
    for (; done < pending_.size(); ++done) {
        if (open_ && openQuery_ && done + 1 == pending_.size())
            break;
        GLint available = 0;
        glGetQueryObjectiv(pending_[done].query, GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available)
            break;
        GLuint64 nanoseconds = 0;
        glGetQueryObjectui64v(pending_[done].query, GL_QUERY_RESULT, &nanoseconds);
        free_.push_back(pending_[done].query);
        // A pass cannot have run longer than the time since it began. llvmpipe answers the first query of a
        // new context with its end time alone (the time since boot: 3096 s after two frames), which would
        // swamp every total; such a result is not a measurement.
        const double ms = double(nanoseconds) * 1e-6;
        if (ms > std::chrono::duration<double, std::milli>(now - pending_[done].begun).count())
            continue;
        PassTime& total = totals_[static_cast<std::size_t>(pending_[done].pass)];
        total.gpuMs += ms;
        ++total.samples;
    }
    pending_.erase(pending_.begin(), pending_.begin() + std::ptrdiff_t(done));
}

void PassTimers::reset() {
    totals_ = {};
}

} // namespace sp::render
