#include "core/render/shadow_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/render/shadow_maps.h"

namespace sp::render {
namespace {

// The lookup's reach in a map, in texels: the normal offset (1.5, see offsetShadowClip() in shaders.cpp)
// plus the bilinear tap's texel around the offset point (up to sqrt 2), rounded up.
constexpr double kReachTexels = 4.0;
// The tests a view may make (casters x shadowed lights x instances, each a few dozen nanoseconds): one per 8
// pixels, at least 4096. Past it every instance is drawn whole with its lookups, as the tests would cost
// more than the lookups they spare (a 1080p view allows 512 casters of one light among 512 instances).
constexpr std::size_t kPixelsPerTest = 8, kMinTests = 4096;

Eigen::AlignedBox3d widened(const Eigen::AlignedBox3d& box, double by) {
    return {box.min().array() - by, box.max().array() + by};
}

Eigen::AlignedBox3d translated(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& by) {
    return {box.min() + by, box.max() + by};
}

} // namespace

ShadowReceivers::ShadowReceivers(const Scene& scene, const Camera& camera, int width, int height,
                                 const std::vector<ShadowInfo>& maps)
    : viewProjection_(camera.projectionMatrix(true) * camera.viewMatrix()), width_(width), height_(height) {
    int ordinal = 0;
    scene.forEachLight([&](LightId, const Light& light) {
        for (const ShadowInfo& map : maps) {
            if (map.lightOrdinal != ordinal)
                continue;
            ShadowLight shadowLight;
            shadowLight.directional = !map.perspective;
            if (shadowLight.directional) {
                shadowLight.direction = light.direction.normalized();
                // Plus two steps of a 16-bit depth: clip z spans [-1, 1] over 2 / |row z| metres.
                const double depthStep = 2.0 / (65535.0 * double(map.worldToClip.row(2).head<3>().norm()));
                shadowLight.margin = kReachTexels * double(map.texel) + 2.0 * depthStep;
            } else {
                shadowLight.worldToClip = map.worldToClip.cast<double>();
                // clip x / w spans 2 over the map's resolution
                shadowLight.clipReach =
                    1.0 + 2.0 * kReachTexels / std::max(1, camera.params.shadowResolution);
                shadowLight.apex = light.position;
                shadowLight.margin = kReachTexels * double(map.texel); // a texel per metre of distance
                shadowLight.range = light.ranged() ? double(light.range) : 0.0;
                shadowLight.allAround = light.type == LightType::Point;
            }
            lights_.push_back(shadowLight);
            if (shadowLight.allAround)
                break; // a point light's six faces are one light here: the cone from its position
        }
        ++ordinal;
    });
    scene.forEachInstance([&](InstanceId, const Instance& instance) {
        if (instance.visible && instance.castShadows)
            casters_.push_back(
                {scene.boundingBox(instance),
                 scene.meshConvexFaceted(instance.mesh) && scene.meshLods(instance.mesh).empty(), &instance});
    });
    const std::size_t tests = casters_.size() * lights_.size() * scene.instanceCount();
    affordable_ = tests <= std::max(kMinTests, std::size_t(width) * std::size_t(height) / kPixelsPerTest);
}

ShadowReach ShadowReceivers::reach(const Scene& scene, const Instance& receiver) const {
    if (lights_.empty())
        return {ShadowReach::Kind::None, {}, {}};
    if (!affordable_)
        return {};
    const Eigen::AlignedBox3d box = scene.boundingBox(receiver);
    const PixelRect own = pixels(box);
    if (own.empty())
        return {ShadowReach::Kind::None, {}, {}};
    std::vector<PixelRect> reached;
    for (const ShadowLight& light : lights_)
        for (const Caster& caster : casters_) {
            if (caster.instance == &receiver && caster.selfShadowFree)
                continue;
            const Eigen::AlignedBox3d region = darkened(light, caster.box, box);
            if (region.isEmpty())
                continue;
            PixelRect rect = pixels(region);
            rect = {std::max(rect.x0, own.x0), std::max(rect.y0, own.y0), std::min(rect.x1, own.x1),
                    std::min(rect.y1, own.y1)};
            if (!rect.empty())
                reached.push_back(rect);
        }
    if (reached.empty())
        return {ShadowReach::Kind::None, {}, {}};
    return split(own, reached);
}

Eigen::AlignedBox3d ShadowReceivers::darkened(const ShadowLight& light, const Eigen::AlignedBox3d& caster,
                                              const Eigen::AlignedBox3d& receiver) {
    if (light.directional)
        return sweptAway(light.direction, widened(caster, light.margin), receiver);
    if (!light.allAround && outsideMap(light, caster))
        return {};
    const Eigen::AlignedBox3d region = coneBeyond(light.apex, light.margin, caster, receiver);
    if (light.range <= 0.0 || region.isEmpty())
        return region;
    // A light of finite range adds nothing past it, so nothing there is darker for its shadow (a point
    // light's cube reaches all around it: without this its shadows would reach every receiver).
    const Eigen::Vector3d reach = Eigen::Vector3d::Constant(light.range);
    return region.intersection(Eigen::AlignedBox3d(light.apex - reach, light.apex + reach));
}

bool ShadowReceivers::outsideMap(const ShadowLight& light, const Eigen::AlignedBox3d& caster) {
    // Outside when every corner is outside one of the frustum's side planes (x or y beyond +-w, widened by
    // the reach) or behind the light (w <= 0). Each is a half-space of world space, tested by a linear
    // function of the corner, so the test holds for corners behind the light too: a box holding the light
    // has corners on both sides of every plane through it. Depth is clamped when the map is drawn, so near
    // and far do not count.
    unsigned outside = 0x1f;
    for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector4d c =
            light.worldToClip *
            caster.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)).homogeneous();
        const double w = c.w() * light.clipReach;
        outside &= (c.x() < -w ? 1u : 0u) | (c.x() > w ? 2u : 0u) | (c.y() < -w ? 4u : 0u) |
                   (c.y() > w ? 8u : 0u) | (c.w() <= 0.0 ? 16u : 0u);
    }
    return outside != 0;
}

