#pragma once
// FFrameTimings: where a world's frames spent the CPU's time, for a user finding what bounds a step
// (UWorld.get_frame_timings()). Wall-clock sums since the world began, so any span of frames is a difference.

#include <cstdint>

#include "core/reflect/macros.h"

/// The CPU time a world's frames took, by stage, summed over the frames since the world began (take two and
/// subtract for a span). GPU time is the renderer's (UCameraSensorComponent.GetRenderStats()).
SPSTRUCT()
struct FFrameTimings {
    SP_GENERATED_BODY()

    /// Frames ticked.
    SPPROPERTY()
    int64_t Frames = 0;
    /// Milliseconds ticking actors and their components (controllers, movement, vehicles, scripted logic).
    SPPROPERTY()
    double ActorsMs = 0.0;
    /// Milliseconds in physics: stepping the bodies and writing their poses back to the components.
    SPPROPERTY()
    double PhysicsMs = 0.0;
    /// Milliseconds in rendering on the CPU: gathering the cameras' scenes and issuing their GPU work (a
    /// camera whose images are read at once waits for the GPU in the read, not here). Engines with several
    /// worlds issue one batch for all of them, counted in the world that issued it.
    SPPROPERTY()
    double RenderingMs = 0.0;
    /// Milliseconds in other subsystems (navigation, plugins' subsystems).
    SPPROPERTY()
    double OtherMs = 0.0;
};
