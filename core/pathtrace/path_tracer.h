#pragma once
// sp::pathtrace: the reference renderer behind the camera sensor (ECameraRenderer.PathTraced), a CPU path
// tracer on Embree over the rasteriser's own scene (core/render/scene.h): the same meshes, materials
// (base colour and its texture, roughness/metallic and their texture, emissive), lights and sky.
//
// Multi-bounce global illumination, unbiased up to the bounce limit: at every vertex, next-event estimation
// of each analytic light (directional, point, spot: delta lights, one shadow ray each; rect: one point of its
// area) and of the sky (combined with the BSDF-sampled ray by multiple importance sampling, power
// heuristic); at every rough vertex a light-vertex connection (the surface a point or spot lamp's ray
// lights, joined to the vertex: Settings::lightConnections); the surface model is the rasteriser's (bsdf.h),
// normal maps included. Russian roulette after three bounces. Images accumulate across calls while the scene,
// the camera and maxBounces stay the same, so a still view converges; any change anywhere in the scene
// restarts them. Point lights cast shadows (as the rasteriser's cube maps do), rect lights soft ones;
// instances that do not cast shadows are invisible to shadow rays only. Primary rays that leave the scene
// show the environment's background, as in the rasteriser; rays that leave it after a bounce bring back the
// sky's radiance.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/render/camera.h"
#include "core/render/scene.h"

namespace sp::pathtrace {

struct Settings {
    Settings() = default;
    Settings(int samples, int bounces, float maxIntensity = 0.0f, bool caustics = false,
             bool connections = true)
        : samplesPerPixel(samples), maxBounces(bounces), maxPathIntensity(maxIntensity),
          approximateCaustics(caustics), lightConnections(connections) {}

    int samplesPerPixel = 4; // samples added per render() call, in [1, 65536]
    int maxBounces = 4;      // indirect bounces after the first hit, in [0, 64] (0: direct light only)
    // Firefly control: the radiance a path brings back to its first surface from beyond it (bounced light,
    // not the first surface's own direct light), scaled down so that no channel exceeds this; 0 (the default)
    // clamps nothing and keeps the estimate unbiased. Finite, >= 0.
    float maxPathIntensity = 0.0f;
    // Path regularisation (Unreal's r.PathTracing.ApproximateCaustics; off here, so that the reference stays
    // unbiased unless asked): each
    // surface a path meets after its first is at least as rough as the lobes it was reached through (a
    // diffuse lobe counts as roughness 1), so light that a glossy floor or a metal leg reflects from the
    // sun onto a wall arrives as a smooth glow instead of as speckles that take tens of thousands of
    // samples to average out. What the camera sees directly, and through mirrors, stays sharp; caustics
    // are blurred (a bias).
    bool approximateCaustics = false;
    // Light-vertex connections: at each rough surface a path meets, a ray from a point or spot lamp (drawn
    // by power) to the first surface it lights, joined to the path there, weighed against the bounce that
    // would find the same light (multiple importance sampling). The light a lamp's hot spot on a ceiling
    // throws into a room is found from the first samples. Unbiased; on by default; two more rays a vertex.
    bool lightConnections = true;
    // Throws sp::InvalidArgument naming the bad field.
    void validate(const char* function) const;
};

// The running estimate of one camera's image and of its intrinsic parts: diffuse_only, the light the first
// surface a pixel sees reflects through its diffuse lobe, and diffuse_illumination, what a white Lambertian
// surface there would reflect (both with indirect light); hdr_color minus diffuse_only is the specular
// residual (specular reflection, emission and background).
struct Accumulation {
    int width = 0;
    int height = 0;
    std::vector<double> sum;                    // hdr_color RGB sums, (height, width, 3), row 0 = top
    std::vector<double> diffuseOnlySum;         // likewise
    std::vector<double> diffuseIlluminationSum; // likewise
    // What the paths' first surfaces were, for the denoiser (denoise.h): base colour and normal sums (H, W,
    // 3), distance sums (H, W), and the instance (+ 1; 0: nothing) the first sample of each pixel met.
    std::vector<double> albedoSum, normalSum, depthSum;
    std::vector<double> directSum; // the analytic lights' direct light and emission (H, W, 3): not filtered
    // Sums of the square of each sample's luminance less its direct light (H, W): how noisy each pixel's
    // filtered part is (the denoiser's edge-stopping scale).
    std::vector<double> indirectSquareSum;
    std::vector<std::uint32_t> ids;
    std::uint64_t samples = 0;   // per pixel
    std::uint64_t signature = 0; // of the scene, camera and settings the samples were taken of
    // The mean of channel c of pixel (x, y) of `sums` (one of the three above).
    float mean(const std::vector<double>& sums, int x, int y, int c) const {
        return samples == 0 ? 0.0f : float(sums[(std::size_t(y) * width + x) * 3 + c] / double(samples));
    }
    float mean(int x, int y, int c) const { return mean(sum, x, y, c); }
};

// How far from the origin (m) anything is traced: rays start as floats, which Embree refuses beyond about
// 1.8e18, and an instance's own space must keep them valid (a million kilometres is past any scene).
constexpr double kMaxTraceableReach = 1e9;

// What the probes' rays see of a scene: not the instances whose bounding radius is under
// `ignoreBelowRadius` (lit by the probes, they neither block nor bounce light for them, so that small things
// moving do not make every probe stale), nor those wholly outside `within` (the grid's region; empty: all
// of space), so that a thing falling away out there does not either.
struct ProbeScope {
    double ignoreBelowRadius = 0.0;
    Eigen::AlignedBox3d within;
    bool operator==(const ProbeScope& other) const {
        return ignoreBelowRadius == other.ignoreBelowRadius && within.min() == other.within.min() &&
               within.max() == other.within.max();
    }
    // Whether the probes' rays see `instance` (a visible one).
    bool sees(const render::Scene& scene, const render::Instance& instance) const;
};

class PathTracer {
  public:
    // Starts an Embree device; throws sp::InvalidState when it cannot.
    PathTracer();
    ~PathTracer();
    PathTracer(const PathTracer&) = delete;
    PathTracer& operator=(const PathTracer&) = delete;