Eigen::AlignedBox3d ShadowReceivers::sweptAway(const Eigen::Vector3d& direction,
                                               const Eigen::AlignedBox3d& caster,
                                               const Eigen::AlignedBox3d& receiver) {
    // The caster box moved by t * direction, t >= 0, meets the receiver box for t in [from, to]: on each
    // axis, caster.min + t d <= receiver.max and caster.max + t d >= receiver.min.
    double from = 0.0, to = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const double d = direction[k];
        const double upper = receiver.max()[k] - caster.min()[k], lower = receiver.min()[k] - caster.max()[k];
        if (std::abs(d) < 1e-12) {
            if (upper < 0.0 || lower > 0.0)
                return {};
            continue;
        }
        const double a = upper / d, b = lower / d; // t bounds; which is which depends on the sign of d
        from = std::max(from, d > 0.0 ? b : a);
        to = std::min(to, d > 0.0 ? a : b);
    }
    if (!(from <= to))
        return {};
    // The swept box between those times is the hull of its two ends (a box moved along a segment).
    Eigen::AlignedBox3d region = translated(caster, from * direction);
    region.extend(translated(caster, to * direction));
    return region.intersection(receiver);
}

Eigen::AlignedBox3d ShadowReceivers::coneBeyond(const Eigen::Vector3d& apex, double margin,
                                                const Eigen::AlignedBox3d& caster,
                                                const Eigen::AlignedBox3d& whole) {
    // A ray from the light that passed through the caster box stays beyond it on every axis the light is
    // outside it on (above a floor, below its top): the receiver is clipped to that side first, so that a
    // floor, whose bounding sphere may hold the light, darkens only what lies under it.
    double far = 0.0;
    for (int corner = 0; corner < 8; ++corner)
        far =
            std::max(far, (whole.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)) - apex).norm());
    const double reach = margin * far; // the lookup's reach, in metres, at the receiver's farthest
    Eigen::AlignedBox3d receiver = whole;
    for (int k = 0; k < 3; ++k) {
        if (apex[k] > caster.max()[k] + reach)
            receiver.max()[k] = std::min(receiver.max()[k], caster.max()[k] + reach);
        if (apex[k] < caster.min()[k] - reach)
            receiver.min()[k] = std::max(receiver.min()[k], caster.min()[k] - reach);
    }
    if (receiver.isEmpty())
        return {};
    // Then it lies in the cone from the light through the caster's bounding sphere (widened by the reach,
    // an angle), no nearer the light along the axis than the sphere.
    const Eigen::Vector3d centre = caster.center();
    const double radius = 0.5 * caster.diagonal().norm();
    const double distance = (centre - apex).norm();
    if (distance <= radius * 1.0001 + 1e-9)
        return receiver; // the light is inside the caster's bounding sphere: no cone bounds it
    const double angle = std::asin(radius / distance) + margin;
    if (angle >= 1.4)
        return receiver; // a cone that wide bounds nothing usefully
    const Eigen::Vector3d axis = (centre - apex) / distance;
    // Reject a receiver whose bounding sphere lies outside the cone.
    const Eigen::Vector3d toReceiver = receiver.center() - apex;
    const double receiverRadius = 0.5 * receiver.diagonal().norm(), receiverDistance = toReceiver.norm();
    if (receiverDistance > receiverRadius) {
        const double off = std::acos(std::clamp(toReceiver.dot(axis) / receiverDistance, -1.0, 1.0));
        if (off - std::asin(receiverRadius / receiverDistance) > angle)
            return {};
    }
    // The depths along the axis at which the cone can meet the receiver: beyond the caster's nearest point
    // (less the reach), within the receiver's corners' depths, and on each axis k within its slab, which the
    // cone's cross-section at depth t (centre apex + t a, reaching t tan(angle) sqrt(1 - a_k^2) along k)
    // meets only for t (a_k + g_k) >= min_k - apex_k and t (a_k - g_k) <= max_k - apex_k.
    const double slope = std::tan(angle);
    const Eigen::Vector3d spread = (Eigen::Vector3d::Ones() - axis.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
    double nearest = std::max(distance - radius - margin * distance, 0.0);
    double farthest = -std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner)
        farthest = std::max(
            farthest,
            (receiver.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)) - apex).dot(axis));
    const auto atLeast = [&](double coefficient, double bound) { // coefficient * t >= bound
        if (std::abs(coefficient) < 1e-12) {
            if (bound > 0.0)
                farthest = -1.0; // never
        } else if (coefficient > 0.0) {
            nearest = std::max(nearest, bound / coefficient);
        } else {
            farthest = std::min(farthest, bound / coefficient);
        }
    };
    for (int k = 0; k < 3; ++k) {
        const double g = slope * spread[k];
        atLeast(axis[k] + g, receiver.min()[k] - apex[k]);
        atLeast(g - axis[k], apex[k] - receiver.max()[k]);
    }
    if (nearest > farthest)
        return {};
    // The cone between those two depths is the hull of its two end discs.
    Eigen::AlignedBox3d region;
    for (const double t : {nearest, farthest}) {
        const Eigen::Vector3d disc = apex + t * axis, extent = t * slope * spread;
        region.extend(Eigen::AlignedBox3d(disc - extent, disc + extent));
    }
    return region.intersection(receiver);
}

