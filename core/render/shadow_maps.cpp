#include "core/render/shadow_maps.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/base/log.h"
#include "core/render/shaders.h"

namespace sp::render {
namespace {

// World -> GL eye for an eye at `eye` looking along unit `forward`.
Eigen::Matrix4d lookAlong(const Eigen::Vector3d& eye, const Eigen::Vector3d& forward) {
    const Eigen::Vector3d up =
        std::abs(forward.z()) < 0.99 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d right = forward.cross(up).normalized();
    const Eigen::Vector3d trueUp = right.cross(forward);
    Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
    view.block<1, 3>(0, 0) = right.transpose();
    view.block<1, 3>(1, 0) = trueUp.transpose();
    view.block<1, 3>(2, 0) = -forward.transpose();
    view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
    return view;
}

Eigen::Matrix4d orthographic(double halfSize, double nearClip, double farClip) {
    Eigen::Matrix4d p = Eigen::Matrix4d::Identity();
    p(0, 0) = p(1, 1) = 1.0 / halfSize;
    p(2, 2) = -2.0 / (farClip - nearClip);
    p(2, 3) = -(farClip + nearClip) / (farClip - nearClip);
    return p;
}

Eigen::Matrix4d perspective(double halfAngle, double nearClip, double farClip) {
    Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
    p(0, 0) = p(1, 1) = 1.0 / std::tan(halfAngle);
    p(2, 2) = -(farClip + nearClip) / (farClip - nearClip);
    p(2, 3) = -2.0 * farClip * nearClip / (farClip - nearClip);
    p(3, 2) = -1.0;
    return p;
}

// Everything the maps depend on, as numbers: comparing it is far cheaper than rendering the maps.
std::vector<double> shadowSignature(const Scene& scene, int resolution) {
    std::vector<double> signature{double(scene.uid()), double(resolution)};
    // Handles are left out: a world re-adds its lights every frame, so only their values count.
    scene.forEachLight([&](LightId, const Light& light) {
        signature.insert(signature.end(),
                         {double(light.type), light.castShadows ? 1.0 : 0.0, light.position.x(),
                          light.position.y(), light.position.z(), light.direction.x(), light.direction.y(),
                          light.direction.z(), light.outerConeDeg});
    });
    scene.forEachInstance([&](InstanceId, const Instance& instance) {
        if (!instance.visible)
            return; // invisible instances neither cast shadows nor widen the scene's bounds
        signature.insert(signature.end(),
                         {double(instance.mesh.index), double(instance.mesh.generation),
                          double(scene.meshRevision(instance.mesh)), instance.castShadows ? 1.0 : 0.0});
        const Eigen::Matrix4d& m = instance.transform.matrix();
        signature.insert(signature.end(), m.data(), m.data() + 16);
    });
    return signature;
}

// `sphere` snapped: the radius to steps of 2^(1/4), the centre to a grid of 1/16 of it, the sphere grown
// until it holds the exact one. Objects moving inside it then leave the maps where they are (no shimmering
// texel grid, and the still casters stay valid). Empty for an empty sphere, or one no map can cover
// (coordinates near the float limits overflow the bounds).
Sphere snapped(const Sphere& sphere) {
    if (!std::isfinite(sphere.radius) || !sphere.centre.allFinite() || sphere.radius > 1e30 ||
        sphere.radius <= 0.0)
        return {};
    double step = std::exp2(std::ceil(4.0 * std::log2(sphere.radius)) / 4.0);
    for (int attempt = 0; attempt < 8; ++attempt) { // two suffice; the bound keeps rounding from looping
        const double grid = step / 16.0;
        const Eigen::Vector3d centre = (sphere.centre / grid).array().round().matrix() * grid;
        if ((centre - sphere.centre).norm() + sphere.radius <= step)
            return {centre, step};
        step *= std::exp2(0.25);
    }
    return {sphere.centre, sphere.radius * 1.25}; // not reached for finite bounds; certainly holds it
}

// A directional region kept for a new frame may be at most this much wider than what is seen: wider, its
// texels are coarser than a fresh fit's by more than the snapping's own steps.
constexpr double kLooseRegion = 1.4142135623730951;

std::uint64_t packed(InstanceId id) {
    return (std::uint64_t(id.generation) << 32) | id.index;
}

} // namespace

Sphere united(const Sphere& a, const Sphere& b) {
    if (a.radius <= 0.0)
        return b;
    if (b.radius <= 0.0 || a.holds(b))
        return a;
    if (b.holds(a))
        return b;
    const double distance = (b.centre - a.centre).norm();
    const double radius = 0.5 * (distance + a.radius + b.radius);
    return {a.centre + (b.centre - a.centre) * ((radius - a.radius) / distance), radius};
}

ShadowMaps::~ShadowMaps() {
    layers_.release(owner_);
    glDeleteVertexArrays(1, &quadVao_);
    glDeleteBuffers(2, quadBuffers_);
}

void ShadowMaps::ensure(int resolution, unsigned format, int maps) {
    // As many layers as maps are drawn, not shaders::kMaxShadowMaps: a world with one sun holds one map
    // (at 2048 texels, 8 MB instead of 32; sixty-four worlds of an engine, 0.5 GB instead of 2).
    const ShadowLayers::Place before = layers_.place(owner_);
    const ShadowLayers::Place now = layers_.acquire(owner_, resolution, format, maps);
    if (now.first != before.first || now.count != before.count || now.resolution != before.resolution ||
        now.format != before.format)
        lightSignature_.clear(); // new layers hold nothing of this scene yet: the next update draws in full
}

void ShadowMaps::clearRects(const std::vector<Rect>& rects, int resolution) {
    if (rects.empty())
        return;
    if (quadVao_ == 0) { // the unit square, drawn once per rectangle
        const float corners[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        const std::uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
        glCreateBuffers(2, quadBuffers_);
        glNamedBufferStorage(quadBuffers_[0], sizeof(corners), corners, 0);
        glNamedBufferStorage(quadBuffers_[1], sizeof(triangles), triangles, 0);
        glCreateVertexArrays(1, &quadVao_);
        glVertexArrayVertexBuffer(quadVao_, 0, quadBuffers_[0], 0, sizeof(float) * 3);
        glVertexArrayElementBuffer(quadVao_, quadBuffers_[1]);
        glEnableVertexArrayAttrib(quadVao_, 0);
        glVertexArrayAttribFormat(quadVao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(quadVao_, 0, 0);
        configureInstanceAttributes(quadVao_);
    }
    // Each rectangle's square at the far plane (z = w: depth 1), over the texels' centres it holds.
    records_.resize(rects.size());
    for (std::size_t i = 0; i < rects.size(); ++i) {
        const Rect& rect = rects[i];
        Eigen::Matrix4d toClip = Eigen::Matrix4d::Zero();
        toClip(0, 0) = 2.0 * (rect.x1 - rect.x0) / resolution;
        toClip(0, 3) = 2.0 * rect.x0 / resolution - 1.0;
        toClip(1, 1) = 2.0 * (rect.y1 - rect.y0) / resolution;
        toClip(1, 3) = 2.0 * rect.y0 / resolution - 1.0;
        toClip(2, 3) = toClip(3, 3) = 1.0;
        records_[i].setModelViewProjection(toClip);
    }
    instances_.upload(records_);
    instances_.bind(quadVao_);
    glBindVertexArray(quadVao_);
    glDepthFunc(GL_ALWAYS);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDrawElementsInstanced(GL_TRIANGLES, 6, GL_UNSIGNED_INT, nullptr, GLsizei(rects.size()));
    glEnable(GL_POLYGON_OFFSET_FILL);
    glDepthFunc(GL_LESS);
    glBindVertexArray(0);
}

void ShadowMaps::draw(const Scene& scene, const std::vector<const Instance*>& casters, const ShadowInfo& info,
                      const Eigen::Matrix4d& lightProjection, const Eigen::Vector3d& lightPosition,
                      GpuSceneCache& cache) {
    // Each caster at the level of detail whose error stays within half a shadow-map texel; then one
    // instanced draw per level of detail (the order of casters does not change a depth map).
    std::vector<std::pair<MeshId, const Instance*>> drawn;
    drawn.reserve(casters.size());
    for (const Instance* instance : casters) {
        Eigen::Vector3d centre;
        double radius = 0.0;
        scene.boundingSphere(*instance, centre, radius);
        const double texel = info.perspective
                                 ? info.texel * std::max((centre - lightPosition).norm() - radius, 0.02)
                                 : double(info.texel);
        drawn.emplace_back(scene.lodFor(instance->mesh, radius / texel), instance);
    }
    std::stable_sort(drawn.begin(), drawn.end(), [](const auto& a, const auto& b) {
        return a.first.index != b.first.index ? a.first.index < b.first.index
                                              : a.first.generation < b.first.generation;
    });
    records_.resize(drawn.size());
    for (std::size_t i = 0; i < drawn.size(); ++i)
        records_[i].setModelViewProjection(lightProjection * drawn[i].second->transform.matrix());
    instances_.upload(records_);
    for (std::size_t first = 0, last = 0; first < drawn.size(); first = last) {
        for (last = first + 1; last < drawn.size() && drawn[last].first == drawn[first].first;)
            ++last;
        const GpuMesh& mesh = cache.mesh(scene, drawn[first].first);
        instances_.bind(mesh.vao);
        glBindVertexArray(mesh.vao);
        for (const Submesh& sub : mesh.submeshes)
            glDrawElementsInstancedBaseInstance(
                GL_TRIANGLES, GLsizei(sub.indexCount), GL_UNSIGNED_INT,
                reinterpret_cast<const void*>(std::uintptr_t(sub.firstIndex) * 4), GLsizei(last - first),
                GLuint(first));
    }
    glBindVertexArray(0);
}

ShadowMaps::Rect ShadowMaps::footprint(const Scene& scene, const Instance& instance,
                                       const Eigen::Matrix4d& lightProjection, int resolution) const {
    Eigen::Vector3d centre;
    double radius = 0.0;
    scene.boundingSphere(instance, centre, radius);
    const Rect whole{0, 0, resolution, resolution};
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    const bool orthographic = lightProjection.row(3) == Eigen::RowVector4d(0, 0, 0, 1);
    if (orthographic) {
        // An orthographic (affine) map: the sphere's shadow is the disc of its centre's image, as wide along
        // each axis as the radius times that row's scale; a box around the cube of the sphere would be up
        // to sqrt(3) wider, three times the texels to redraw.
        const Eigen::Vector4d clip = lightProjection * centre.homogeneous();
        const double rx = radius * lightProjection.row(0).head<3>().norm();
        const double ry = radius * lightProjection.row(1).head<3>().norm();
        x0 = ((clip.x() - rx) * 0.5 + 0.5) * resolution, x1 = ((clip.x() + rx) * 0.5 + 0.5) * resolution;
        y0 = ((clip.y() - ry) * 0.5 + 0.5) * resolution, y1 = ((clip.y() + ry) * 0.5 + 0.5) * resolution;
    }
    // A perspective map: nothing of it when the sphere lies wholly outside one of the frustum's side planes
    // (x or y beyond +-w; a point light's faces see their sixth of the space around it).
    for (int side = 0; side < 4 && !orthographic; ++side) {
        const Eigen::RowVector4d plane =
            lightProjection.row(3) + (side % 2 == 0 ? -1.0 : 1.0) * lightProjection.row(side / 2);
        if (plane * centre.homogeneous() < -radius * plane.head<3>().norm())
            return {};
    }
    int behind = 0;
    for (int corner = 0; corner < 8 && !orthographic; ++corner) {
        const Eigen::Vector3d offset((corner & 1) ? radius : -radius, (corner & 2) ? radius : -radius,
                                     (corner & 4) ? radius : -radius);
        const Eigen::Vector4d clip = lightProjection * (centre + offset).homogeneous();
        if (clip.w() <= 1e-9) {
            ++behind;
            continue;
        }
        const double x = (clip.x() / clip.w() * 0.5 + 0.5) * resolution;
        const double y = (clip.y() / clip.w() * 0.5 + 0.5) * resolution;
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
    if (behind == 8)
        return {}; // wholly behind the light's map (another face of a point light's cube): not in it
    if (behind > 0)
        return whole; // reaches behind a spot light: no bounded footprint
    // Two texels of margin for rasterisation rules and the polygon offset.
    auto clampTo = [&](double v) { return int(std::clamp(v, 0.0, double(resolution))); };
    return {clampTo(std::floor(x0) - 2), clampTo(std::floor(y0) - 2), clampTo(std::ceil(x1) + 2),
            clampTo(std::ceil(y1) + 2)};
}

std::vector<ShadowMaps::Rect> ShadowMaps::coalesced(std::vector<Rect> rects) {
    std::erase_if(rects, [](const Rect& rect) { return rect.empty(); });
    // Merging is quadratic in the rectangles: past this many (over a hundred moving casters), one rectangle
    // around them all is cheaper to find and about as cheap to redraw, as they cover much of the map.
    constexpr std::size_t kMostRects = 256;
    if (rects.size() > kMostRects) {
        Rect all;
        for (const Rect& rect : rects)
            all = all.united(rect);
        return {all};
    }
    // Two rectangles become their union when it costs little more than drawing both: the texels it adds
    // against the fixed cost of a rectangle (its own scissored draws of the casters reaching into it, which
    // a software rasteriser pays as about this many texels).
    constexpr std::size_t kRectCostInTexels = 4096;
    for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < rects.size(); ++i)
            for (std::size_t j = i + 1; j < rects.size();) {
                const Rect both = rects[i].united(rects[j]);
                if (both.area() <= rects[i].area() + rects[j].area() + kRectCostInTexels) {
                    rects[i] = both;
                    rects[j] = rects.back();
                    rects.pop_back();
                    merged = true;
                } else {
                    ++j;
                }
            }
    }
    return rects;
}

Sphere ShadowMaps::chooseRegion(const Sphere& seen, bool sameScene) const {
    const bool held = region_.radius > 0.0 && region_.holds(seen);
    if (seen.radius <= 0.0 || (held && (sameScene || region_.radius <= kLooseRegion * seen.radius)))
        return region_; // nothing seen needs covering, or the region covers it well enough
    // Another view of the frame (or of a still scene) seeing beyond the region widens it to hold both, so
    // that the views share one map; a new frame fits it afresh.
    return snapped(sameScene && region_.radius > 0.0 ? united(region_, seen) : seen);
}

std::size_t ShadowMaps::render(const Scene& scene, int resolution, GpuSceneCache& cache,
                               ShaderProgram& depthProgram, const Sphere* seen) {
    std::vector<double> signature = shadowSignature(scene, resolution);
    update_ = {};
    const bool sameScene = layers_.place(owner_).first >= 0 && signature == signature_;
    bool directional = false, spot = false;
    scene.forEachLight([&](LightId, const Light& light) {
        directional = directional || (light.castShadows && light.type == LightType::Directional);
        spot = spot || (light.castShadows && light.type != LightType::Directional);
    });
    Sphere region;
    if (directional) {
        Sphere wanted;
        if (seen)
            wanted = *seen;
        else
            scene.bounds(wanted.centre, wanted.radius);
        region = chooseRegion(wanted, sameScene);
    }
    if (sameScene && region == region_)
        return 0;
    signature_ = std::move(signature);
    region_ = region;

    std::vector<std::pair<std::uint64_t, const Instance*>> current; // the casters, by packed InstanceId
    scene.forEachInstance([&](InstanceId id, const Instance& instance) {
        if (instance.visible && instance.castShadows)
            current.emplace_back(packed(id), &instance);
    });
    // The projections the maps are drawn with; while they stay the same, an update redraws only where
    // casters changed.
    std::vector<double> lightSignature{double(resolution)};

    std::vector<ShadowInfo>& infos = infos_;
    infos.clear();
    // Spot maps reach as far as the scene does (its bounds are not needed without them).
    Sphere scope;
    if (spot) {
        scene.bounds(scope.centre, scope.radius);
        scope = snapped(scope);
    }
    const Eigen::Vector3d& centre = scope.centre;
    const double radius = scope.radius;
    if (radius <= 0.0 && region_.radius <= 0.0) {
        lightSignature_.clear(); // no maps now: the next ones are drawn whole
        return 0;
    }
    int skipped = 0;
    std::vector<Eigen::Matrix4d> projections;
    std::vector<Eigen::Vector3d> positions;
    // A perspective map of `light`, seen from its position along `forward` over `halfAngle`.
    auto perspectiveMap = [&](ShadowInfo& info, const Light& light, const Eigen::Vector3d& forward,
                              double halfAngle) {
        const double farClip = (light.position - centre).norm() + radius;
        const double nearClip = std::max(0.02, farClip * 1e-3);
        projections.push_back(perspective(halfAngle, nearClip, farClip) * lookAlong(light.position, forward));
        info.texel = float(2.0 * std::tan(halfAngle) / resolution);
        info.perspective = true;
    };
    auto add = [&](ShadowInfo info, const Light& light) {
        positions.push_back(light.position);
        info.worldToClip = projections.back().cast<float>();
        info.layer = static_cast<int>(infos.size());
        infos.push_back(info);
        lightSignature.insert(lightSignature.end(), projections.back().data(),
                              projections.back().data() + 16);
        lightSignature.insert(lightSignature.end(),
                              {light.position.x(), light.position.y(), light.position.z()});
    };
    // Directional, spot and rect lights first: their maps take the first layers, whose coordinates the
    // vertex shader interpolates (shaders::kMaxProjectedShadowMaps); then the point lights' cubes.
    int ordinal = -1;
    scene.forEachLight([&](LightId, const Light& light) {
        ++ordinal;
        if (!light.castShadows || light.type == LightType::Point)
            return;
        if (infos.size() >= std::size_t(shaders::kMaxProjectedShadowMaps)) {
            ++skipped;
            return;
        }
        ShadowInfo info;
        info.lightOrdinal = ordinal;
        const Eigen::Vector3d forward = light.direction.normalized();
        if (light.type == LightType::Directional) {
            if (region_.radius <= 0.0)
                return; // the view sees nothing: no map
            projections.push_back(orthographic(region_.radius, 0.0, 4.0 * region_.radius) *
                                  lookAlong(region_.centre - forward * (2.0 * region_.radius), forward));
            info.texel = float(2.0 * region_.radius / resolution);
        } else {
            if (radius <= 0.0)
                return; // the scene has no bounds a map could cover
            // A rect light shines over a hemisphere: its map, seen from its centre, covers the 75 degrees
            // about its normal that carry 93 % of its light (sin^2 75); points further out are unshadowed.
            perspectiveMap(info, light, forward,
                           light.type == LightType::Rect
                               ? 75.0 * M_PI / 180.0
                               : std::min(light.outerConeDeg * M_PI / 180.0 + 0.05, 1.5));
        }
        add(info, light);
    });
    ordinal = -1;
    scene.forEachLight([&](LightId, const Light& light) {
        ++ordinal;
        if (!light.castShadows || light.type != LightType::Point || radius <= 0.0)
            return;
        if (infos.size() + 6 > std::size_t(shaders::kMaxShadowMaps)) {
            ++skipped;
            return;
        }
        // Six faces, +x, -x, +y, -y, +z, -z (the order pointShadowFactor() in shaders.cpp picks them in),
        // each a little wider than 90 degrees, so that a point near an edge, moved by the normal offset and
        // read by the bilinear tap, still lies inside the face its direction chooses.
        ShadowInfo info;
        info.lightOrdinal = ordinal;
        for (int face = 0; face < 6; ++face) {
            Eigen::Vector3d forward = Eigen::Vector3d::Zero();
            forward[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
            perspectiveMap(info, light, forward, std::atan(1.0 + 8.0 / resolution));
            add(info, light);
        }
    });
    if (skipped > 0 && !warnedTooMany_) {
        SP_LOG("render: ", skipped, " shadow-casting light(s) beyond the first ",
               shaders::kMaxProjectedShadowMaps, " directional, spot or rect lights, or past ",
               shaders::kMaxShadowMaps,
               " maps in all (a point light takes six), are rendered without shadows");
        warnedTooMany_ = true;
    }
    if (infos.empty()) {
        lightSignature_.clear();
        return 0;
    }

    // 16 bits of depth when every map is orthographic: a step (extent / 37000 for a cube of the scene)
    // is far below the 1.5-texel normal offset (extent / resolution), and half the bytes to clear, write
    // and read. A perspective map's depth is not linear; far from the light 16 bits would be too coarse.
    const bool anyPerspective =
        std::any_of(infos.begin(), infos.end(), [](const ShadowInfo& info) { return info.perspective; });
    ensure(resolution, anyPerspective ? GL_R32F : GL_R16, int(infos.size()));
    const bool drawAll = lightSignature != lightSignature_;
    lightSignature_ = std::move(lightSignature);

    // Casters unchanged since the previous update are still, and their footprints (where they were drawn)
    // still hold. Each other caster marks its footprint now and where it was drawn last (a caster removed
    // or hidden since, the latter) as stale: what the update clears and draws again. A caster coming to
    // rest or starting to move changes nothing else.
    std::vector<const Instance*> statics, moving;
    std::vector<const std::vector<Rect>*> staticFootprints, movingFootprints;
    std::vector<std::vector<Rect>> stale(infos.size());
    std::unordered_map<std::uint64_t, CasterState> casters;
    casters.reserve(current.size());
    for (const auto& [id, instance] : current) {
        CasterState state{
            instance->mesh, scene.meshRevision(instance->mesh), instance->transform.matrix(), {}};
        const auto previous = casters_.find(id);
        const bool known = previous != casters_.end() && !drawAll;
        if (known && previous->second.mesh == state.mesh &&
            previous->second.meshRevision == state.meshRevision &&
            previous->second.transform == state.transform) {
            state.footprints = std::move(previous->second.footprints);
            casters_.erase(previous);
            statics.push_back(instance);
            staticFootprints.push_back(&casters.emplace(id, std::move(state)).first->second.footprints);
            continue;
        }
        for (std::size_t i = 0; i < infos.size(); ++i) {
            state.footprints.push_back(footprint(scene, *instance, projections[i], resolution));
            stale[i].push_back(state.footprints.back());
            if (known)
                stale[i].push_back(previous->second.footprints[i]);
        }
        if (previous != casters_.end())
            casters_.erase(previous);
        moving.push_back(instance);
        movingFootprints.push_back(&casters.emplace(id, std::move(state)).first->second.footprints);
    }
    if (!drawAll)
        for (const auto& [id, gone] : casters_) // removed, hidden or no longer casting since the last update
            for (std::size_t i = 0; i < infos.size(); ++i)
                stale[i].push_back(gone.footprints[i]);
    casters_ = std::move(casters);

    glViewport(0, 0, resolution, resolution);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    // Slope-scaled offset against acne; the surface pass's vertex shader adds a normal offset of 1.5 texels.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 2.0f);
    // Whatever happens below (a mesh upload can throw), the passes after this one must not inherit the
    // offset or a scissor: a scissored clear would clear only the rectangle.
    struct RestoreState {
        ~RestoreState() {
            glDisable(GL_SCISSOR_TEST);
            glDisable(GL_POLYGON_OFFSET_FILL);
            glDisable(GL_DEPTH_CLAMP);
        }
    } restoreState;
    depthProgram.use();
    const ShadowLayers::Place place = layers_.place(owner_);
    // The whole layer's depths to the far plane, and the depth layer with them (clearRects() clears parts).
    // In a layered framebuffer of several layers a clear would clear them all: the far square is drawn
    // into this one instead, to the same values.
    auto clear = [&] {
        if (layers_.layered() && place.arrayLayers > 1) {
            clearRects({Rect{0, 0, resolution, resolution}}, resolution);
            return;
        }
        const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        glClearBufferfv(GL_COLOR, 0, far);
        glClearBufferfv(GL_DEPTH, 0, far);
    };
    for (std::size_t i = 0; i < infos.size(); ++i) {
        const ShadowInfo& info = infos[i];
        layers_.bind(owner_, info.layer);
        if (layers_.layered())
            depthProgram.set("uLayer", place.first + info.layer);
        // A directional map covers a region, not the scene: casters nearer the light than its near plane are
        // drawn at depth 0 rather than clipped, since they still shadow the region.
        if (info.perspective)
            glDisable(GL_DEPTH_CLAMP);
        else
            glEnable(GL_DEPTH_CLAMP);
        if (drawAll) {
            // Every caster is new to the map (drawAll leaves no still ones); those wholly outside it are
            // not drawn.
            clear();
            std::vector<const Instance*> inside;
            for (std::size_t c = 0; c < moving.size(); ++c)
                if (!(*movingFootprints[c])[i].empty())
                    inside.push_back(moving[c]);
            draw(scene, inside, info, projections[i], positions[i], cache);
            ++update_.fullMaps;
            update_.dynamicDraws += inside.size();
        } else {
            // Each stale rectangle is cleared and drawn again, scissored to it, from every caster reaching
            // into it. A texel's depth is the nearest of the casters covering it, whatever the order, so this
            // equals a full render bit for bit; and unlike copying the rectangle back from a map of the still
            // casters, it never makes the CPU wait for the rasteriser (a software one copies through mapped
            // memory).
            const std::vector<Rect> regions = coalesced(std::move(stale[i]));
            clearRects(regions, resolution);
            for (const Rect& region : regions) {
                glEnable(GL_SCISSOR_TEST);
                glScissor(region.x0, region.y0, region.x1 - region.x0, region.y1 - region.y0);
                std::vector<const Instance*> reaching;
                for (std::size_t c = 0; c < statics.size(); ++c)
                    if ((*staticFootprints[c])[i].overlaps(region))
                        reaching.push_back(statics[c]);
                update_.staticDraws += reaching.size();
                for (std::size_t c = 0; c < moving.size(); ++c)
                    if ((*movingFootprints[c])[i].overlaps(region)) {
                        reaching.push_back(moving[c]);
                        ++update_.dynamicDraws;
                    }
                draw(scene, reaching, info, projections[i], positions[i], cache);
                glDisable(GL_SCISSOR_TEST);
                update_.redrawnTexels += region.area();
                ++update_.redrawnRects;
            }
        }
    }
    update_.maps = infos.size();
    return infos.size();
}

} // namespace sp::render
