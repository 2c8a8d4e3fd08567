#pragma once
// Where, in one view, a shadow map can darken a surface. A pixel no shadow reaches shades the same without
// its shadow-map lookups, and on a software rasteriser those lookups are a fifth of a shaded pixel (four
// imageLoads per map: see shadowFactor() in shaders.cpp), so the surface pass draws what no shadow reaches
// with programs that make none (Renderer::setShadowReach). A floor under a few objects is drawn in
// scissored parts: with the lookups in the rectangles their shadows can fall in, without them elsewhere.
//
// What a caster can darken is bounded conservatively, so images are the same bit for bit either way: its
// box, widened by the lookup's reach in the map (the normal offset of 1.5 texels, the bilinear tap's texel,
// the map's depth step), swept away from a directional light (a box along a segment), or the cone from a
// spot light through its bounding sphere; a receiver is reached where that region meets its own box. An
// instance is its own receiver unless its mesh is convex, shaded flat and has no levels of detail (a box, a
// floor): such a surface, drawn as it is in the map, cannot shadow itself past the normal offset; smooth
// normals shade facets that face away from the light (a sphere's terminator), and another level of detail
// in the map may stand in front of the one in view.

#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "core/render/camera.h"
#include "core/render/scene.h"

namespace sp::render {

struct ShadowInfo;

// Pixels [x0, x1) x [y0, y1) of the framebuffer (GL window coordinates, as glScissor takes them).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
    bool operator==(const PixelRect&) const = default;
};

// How one visible instance receives shadows in a view.
struct ShadowReach {
    enum class Kind {
        None,  // no shadow reaches it: drawn without lookups
        Whole, // drawn with lookups
        Part,  // drawn in parts, scissored
    };
    Kind kind = Kind::Whole;
    std::vector<PixelRect> shadowed;   // Part: drawn with lookups
    std::vector<PixelRect> unshadowed; // Part: the rest of the instance's rectangle, drawn without
};

class ShadowReceivers {
  public:
    // Side of the square tiles the shadowed rectangles are rounded out to (pixels): llvmpipe's own tiles,
    // which it shades whole when one triangle covers them; split between two scissored draws, a tile is
    // rasterised twice with the scissor's edges (32-pixel tiles measured 11% slower a frame than 64, Table 3,
    // N = 64, 1080p). And the most scissored draws one instance is split into: past it, drawing it whole
    // costs less than the draws.
    static constexpr int kTile = 64;
    static constexpr std::size_t kMaxParts = 48;
    // The fewest pixels an instance must have where no shadow reaches for it to be drawn in parts: each
    // part draws all of its triangles again (scissored), which pays only for large, simple surfaces.
    static constexpr long kMinUnshadowedPixels = 256 * 256;

    // For `camera` rendering `width` x `height` pixels of `scene` with the shadow maps `maps` (as
    // ShadowMaps::infos() gives them, for the scene's lights in their order).
    ShadowReceivers(const Scene& scene, const Camera& camera, int width, int height,
                    const std::vector<ShadowInfo>& maps);

    // How `receiver` (a visible instance of the scene) receives shadows.
    ShadowReach reach(const Scene& scene, const Instance& receiver) const;

    // The pixels of a world box in the view (rounded out by a pixel, clipped to the framebuffer; empty
    // when it is wholly behind the camera or outside).
    PixelRect pixels(const Eigen::AlignedBox3d& box) const;

  private:
    struct Caster {
        Eigen::AlignedBox3d box;
        bool selfShadowFree = false; // convex, faceted and drawn the same in the map and the view
        const Instance* instance = nullptr;
    };
    // A shadowed light: directional (a direction) or spot (an apex), with the lookup's reach in its map.
    struct ShadowLight {
        bool directional = true;
        Eigen::Vector3d direction = Eigen::Vector3d::UnitZ(); // directional: where the light travels (unit)
        Eigen::Vector3d apex = Eigen::Vector3d::Zero();       // spot: the light's position
        double margin = 0.0;                                  // directional: metres; spot: radians
        Eigen::Matrix4d worldToClip = Eigen::Matrix4d::Identity(); // spot: the map's projection
        double clipReach = 1.0; // spot: the map's frustum widened by the reach, in clip x / w
        double range =
            0.0; // point, spot or rect light of finite range: it lights nothing beyond (0: no limit)
        bool allAround =
            false; // a point light: its cube of maps sees every direction (no frustum to be out of)
    };
    // Whether a caster box lies wholly outside a spot map's frustum (so it is not in the map).
    static bool outsideMap(const ShadowLight& light, const Eigen::AlignedBox3d& caster);

    // The part of `receiver` that `caster` can darken under `light`, as a box (empty: none).
    static Eigen::AlignedBox3d darkened(const ShadowLight& light, const Eigen::AlignedBox3d& caster,
                                        const Eigen::AlignedBox3d& receiver);
    static Eigen::AlignedBox3d sweptAway(const Eigen::Vector3d& direction, const Eigen::AlignedBox3d& caster,
                                         const Eigen::AlignedBox3d& receiver);
    static Eigen::AlignedBox3d coneBeyond(const Eigen::Vector3d& apex, double margin,
                                          const Eigen::AlignedBox3d& caster,
                                          const Eigen::AlignedBox3d& whole);
    // Splits `own` into runs of kTile tiles that the rectangles `reached` touch and runs they do not (Whole
    // when that does not pay: see kMaxParts and kMinUnshadowedPixels).
    static ShadowReach split(const PixelRect& own, const std::vector<PixelRect>& reached);

    Eigen::Matrix4d viewProjection_;
    int width_ = 0, height_ = 0;
    std::vector<ShadowLight> lights_;
    std::vector<Caster> casters_;
    bool affordable_ = true; // whether the tests fit the view's budget (see the .cpp)
};

} // namespace sp::render