PixelRect ShadowReceivers::pixels(const Eigen::AlignedBox3d& box) const {
    if (box.isEmpty())
        return {};
    // The box's corners in front of the near plane (clip z >= -w), and where its edges cross that plane.
    Eigen::Vector4d clip[8];
    for (int corner = 0; corner < 8; ++corner)
        clip[corner] =
            viewProjection_ * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)).homogeneous();
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    const auto add = [&](const Eigen::Vector4d& p) {
        const double x = (0.5 * p.x() / p.w() + 0.5) * width_, y = (0.5 * p.y() / p.w() + 0.5) * height_;
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
    };
    for (int a = 0; a < 8; ++a) {
        const double da = clip[a].z() + clip[a].w();
        if (da >= 0.0)
            add(clip[a]);
        for (int bit = 1; bit < 8; bit <<= 1) { // the edges from a to corners differing in one coordinate
            const int b = a | bit;
            if (b == a)
                continue;
            const double db = clip[b].z() + clip[b].w();
            if ((da < 0.0) != (db < 0.0))
                add(clip[a] + (da / (da - db)) * (clip[b] - clip[a]));
        }
    }
    if (!(x0 <= x1 && y0 <= y1))
        return {};
    // Rounded out by a pixel: coverage is decided at pixel centres, after the driver's own rounding.
    const auto clampTo = [](double v, int size) { return int(std::clamp(v, 0.0, double(size))); };
    return {clampTo(std::floor(x0) - 1.0, width_), clampTo(std::floor(y0) - 1.0, height_),
            clampTo(std::ceil(x1) + 1.0, width_), clampTo(std::ceil(y1) + 1.0, height_)};
}

