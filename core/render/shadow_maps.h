#pragma once
// Shadow maps of directional, spot and rect lights, one layer each of texture arrays the renderer's scenes
// share (ShadowLayers), and of point lights, six each (a cube of perspective maps around the lamp, after the
// others' layers). Spot maps are perspective over the cone. Needs a current context.
//
// Directional maps are orthographic over a region fitted to what the camera sees (the bounding sphere of
// the instances in its frustum), not to the whole scene: objects that fall or roll far out of view neither
// stretch the map (costing texels and detail where the camera looks) nor force it to be redrawn. The region
// is snapped (radius to steps of 2^(1/4), centre to 1/16 of it) and kept while it holds what is seen and is
// not much larger, so a moving camera or moving objects rarely change it, and the views of one frame share
// it: a batch of views (Renderer::render) asks once for what all of them see, and a view seeing beyond the
// region of an earlier view of the same frame, submitted apart, widens it to hold both. Casters
// between the light and the region are drawn however far (depth clamping), so they still shadow it.
//
// Casters that did not change since the previous update are still: while the lights' projections stay the
// same, an update clears and redraws only the rectangle around what changed (the footprints of casters that
// moved, now and where they were drawn last, and of casters added or removed), scissored, drawing there
// every caster that reaches into it.
// A robot in a large still scene costs the texels it covers, not the whole map. The result equals a full
// render bit for bit.
//
// The maps are layers of a colour texture array holding each texel's depth (the depth test's own value,
// polygon offset included), not a depth texture: the surface pass reads four texels with imageLoad, which a
// software rasteriser runs several times faster than a texture gather (see shadowFactor() in shaders.cpp).
// The arrays are shared by the scenes a Renderer draws (ShadowLayers), so that a batch of worlds draws all
// its maps in one framebuffer.

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "core/render/gpu_scene_cache.h"
#include "core/render/instances.h"
#include "core/render/scene.h"
#include "core/render/shader_program.h"
#include "core/render/shadow_layers.h"

namespace sp::render {

// A sphere in world space; radius 0: empty.
struct Sphere {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0.0;
    bool holds(const Sphere& other) const { return (other.centre - centre).norm() + other.radius <= radius; }
    bool operator==(const Sphere&) const = default;
};
// The smallest sphere holding both (an empty one adds nothing).
Sphere united(const Sphere& a, const Sphere& b);

struct ShadowInfo {
    int lightOrdinal = -1; // the light's position in the scene's light order
    int layer = -1; // the map's number among the scene's (its layer is ShadowMaps::firstLayer() + this)
    Eigen::Matrix4f worldToClip = Eigen::Matrix4f::Identity();
    float texel = 0.0f; // world size of a texel (per metre of distance when perspective)
    bool perspective = false;
};

// What the last update() did, for RenderStats and tests.
struct ShadowUpdate {
    std::size_t maps = 0;          // maps brought up to date (0: nothing changed, the maps were reused)
    std::size_t fullMaps = 0;      // of which every caster was drawn again over the whole map
    std::size_t dynamicDraws = 0;  // moving casters drawn
    std::size_t staticDraws = 0;   // still casters drawn again (those reaching into a redrawn rectangle)
    std::size_t redrawnTexels = 0; // texels cleared and drawn again around moving casters
    std::size_t redrawnRects = 0;  // the rectangles they form (each drawn on its own, scissored)
};

class ShadowMaps {
  public:
    // The maps of the scene `owner` (its Scene::uid()), in layers of `layers`.
    ShadowMaps(ShadowLayers& layers, std::uint64_t owner) : layers_(layers), owner_(owner) {}
    ~ShadowMaps();
    ShadowMaps(const ShadowMaps&) = delete;
    ShadowMaps& operator=(const ShadowMaps&) = delete;

