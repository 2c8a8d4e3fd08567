#pragma once
// Keeps a scene's irradiance volume (core/render/irradiance_volume.h) lit as the scene changes, lighting the
// probes with the path tracer's own estimator (PathTracer::lightProbes), so that the rasteriser's indirect
// light is the reference renderer's, blurred to the probe spacing.
//
// The grid covers the visible instances' bounding box with a margin (a quarter of its largest side), its
// lattice offset from round coordinates (a probe exactly on a floor or wall sees half its rays end at
// distance 0). It is placed again, and every probe lit, only when the scene outgrows it (the margin grows
// with the box, so a thing flying away does not re-place it every frame) or the settings change. Otherwise,
// when the light changed (geometry, materials, lights, sky: PathTracer::lightingSignature; instances under
// half a spacing in bounding radius are invisible to the probes, so small things moving change nothing), each
// update lights the `probesPerFrame` probes lit longest ago: a change reaches every probe within
// framesToSettle() updates, and a still scene costs nothing. Probes inside geometry take the mean of their
// lit neighbours, so that a point whose every visible probe is hidden still blends something near.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/pathtrace/path_tracer.h"
#include "core/render/irradiance_volume.h"

namespace sp::pathtrace {

struct ProbeSettings {
    double spacing = 0.5;      // metres between probes at least; wider where the scene needs more
    int maxProbesPerAxis = 24; // in [2, 256]: a larger scene spaces its probes wider
    int rays = 256;            // radiance estimates per probe and lighting, in [1, 65536]
    int maxBounces = 3;        // bounces after the first surface, in [0, 64]
    int probesPerFrame = 64;   // lit per update once the volume is lit, when the light changed; >= 1
    // Throws sp::InvalidArgument naming the bad field.
    void validate(const char* function) const;
    bool operator==(const ProbeSettings&) const = default;
};

class IrradianceProbes {
  public:
    // Brings the volume up to date with `scene` (see the header comment) and returns it, to be set on the
    // scene; the same pointer while nothing changed, a new one when probes were lit. Null for a scene with
    // nothing visible. The grid covers the visible instances that reach into `around` (the region the
    // cameras that ask for indirect light can use; an empty box: the whole scene), so a thing falling away
    // wholly out of it (off the ground in a long run) neither coarsens the grid nor re-places it as it falls.
    std::shared_ptr<const render::IrradianceVolume> update(const render::Scene& scene, PathTracer& tracer,
                                                           const ProbeSettings& settings,
                                                           const Eigen::AlignedBox3d& around = {});
    // Updates after which a change of the scene has reached every probe: the probe count over probesPerFrame,
    // rounded up (0 before the first update).
    int framesToSettle() const;
    // Probes lit by the last update (all of them when it placed the grid; 0 when nothing changed).
    std::size_t litLastUpdate() const { return litLastUpdate_; }

  private:
    // Places the grid over `box` (the visible instances' bounds).
    void place(const Eigen::AlignedBox3d& box, const ProbeSettings& settings);

    std::shared_ptr<render::IrradianceVolume> volume_; // what update() last returned
    render::IrradianceVolume lit_;                     // the probes as lit, before the inside ones are filled
    Eigen::AlignedBox3d covered_;                      // what the grid was placed to cover
    ProbeSettings settings_;
    std::vector<std::uint64_t> litFor_; // per probe: the lighting signature it was lit for
    std::vector<std::uint64_t> litAt_;  // per probe: the update that lit it
    std::uint64_t updates_ = 0;
    std::size_t litLastUpdate_ = 0;
};

} // namespace sp::pathtrace