    // Adds settings.samplesPerPixel samples per pixel of `camera`'s view of `scene` to `image`, after
    // restarting it when the scene, the camera or settings.maxBounces changed since its last samples. Runs
    // on every hardware thread.
    void render(const render::Scene& scene, const render::Camera& camera, const Settings& settings,
                Accumulation& image);

    // Lights the probes of `volume` named by `probes` (IrradianceVolume::index()) as this renderer sees
    // `scene`: each probe's constant and linear terms (IrradianceProbe) from `rays` path-traced estimates of
    // the radiance arriving from directions spread evenly over the sphere (settings.maxBounces bounces after
    // the first surface; lights cast shadows; rays that leave the scene bring back the sky,
    // Environment::ambient), and its free distances from one ray along each axis. A probe whose rays meet the
    // back of a surface first more than a quarter of the time is inside geometry: its free distances are 0.
    // The random numbers are seeded from the scene's light (lightingSignature()) and the probe's index, so
    // the same scene gives the same probes in every run. Runs on every hardware thread. The rays see what
    // `scope` leaves of the scene.
    void lightProbes(const render::Scene& scene, render::IrradianceVolume& volume,
                     std::span<const std::size_t> probes, int rays, const Settings& settings,
                     const ProbeScope& scope = {});
    // What the light the probes see in `scene` depends on: geometry (what `scope` leaves of it), materials,
    // lights and sky; not the camera.
    std::uint64_t lightingSignature(const render::Scene& scene, const ProbeScope& scope = {});

    // Geometry (re)builds so far: one whenever an instance, a mesh or a transform changed.
    std::uint64_t builds() const;
    // Rays the last render() traced: closest hits and shadow (occlusion) rays.
    std::uint64_t lastRays() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace sp::pathtrace