ShadowReach ShadowReceivers::split(const PixelRect& own, const std::vector<PixelRect>& reached) {
    const int tx0 = own.x0 / kTile, ty0 = own.y0 / kTile;
    const int columns = (own.x1 + kTile - 1) / kTile - tx0, rows = (own.y1 + kTile - 1) / kTile - ty0;
    std::vector<char> marked(std::size_t(columns) * std::size_t(rows), 0);
    std::size_t count = 0;
    for (const PixelRect& r : reached)
        for (int y = r.y0 / kTile - ty0; y <= (r.y1 - 1) / kTile - ty0; ++y)
            for (int x = r.x0 / kTile - tx0; x <= (r.x1 - 1) / kTile - tx0; ++x) {
                char& tile = marked[std::size_t(y) * std::size_t(columns) + std::size_t(x)];
                count += tile == 0 ? 1 : 0;
                tile = 1;
            }
    if (2 * count >= marked.size())
        return {}; // mostly reached: one draw with lookups
    // Runs of equally marked tiles along each row, merged with the run just above when it spans the same
    // columns.
    ShadowReach reach{ShadowReach::Kind::Part, {}, {}};
    struct Run {
        int from, to;
        char mark;
        std::size_t index; // in the list of its mark
    };
    std::vector<Run> above, current;
    for (int y = 0; y < rows; ++y) {
        current.clear();
        for (int x = 0; x < columns;) {
            const char mark = marked[std::size_t(y) * std::size_t(columns) + std::size_t(x)];
            int end = x + 1;
            while (end < columns && marked[std::size_t(y) * std::size_t(columns) + std::size_t(end)] == mark)
                ++end;
            std::vector<PixelRect>& list = mark ? reach.shadowed : reach.unshadowed;
            const PixelRect rect{std::max(own.x0, (tx0 + x) * kTile), std::max(own.y0, (ty0 + y) * kTile),
                                 std::min(own.x1, (tx0 + end) * kTile),
                                 std::min(own.y1, (ty0 + y + 1) * kTile)};
            const auto same = std::find_if(above.begin(), above.end(), [&](const Run& run) {
                return run.from == x && run.to == end && run.mark == mark;
            });
            std::size_t index = list.size();
            if (same != above.end()) {
                index = same->index;
                list[index].y1 = rect.y1;
            } else {
                list.push_back(rect);
            }
            current.push_back({x, end, mark, index});
            x = end;
        }
        std::swap(above, current);
    }
    long spared = 0;
    for (const PixelRect& rect : reach.unshadowed)
        spared += long(rect.x1 - rect.x0) * long(rect.y1 - rect.y0);
    if (reach.shadowed.size() + reach.unshadowed.size() > kMaxParts || spared < kMinUnshadowedPixels)
        return {};
    return reach;
}

} // namespace sp::render