    // Brings the maps up to date for `scene` seen by a view: one for each of the first
    // shaders::kMaxProjectedShadowMaps shadow-casting directional, spot or rect lights (in handle order),
    // then six for each shadow-casting point light while they fit in shaders::kMaxShadowMaps. `seen` is what
    // the directional maps must cover (Scene::bounds within the view's frustum); left out, the whole scene.
    // Returns how many maps were rendered: 0 when nothing that shapes them (lights, visible instances and
    // their meshes, the resolution, the directional region) changed since the last call, so the views of
    // one frame and still scenes share one render.
    std::size_t render(const Scene& scene, int resolution, GpuSceneCache& cache, ShaderProgram& depthProgram,
                       const Sphere* seen = nullptr);
    // The region the directional maps cover, as of the last render() (radius 0: none).
    const Sphere& directionalRegion() const { return region_; }
    // Where each map is, as of the last render().
    const std::vector<ShadowInfo>& infos() const { return infos_; }
    const ShadowUpdate& lastUpdate() const { return update_; }
    // The texture array holding the maps (0: none), the layer of the first map, and the format:
    // GL_R16 (unsigned normalised) when every map is orthographic, else GL_R32F.
    unsigned texture() const { return layers_.place(owner_).texture; }
    int firstLayer() const { return layers_.place(owner_).first; }
    unsigned format() const { return layers_.place(owner_).format; }

  private:
    // A rectangle of texels [x0, x1) x [y0, y1); empty when x0 >= x1.
    struct Rect;
    // A caster as of the previous update: it is still now if nothing of this changed.
    struct CasterState {
        MeshId mesh;
        std::uint64_t meshRevision = 0;
        Eigen::Matrix4d transform;
        std::vector<Rect> footprints; // per map: where it was drawn (all the texels it may cover)
    };
    struct Rect {
        int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        bool empty() const { return x0 >= x1 || y0 >= y1; }
        std::size_t area() const { return empty() ? 0 : std::size_t(x1 - x0) * std::size_t(y1 - y0); }
        bool overlaps(const Rect& other) const {
            return !empty() && !other.empty() && x0 < other.x1 && other.x0 < x1 && y0 < other.y1 &&
                   other.y0 < y1;
        }
        // The smallest rectangle holding both (an empty one adds nothing).
        Rect united(const Rect& other) const {
            if (empty())
                return other;
            if (other.empty())
                return *this;
            return {std::min(x0, other.x0), std::min(y0, other.y0), std::max(x1, other.x1),
                    std::max(y1, other.y1)};
        }
    };

    // The region the directional maps cover now, given what is seen and whether the scene is the one of
    // the last update (another view of the same frame, or a still scene).
    Sphere chooseRegion(const Sphere& seen, bool sameScene) const;
    // `rects` with those that overlap or lie close merged into their union (see the cost in the .cpp).
    static std::vector<Rect> coalesced(std::vector<Rect> rects);
    // Sets the texels of `rects` in the bound layer, and the depth buffer's, to the far plane, with one draw
    // of the depth program (already in use) rather than a scissored clear each: a software rasteriser runs
    // such a clear apart from the draws queued before it, and each cost more than the draws it served.
    void clearRects(const std::vector<Rect>& rects, int resolution);
    // Takes `maps` layers of the arrays of `resolution` x `format` maps (see ShadowLayers).
    void ensure(int resolution, unsigned format, int maps);
    // Draws `casters` into the bound layer with the depth program in use.
    void draw(const Scene& scene, const std::vector<const Instance*>& casters, const ShadowInfo& info,
              const Eigen::Matrix4d& lightProjection, const Eigen::Vector3d& lightPosition,
              GpuSceneCache& cache);
    Rect footprint(const Scene& scene, const Instance& instance, const Eigen::Matrix4d& lightProjection,
                   int resolution) const;

    ShadowLayers& layers_;
    std::uint64_t owner_;
    unsigned quadVao_ = 0, quadBuffers_[2] = {0, 0}; // a unit square (clearRects)
    bool warnedTooMany_ = false;
    std::vector<ShadowInfo> infos_;
    ShadowUpdate update_;
    Sphere region_;                      // what the directional maps cover
    std::vector<double> signature_;      // what the maps were rendered from
    std::vector<double> lightSignature_; // the projections the maps were drawn with (empty: draw them whole)
    std::unordered_map<std::uint64_t, CasterState> casters_; // by packed InstanceId, as last drawn
    InstanceBuffer instances_;                               // the casters' light projections
    std::vector<InstanceRecord> records_;
};

} // namespace sp::render
