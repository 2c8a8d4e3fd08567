#include "core/pathtrace/path_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <thread>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/progress.h"
#include "core/pathtrace/bsdf.h"
#include "core/pathtrace/emitters.h"
#include "core/pathtrace/sampler.h"
#include "core/render/box_uv.h"
#include "core/render/luminance.h"

namespace sp::pathtrace {
namespace {

// Geometry mask bits: every instance is seen by camera and bounce rays, shadow-casting ones by shadow rays.
// Probe rays (PathTracer::lightProbes) see only the instances at least the probes' cutoff in radius: small
// things that move do not relight every probe.
constexpr unsigned kCameraRays = 1u, kShadowRays = 2u, kProbeRays = 4u, kProbeShadowRays = 8u;

// FNV-1a over the bytes of what an image depends on.
struct Hasher {
    std::uint64_t value = 1469598103934665603ull;
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i)
            value = (value ^ p[i]) * 1099511628211ull;
    }
    template <typename T> void add(const T& v) { bytes(&v, sizeof v); }
    template <typename Derived> void matrix(const Eigen::MatrixBase<Derived>& m) {
        for (Eigen::Index i = 0; i < m.size(); ++i)
            add(m(i));
    }
};

// A point of the aperture disc of `radius` (camera body frame: the disc spans +Y and +Z at X = 0), uniform
// over its area by Shirley and Chiu's concentric mapping.
Eigen::Vector3f lensPoint(PathSampler& random, float radius) {
    const auto [ua, ub] = random.next2();
    const float a = 2.0f * ua - 1.0f, b = 2.0f * ub - 1.0f;
    if (a == 0.0f && b == 0.0f)
        return Eigen::Vector3f::Zero();
    const float quarter = 0.25f * float(M_PI);
    const bool wide = std::abs(a) > std::abs(b);
    const float r = wide ? a : b, phi = wide ? quarter * (b / a) : 2.0f * quarter - quarter * (a / b);
    return {0.0f, radius * r * std::cos(phi), radius * r * std::sin(phi)};
}

// One path's estimate: hdr_color, and the part of it the first surface reflects through its diffuse lobe
// (diffuse_only) with what a white Lambertian surface there would reflect (diffuse_illumination).
struct PathSample {
    Eigen::Vector3f hdr = Eigen::Vector3f::Zero();
    // The first surface: base colour, shading normal, distance along the ray, instance + 1 (0: none).
    Eigen::Vector3f albedo = Eigen::Vector3f::Zero();
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();
    float depth = 0.0f;
    std::uint32_t instance = 0;
    // The part of hdr the analytic lights give the first surface directly (and its emission, or the
    // background): sharp and nearly noiseless, so the denoiser filters only the rest.
    Eigen::Vector3f direct = Eigen::Vector3f::Zero();
    Eigen::Vector3f diffuseOnly = Eigen::Vector3f::Zero();
    Eigen::Vector3f diffuseIllumination = Eigen::Vector3f::Zero();
};

// One mesh's triangles in its own space, built once per revision and instanced by every instance of it: a
// moving object costs the top level's rebuild, not its triangles'.
struct MeshShape {
    RTCScene scene = nullptr;
    std::vector<Eigen::Vector3f> positions; // mesh space (a normal map's tangent frame)
    std::vector<Eigen::Vector3f> normals;   // mesh space
    std::vector<Eigen::Vector2f> uvs;
    std::vector<std::uint32_t> indices; // the submeshes' triangles, in submesh order
    std::vector<std::uint32_t> slots;   // each triangle's material slot
    std::uint64_t revision = 0;
    std::uint64_t usedBy = 0; // the last top-level build that instanced it
    MeshShape() = default;
    MeshShape(const MeshShape&) = delete;
    MeshShape& operator=(const MeshShape&) = delete;
    ~MeshShape() {
        if (scene)
            rtcReleaseScene(scene);
    }
};

// One visible instance: its mesh and what turns the mesh's normals into the world's.
struct Shape {
    const MeshShape* mesh = nullptr;
    Eigen::Matrix3f normalMatrix;              // inverse transpose of the instance's linear part
    Eigen::Matrix3f linear;                    // the instance's linear part
    Eigen::Vector3f translation;               // and its translation
    std::vector<render::MaterialId> materials; // one per submesh
    bool probed = true;                        // probe rays see it (not smaller than the probe cutoff)
    bool castsShadows = true;                  // shadow rays (and lights' rays) see it
};

std::array<float, 256> srgbTable() {
    std::array<float, 256> table{};
    for (int i = 0; i < 256; ++i) {
        const float c = float(i) / 255.0f;
        table[std::size_t(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    return table;
}

// Bilinear, repeating texel lookup; colour textures decoded from sRGB.
Eigen::Vector4f sampleTexture(const render::TextureImage& image, bool srgb, const Eigen::Vector2f& uv) {
    static const std::array<float, 256> kSrgb = srgbTable();
    const float x = uv.x() * float(image.width) - 0.5f, y = uv.y() * float(image.height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    auto texel = [&](int i, int j) {
        i = ((i % image.width) + image.width) % image.width;
        j = ((j % image.height) + image.height) % image.height;
        const std::uint8_t* p = &image.rgba[(std::size_t(j) * image.width + i) * 4];
        Eigen::Vector4f v;
        for (int c = 0; c < 3; ++c)
            v[c] = srgb ? kSrgb[p[c]] : float(p[c]) / 255.0f;
        v[3] = float(p[3]) / 255.0f;
        return v;
    };
    const int i = int(fx), j = int(fy);
    return (texel(i, j) * (1 - tx) + texel(i + 1, j) * tx) * (1 - ty) +
           (texel(i, j + 1) * (1 - tx) + texel(i + 1, j + 1) * tx) * ty;
}

// The irradiance at p, at normal incidence, from `light` along the direction l to it (a rect light: to a
// point of it drawn uniformly by u1, u2, so that this is an estimate), and its distance.
Eigen::Vector3f lightIrradiance(const render::Light& light, const Eigen::Vector3f& p, float u1, float u2,
                                Eigen::Vector3f& l, float& distance) {
    const Eigen::Vector3f radiance = light.color * light.intensity;
    if (light.type == render::LightType::Directional) {
        l = -light.direction.cast<float>().normalized();
        distance = std::numeric_limits<float>::infinity();
        return radiance;
    }
    Eigen::Vector3f d = light.position.cast<float>() - p;
    const float centreDistance = d.norm();
    float cosine = 1.0f; // at the light, of its normal and the way to p: a rect is a Lambertian emitter
    if (light.type == render::LightType::Rect) {
        // Uniform on the rectangle (pdf 1 / area): radiance * area * cos / d^2 = intensity * cos / d^2.
        d +=
            (light.right * ((u1 - 0.5) * light.width) + light.up * ((u2 - 0.5) * light.height)).cast<float>();
        cosine =
            std::max(0.0f, -d.dot(light.direction.cast<float>().normalized()) / std::max(d.norm(), 1e-6f));
    }
    distance = d.norm();
    l = d / std::max(distance, 1e-6f);
    Eigen::Vector3f e = radiance * (cosine / std::max(distance * distance, 1e-4f));
    if (light.range > 0.0f) { // the rasteriser's window: (1 - (d / range)^4)^2, of the light's centre
        const float r = centreDistance / light.range;
        const float w = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
        e *= w * w;
    }
    if (light.type == render::LightType::Spot) {
        const float inner = std::cos(light.innerConeDeg * kPi / 180.0f);
        const float outer = std::cos(light.outerConeDeg * kPi / 180.0f);
        const float t = std::clamp(((-l).dot(light.direction.cast<float>().normalized()) - outer) /
                                       std::max(inner - outer, 1e-4f),
                                   0.0f, 1.0f);
        e *= t * t;
    }
    return e;
}

// Light-vertex connections are drawn at surfaces at least this rough (smoother ones reflect a narrow lobe
// that the bounce finds better).
constexpr float kJoinedRoughness = 0.3f;

// Light-vertex connections: the lights whose rays the path tracer follows to the first surface they light
// and joins to a path's vertex (point and spot lights that cast shadows), each drawn in proportion to its
// power. Indexed as Scene::forEachLight() visits the lights.
struct LightVertices {
    std::vector<const render::Light*> lights;
    std::vector<float> chance; // of each light being drawn (0: never)
    std::vector<float> cdf;    // running sum of `chance`
    // The cosine, to the light's axis, of the edge of what its rays light: a spot's outer cone, -1 for a
    // point light (its rays are drawn uniformly over the directions whose cosine is above it).
    std::vector<float> lowestCosine;
    bool empty() const { return cdf.empty() || cdf.back() <= 0.0f; }
    // The solid angle light `i`'s rays are drawn over.
    float solidAngle(std::size_t i) const { return 2.0f * kPi * (1.0f - lowestCosine[i]); }
};

LightVertices lightVertices(const render::Scene& scene) {
    LightVertices out;
    double total = 0.0;
    std::vector<double> power;
    scene.forEachLight([&](render::LightId, const render::Light& light) {
        const bool joins = light.castShadows &&
                           (light.type == render::LightType::Point || light.type == render::LightType::Spot);
        out.lights.push_back(&light);
        out.lowestCosine.push_back(light.type == render::LightType::Spot
                                       ? std::cos(std::clamp(light.outerConeDeg, 0.0f, 180.0f) * kPi / 180.0f)
                                       : -1.0f);
        const double p = joins ? double(light.intensity) * double(render::luminance(light.color)) *
                                     double(out.solidAngle(out.lights.size() - 1))
                               : 0.0;
        power.push_back(std::isfinite(p) && p > 0.0 ? p : 0.0);
        total += power.back();
    });
    double running = 0.0;
    for (double p : power) {
        out.chance.push_back(total > 0.0 ? float(p / total) : 0.0f);
        running += total > 0.0 ? p / total : 0.0;
        out.cdf.push_back(float(running));
    }
    return out;
}

// The density per unit area with which a light-vertex connection draws a point whose direction from light
// `i` is `fromLight` (unit), at `distance` from it, on a surface whose cosine to that direction is `cosine`:
// the light's chance, times the density of its rays' direction, times the area's solid angle.
float lightVertexDensity(const LightVertices& table, std::size_t i, const Eigen::Vector3f& fromLight,
                         float distance, float cosine) {
    const render::Light& light = *table.lights[i];
    if (table.chance[i] <= 0.0f)
        return 0.0f;
    if (light.type == render::LightType::Spot &&
        fromLight.dot(light.direction.cast<float>().normalized()) < table.lowestCosine[i])
        return 0.0f;
    return table.chance[i] / table.solidAngle(i) * cosine / std::max(distance * distance, 1e-4f);
}

// The multiple importance sampling weight of a sample drawn with density `chosen` where another strategy
// would have drawn it with density `other` (Veach's power heuristic, exponent 2).
float powerHeuristic(float chosen, float other) {
    return chosen * chosen / (chosen * chosen + other * other);
}

// Runs `work` on every hardware thread, the caller's included, and returns when all are done.
template <typename Work> void onEveryThread(Work& work) {
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::jthread> pool; // joined on the way out, even when starting one throws
    for (unsigned t = 1; t < threads; ++t)
        pool.emplace_back(work);
    work();
}

} // namespace

void Settings::validate(const char* function) const {
    SP_CHECK(samplesPerPixel >= 1 && samplesPerPixel <= 65536, InvalidArgument, function,
             ": samplesPerPixel ", samplesPerPixel, " is out of range [1, 65536]");
    SP_CHECK(maxBounces >= 0 && maxBounces <= 64, InvalidArgument, function, ": maxBounces ", maxBounces,
             " is out of range [0, 64]");
    SP_CHECK(std::isfinite(maxPathIntensity) && maxPathIntensity >= 0.0f, InvalidArgument, function,
             ": maxPathIntensity ", maxPathIntensity, " must be finite and >= 0");
}

struct PathTracer::Impl {
    RTCDevice device = nullptr;
    RTCScene rtcScene = nullptr;
    std::uint64_t geometrySignature = 0; // of the built geometry (geometryHash())
    std::uint64_t probeGeometrySignature =
        0;                      // of what probe rays see of it (geometryHash(scene, &probeScope))
    ProbeScope probeScope;      // what probe rays see
    std::uint64_t builtFor = 0; // the uid of the scene it was built from
    std::uint64_t builds = 0;
    std::uint64_t lastRays = 0;
    std::vector<Shape> shapes; // by instance geometry id in rtcScene
    Emitters emitters;         // the emissive triangles of `shapes`
    std::uint64_t emittersKey = 0;
    // Mesh scenes by (MeshId index, generation); those no build instanced lately are released.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<MeshShape>> meshShapes;

    ~Impl() {
        meshShapes.clear();
        if (rtcScene)
            rtcReleaseScene(rtcScene);
        if (device)
            rtcReleaseDevice(device);
    }

    // Builds the geometry again when the scene's changed (or it is another scene).
    void sync(const render::Scene& scene) {
        const std::uint64_t geometry = geometryHash(scene, nullptr);
        if (!rtcScene || geometry != geometrySignature || !(builtScope == probeScope) ||
            scene.uid() != builtFor) {
            build(scene);
            geometrySignature = geometry;
            probeGeometrySignature = geometryHash(scene, &probeScope);
            builtScope = probeScope;
            builtFor = scene.uid();
        }
    }
    ProbeScope builtScope; // the probe scope of the built masks

    // What probe rays need: what the scope leaves of the scene, as it is now. The rest keeps whatever
    // transform the last build gave it, masked away from probe rays, so a ball rolling (or 64 objects pushed
    // every step, Table 3) costs no rebuild of every instance each frame.
    void syncForProbes(const render::Scene& scene) {
        if (rtcScene && scene.uid() == builtFor && builtScope == probeScope &&
            geometryHash(scene, &probeScope) == probeGeometrySignature)
            return;
        sync(scene);
    }

    // The closest hit of the ray from `origin` along `direction` within [tnear, tfar] among the instances
    // `mask` sees (hit.hit.geomID RTC_INVALID_GEOMETRY_ID: none).
    RTCRayHit intersect(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, float tnear,
                        float tfar, unsigned mask, std::uint64_t& rays) const {
        ++rays;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit hit{};
        hit.ray.org_x = origin.x(), hit.ray.org_y = origin.y(), hit.ray.org_z = origin.z();
        hit.ray.dir_x = direction.x(), hit.ray.dir_y = direction.y(), hit.ray.dir_z = direction.z();
        hit.ray.tnear = tnear;
        hit.ray.tfar = tfar;
        hit.ray.mask = mask;
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(rtcScene, &context, &hit);
        return hit;
    }

    // The first surface along a ray: its distance (infinity for none) and whether the ray meets its back
    // (the side its winding faces away from).
    float firstHit(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, unsigned mask, bool& back,
                   std::uint64_t& rays) const {
        const RTCRayHit hit =
            intersect(origin, direction, 0.0f, std::numeric_limits<float>::infinity(), mask, rays);
        back = hit.hit.geomID != RTC_INVALID_GEOMETRY_ID &&
               (shapes[hit.hit.instID[0]].normalMatrix *
                Eigen::Vector3f(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z))
                       .dot(direction) > 0.0f;
        return hit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::infinity()
                                                         : hit.ray.tfar;
    }

    // What the geometry is built from (the scene's process-unique id left out: see imageHash()), of the
    // instances `scope` sees (null: all of them).
    static std::uint64_t geometryHash(const render::Scene& scene, const ProbeScope* scope) {
        Hasher h;
        scene.forEachInstance([&](render::InstanceId, const render::Instance& instance) {
            if (!instance.visible || (scope && !scope->sees(scene, instance)))
                return;
            h.add(instance.castShadows);
            h.add(instance.mesh.index);
            h.add(instance.mesh.generation);
            h.add(scene.meshRevision(instance.mesh));
            h.matrix(instance.transform.matrix());
            for (render::MaterialId material : instance.materials) {
                h.add(material.index);
                h.add(material.generation);
            }
        });
        return h.value;
    }

    // The mesh scene of `id`, built when it is new or its revision changed.
    const MeshShape& meshShape(const render::Scene& scene, render::MeshId id) {
        std::unique_ptr<MeshShape>& entry = meshShapes[{id.index, id.generation}];
        const std::uint64_t revision = scene.meshRevision(id);
        if (entry && entry->revision == revision) {
            entry->usedBy = builds;
            return *entry;
        }
        entry = std::make_unique<MeshShape>();
        entry->revision = revision;
        entry->usedBy = builds;
        const render::MeshData& mesh = scene.mesh(id);
        entry->positions = mesh.positions;
        entry->normals = mesh.normals;
        entry->uvs = mesh.uvs;
        // The triangles the rasteriser draws: those of the submeshes, each with its material slot.
        for (std::size_t slot = 0; slot < mesh.submeshes.size(); ++slot) {
            const render::Submesh& sub = mesh.submeshes[slot];
            entry->indices.insert(entry->indices.end(), mesh.indices.begin() + sub.firstIndex,
                                  mesh.indices.begin() + sub.firstIndex + sub.indexCount / 3 * 3);
            entry->slots.resize(entry->indices.size() / 3, std::uint32_t(slot));
        }
        entry->scene = rtcNewScene(device);
        rtcSetSceneFlags(entry->scene, RTC_SCENE_FLAG_ROBUST);
        if (!entry->indices.empty()) {
            RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            SP_CHECK(geometry != nullptr, InvalidState,
                     "PathTracer: Embree could not create a geometry (error ", int(rtcGetDeviceError(device)),
                     ")");
            auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                         RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                         mesh.positions.size()));
            for (std::size_t i = 0; i < mesh.positions.size(); ++i)
                std::memcpy(vertices + 3 * i, mesh.positions[i].data(), 3 * sizeof(float));
            auto* indices = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), entry->indices.size() / 3));
            std::memcpy(indices, entry->indices.data(), entry->indices.size() * sizeof(unsigned));
            rtcCommitGeometry(geometry);
            rtcAttachGeometry(entry->scene, geometry);
            rtcReleaseGeometry(geometry);
        }
        rtcCommitScene(entry->scene);
        return *entry;
    }

    // Whether rays can be traced into an instance with `transform`: finite, each axis scaled by 1e-6 to 1e9
    // and not collapsed by shear, placed within kMaxTraceableReach, so that a ray from anywhere within reach
    // stays a valid float ray in the instance's own space. A scale of 0 or a position of 1e176 m (the RPC
    // fuzzer's) is drawn by no ray.
    static bool traceable(const Eigen::Affine3f& transform) {
        if (!transform.matrix().allFinite() ||
            transform.translation().cwiseAbs().maxCoeff() > float(kMaxTraceableReach))
            return false;
        const Eigen::Vector3f scales = transform.linear().colwise().norm();
        return scales.minCoeff() >= 1e-6f && scales.maxCoeff() <= 1e9f &&
               std::abs(transform.linear().determinant()) >= 1e-18f;
    }

    // The top level: one instance of its mesh scene per visible instance, with its transform.
    void build(const render::Scene& scene) {
        ++builds;
        if (scene.uid() != builtFor) // mesh handles and revisions are another scene's
            meshShapes.clear();
        if (rtcScene)
            rtcReleaseScene(rtcScene);
        shapes.clear();
        rtcScene = rtcNewScene(device);
        rtcSetSceneFlags(rtcScene, RTC_SCENE_FLAG_ROBUST);
        scene.forEachInstance([&](render::InstanceId, const render::Instance& instance) {
            if (!instance.visible)
                return;
            const MeshShape& mesh = meshShape(scene, instance.mesh);
            if (mesh.indices.empty())
                return;
            const Eigen::Affine3f transform = instance.transform.cast<float>();
            if (!traceable(transform))
                return; // nothing a float ray could meet (or Embree accept in the instance's space)
            RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
            SP_CHECK(geometry != nullptr, InvalidState,
                     "PathTracer: Embree could not create an instance (error ",
                     int(rtcGetDeviceError(device)), ")");
            rtcSetGeometryInstancedScene(geometry, mesh.scene);
            const Eigen::Matrix<float, 3, 4> columns = transform.matrix().topRows<3>();
            rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, columns.data());
            // Every camera ray sees the instance; shadow rays only when it casts shadows; probe rays only
            // when it is not smaller than their cutoff.
            const bool probed = probeScope.sees(scene, instance);
            rtcSetGeometryMask(geometry, kCameraRays | (instance.castShadows ? kShadowRays : 0u) |
                                             (probed ? kProbeRays : 0u) |
                                             (probed && instance.castShadows ? kProbeShadowRays : 0u));
            rtcCommitGeometry(geometry);
            rtcAttachGeometryByID(rtcScene, geometry, unsigned(shapes.size()));
            rtcReleaseGeometry(geometry);
            shapes.push_back({&mesh, transform.linear().inverse().transpose(), transform.linear(),
                              transform.translation(), instance.materials, probed, instance.castShadows});
        });
        rtcCommitScene(rtcScene);
        std::erase_if(meshShapes, [&](const auto& entry) { return entry.second->usedBy + 8 < builds; });
    }

    // The emissive triangles again when the geometry was rebuilt or a material's emission changed.
    void syncEmitters(const render::Scene& scene) {
        Hasher h;
        h.add(builds);
        for (const Shape& shape : shapes)
            for (render::MaterialId id : shape.materials)
                h.matrix(scene.material(id).emissive);
        if (h.value == emittersKey)
            return;
        emittersKey = h.value;
        emitters.clear();
        for (std::uint32_t i = 0; i < shapes.size(); ++i) {
            const Shape& shape = shapes[i];
            const MeshShape& mesh = *shape.mesh;
            for (std::size_t t = 0; t < mesh.slots.size(); ++t) {
                const Eigen::Vector3f& radiance = scene.material(shape.materials[mesh.slots[t]]).emissive;
                if (radiance.maxCoeff() <= 0.0f)
                    continue;
                auto world = [&](std::uint32_t v) {
                    return Eigen::Vector3f(shape.linear * mesh.positions[v] + shape.translation);
                };
                emitters.add(i, world(mesh.indices[3 * t]), world(mesh.indices[3 * t + 1]),
                             world(mesh.indices[3 * t + 2]), radiance);
            }
        }
    }

    // Everything the light in the scene depends on: the geometry, materials, lights and sky.
    // `probes`: what probe rays see (the instances not smaller than the cutoff).
    std::uint64_t lightingHash(const render::Scene& scene, bool probes = false) const {
        Hasher h;
        h.add(probes ? probeGeometrySignature : geometrySignature);
        for (const Shape& shape : shapes) {
            if (probes && !shape.probed)
                continue;
            for (render::MaterialId id : shape.materials) {
                const render::Material& m = scene.material(id);
                h.matrix(m.baseColor);
                h.add(m.roughness);
                h.add(m.metallic);
                h.matrix(m.emissive);
                h.add(m.textureSize);
                for (const auto& texture : {m.baseColorTexture, m.roughnessMetallicTexture, m.normalTexture})
                    if (texture) {
                        h.add(texture->index);
                        h.add(texture->generation);
                    } else {
                        h.add(~0u);
                    }
            }
        }
        // A world adds its lights again every frame, in no fixed order: the lights count as a set.
        std::uint64_t lights = 0;
        scene.forEachLight([&](render::LightId, const render::Light& light) {
            Hasher l;
            l.add(light.type);
            l.matrix(light.color);
            l.add(light.intensity);
            l.matrix(light.position);
            l.matrix(light.direction);
            l.add(light.range);
            l.add(light.innerConeDeg);
            l.add(light.outerConeDeg);
            l.add(light.castShadows);
            l.matrix(light.right);
            l.matrix(light.up);
            l.add(light.width);
            l.add(light.height);
            lights += l.value;
        });
        h.add(lights);
        h.matrix(scene.environment().ambient);
        h.matrix(scene.environment().background);
        h.add(scene.environment().map ? scene.environment().map->contentHash() : 0);
        h.matrix(scene.environment().mapScale);
        return h.value;
    }

    // Everything an image depends on: the light in the scene, the camera and the bounces.
    std::uint64_t imageHash(const render::Scene& scene, const render::Camera& camera,
                            const Settings& settings) const {
        Hasher h;
        h.add(lightingHash(scene));
        h.matrix(camera.pose.matrix());
        h.add(camera.params.width);
        h.add(camera.params.height);
        h.add(camera.params.hfovDeg);
        h.add(camera.params.nearClip);
        h.add(camera.params.farClip);
        h.add(camera.params.shadows);
        h.add(camera.params.apertureRadius);
        h.add(camera.params.focusDistance);
        h.add(settings.maxBounces);
        h.add(settings.maxPathIntensity);
        h.add(settings.approximateCaustics);
        return h.value;
    }

    bool occluded(const Eigen::Vector3f& origin, const Eigen::Vector3f& direction, float distance,
                  unsigned mask, std::uint64_t& rays) const {
        ++rays;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray{};
        ray.org_x = origin.x(), ray.org_y = origin.y(), ray.org_z = origin.z();
        ray.dir_x = direction.x(), ray.dir_y = direction.y(), ray.dir_z = direction.z();
        ray.tnear = 0.0f;
        // Short of the light itself, which may sit on a surface or inside a lamp's mesh.
        ray.tfar = std::isinf(distance) ? distance : distance * (1.0f - 1e-4f);
        ray.mask = mask;
        rtcOccluded1(rtcScene, &context, &ray);
        return ray.tfar < 0.0f;
    }

    // A surface a ray met, as shading needs it: its position, geometric normal and shading normal (both
    // facing the ray's origin: surfaces are two-sided, as in the rasteriser), material, and the material's
    // values there (textures and normal map applied).
    struct Surface {
        Eigen::Vector3f p, ng, n;
        SurfacePoint s;
        const render::Material* material = nullptr;
        std::uint32_t shape = 0; // index in `shapes`
    };
    // The surface the ray from `origin` along unit `direction` met (Embree's `hit`, found).
    Surface surfaceAt(const render::Scene& scene, const RTCRayHit& hit, const Eigen::Vector3f& origin,
                      const Eigen::Vector3f& direction) const {
        Surface out;
        out.shape = hit.hit.instID[0];
        const Shape& shape = shapes[hit.hit.instID[0]];
        const MeshShape& mesh = *shape.mesh;
        const std::uint32_t triangle = hit.hit.primID;
        const std::uint32_t i0 = mesh.indices[3 * triangle], i1 = mesh.indices[3 * triangle + 1],
                            i2 = mesh.indices[3 * triangle + 2];
        const float u = hit.hit.u, v = hit.hit.v, w = 1.0f - u - v;
        const Eigen::Vector3f p = origin + direction * hit.ray.tfar;
        out.p = p;
        const Eigen::Vector3f toViewer = -direction;
        // Two-sided, as the rasteriser: the geometric normal faces the viewer, the shading normal
        // follows.
        // Embree gives an instance's hit normal in the mesh's space.
        Eigen::Vector3f ng =
            (shape.normalMatrix * Eigen::Vector3f(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z)).normalized();
        if (ng.dot(toViewer) < 0.0f)
            ng = -ng;
        Eigen::Vector3f n =
            (shape.normalMatrix * (mesh.normals[i0] * w + mesh.normals[i1] * u + mesh.normals[i2] * v))
                .normalized();
        if (!n.allFinite())
            n = ng;
        if (n.dot(ng) < 0.0f)
            n = -n;
        const render::Material& material = scene.material(shape.materials[mesh.slots[triangle]]);
        // The texture coordinates of the hit and of the triangle's corners (for the normal map's frame):
        // the mesh's, or the object's scaled box axes' (box_uv.h), the axis the hit's normal chooses.
        Eigen::Vector2f uv, uv0, uv1, uv2;
        if (material.boxUv()) {
            const Eigen::Vector3f scale = shape.linear.colwise().norm();
            const Eigen::Vector3f normal =
                (mesh.normals[i0] * w + mesh.normals[i1] * u + mesh.normals[i2] * v).cwiseQuotient(scale);
            const float inverse = 1.0f / material.textureSize;
            uv0 = render::boxUv(mesh.positions[i0].cwiseProduct(scale), normal, inverse);
            uv1 = render::boxUv(mesh.positions[i1].cwiseProduct(scale), normal, inverse);
            uv2 = render::boxUv(mesh.positions[i2].cwiseProduct(scale), normal, inverse);
        } else {
            uv0 = mesh.uvs[i0];
            uv1 = mesh.uvs[i1];
            uv2 = mesh.uvs[i2];
        }
        uv = uv0 * w + uv1 * u + uv2 * v;
        SurfacePoint s{n, material.baseColor.head<3>(), material.roughness, material.metallic};
        if (material.baseColorTexture)
            s.base = s.base.cwiseProduct(sampleTexture(scene.texture(*material.baseColorTexture),
                                                       scene.textureEncoding(*material.baseColorTexture) ==
                                                           render::TextureEncoding::Srgb,
                                                       uv)
                                             .head<3>());
        if (material.normalTexture) { // the rasteriser's normal mapping (kMaterialChunk), per triangle
            // Its cotangent frame (Schueler 2013) from the triangle's edges where the rasteriser takes
            // screen derivatives: the same surface gradients of u and v.
            const Eigen::Vector3f e1 = shape.linear * (mesh.positions[i1] - mesh.positions[i0]),
                                  e2 = shape.linear * (mesh.positions[i2] - mesh.positions[i0]);
            const Eigen::Vector2f d1 = uv1 - uv0, d2 = uv2 - uv0;
            const Eigen::Vector3f p2perp = e2.cross(n), p1perp = n.cross(e1);
            const Eigen::Vector3f t = p2perp * d1.x() + p1perp * d2.x(),
                                  b = p2perp * d1.y() + p1perp * d2.y();
            const float orientation = n.dot(e1.cross(e2)) < 0.0f ? -1.0f : 1.0f;
            const float scale =
                orientation / std::sqrt(std::max(std::max(t.squaredNorm(), b.squaredNorm()), 1e-20f));
            const Eigen::Vector3f m =
                sampleTexture(scene.texture(*material.normalTexture), false, uv).head<3>() * 2.0f -
                Eigen::Vector3f::Ones();
            // Green points up in the image, towards decreasing v.
            const Eigen::Vector3f mapped =
                (t * (scale * m.x()) - b * (scale * m.y()) + n * m.z()).normalized();
            if (mapped.allFinite() && mapped.dot(ng) > 0.0f)
                s.n = n = mapped;
        }
        if (material.roughnessMetallicTexture) {
            const Eigen::Vector4f rm =
                sampleTexture(scene.texture(*material.roughnessMetallicTexture), false, uv);
            s.roughness *= rm.y();
            s.metallic *= rm.z();
        }
        out.ng = ng;
        out.n = n;
        out.s = s;
        out.material = &material;
        return out;
    }

    // One light-vertex connection at the surface point `above` (normals n, ng, material s, viewed from
    // `toViewer`, whose bounce draws direction l with density pdf(s, toViewer, l)): a light of `joins` drawn
    // by its power, a ray of it drawn uniformly over what it lights, and the first shadow-casting surface y
    // the ray meets; if y sees the point, `arrive(radiance, l, weight)` is given the lamp's light y reflects
    // towards it along l, and the weight (cos / density, times the multiple importance sampling weight)
    // by which the point reflects it.
    // `rayMask` and `shadowMask`: what the path's own rays and the lamps' shadow rays see (a probe's see only
    // the instances the probes see).
    template <typename Arrive>
    void joinLightVertex(const render::Scene& scene, const LightVertices& joins, PathSampler& random,
                         std::uint64_t& rays, unsigned rayMask, unsigned shadowMask,
                         const Eigen::Vector3f& above, const Eigen::Vector3f& n, const Eigen::Vector3f& ng,
                         const SurfacePoint& s, const Eigen::Vector3f& toViewer, const Settings& settings,
                         Arrive&& arrive) const {
        const float pick = random.next();
        const auto [u1, u2] = random.next2();
        const std::size_t i = std::min<std::size_t>(
            std::size_t(std::upper_bound(joins.cdf.begin(), joins.cdf.end(), pick) - joins.cdf.begin()),
            joins.cdf.size() - 1);
        if (joins.chance[i] <= 0.0f)
            return;
        const render::Light& light = *joins.lights[i];
        // Uniform over the sphere, or over a spot light's outer cone.
        const Eigen::Vector3f axis = light.type == render::LightType::Spot
                                         ? Eigen::Vector3f(light.direction.cast<float>().normalized())
                                         : Eigen::Vector3f::UnitZ();
        const float z = 1.0f - u1 * (1.0f - joins.lowestCosine[i]),
                    r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        Eigen::Vector3f t, b;
        basis(axis, t, b);
        const Eigen::Vector3f ray =
            (t * (r * std::cos(2.0f * kPi * u2)) + b * (r * std::sin(2.0f * kPi * u2)) + axis * z)
                .normalized();
        const Eigen::Vector3f from = light.position.cast<float>();
        // What the lamp's shadow rays see.
        const RTCRayHit hit =
            intersect(from, ray, 0.0f, std::numeric_limits<float>::infinity(), shadowMask, rays);
        if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            return;
        Surface y = surfaceAt(scene, hit, from, ray);
        if (settings.approximateCaustics) // as a bounce from this rough surface would have shaded it
            y.s.roughness = std::max(y.s.roughness, s.roughness);
        Eigen::Vector3f toLight;
        float lightDistance = 0.0f;
        const Eigen::Vector3f e = lightIrradiance(light, y.p, 0.5f, 0.5f, toLight, lightDistance);
        const float lit = y.n.dot(toLight), facing = y.ng.dot(toLight);
        if (lit <= 0.0f || facing <= 0.0f || e.maxCoeff() <= 0.0f)
            return;
        const Eigen::Vector3f yAbove = y.p + y.ng * (1e-4f * std::max(1.0f, y.p.cwiseAbs().maxCoeff()));
        const Eigen::Vector3f d = yAbove - above;
        const float distance2 = d.squaredNorm(), distance = std::sqrt(distance2);
        if (!(distance > 0.0f))
            return;
        const Eigen::Vector3f l = d / distance;
        const float nol = n.dot(l), cosine = -y.ng.dot(l);
        if (nol <= 0.0f || ng.dot(l) <= 0.0f || cosine <= 1e-6f ||
            occluded(above, l, distance, rayMask, rays))
            return;
        const float joined = lightVertexDensity(joins, i, -toLight, lightDistance, facing);
        const float bounced = pdf(s, toViewer, l) * cosine / distance2;
        if (!(joined > 0.0f))
            return;
        const Eigen::Vector3f reflected = evaluate(y.s, -l, toLight).cwiseProduct(e) * lit;
        // Per solid angle at this point: the area density times distance^2 / cosine at y.
        const float perSolidAngle = joined * distance2 / cosine;
        arrive(reflected, l, nol / perSolidAngle * powerHeuristic(joined, bounced));
    }

    // One path's estimate of the radiance arriving at `origin` from `direction` (a primary ray, clipped to
    // [tnear, tfar]), with its intrinsic parts (see PathSample).
    // `shadows`: lights cast shadows (a camera's bShadows, as the rasteriser's shadow maps); `missed`: what a
    // primary ray that hits nothing brings back (a camera's background, a probe's sky).
    // `probe`: a probe's path, whose rays see only the instances not smaller than the probe cutoff.
    PathSample trace(const render::Scene& scene, bool shadows, const Eigen::Vector3f& missed,
                     Eigen::Vector3f origin, Eigen::Vector3f direction, float tnear, float tfar,
                     const Settings& settings, PathSampler& random, std::uint64_t& rays, bool probe = false,
                     const LightVertices* joins = nullptr) const {
        const unsigned rayMask = probe ? kProbeRays : kCameraRays,
                       shadowMask = probe ? kProbeShadowRays : kShadowRays;
        const render::Environment& environment = scene.environment();
        const render::EnvironmentMap* map = environment.map.get();
        const bool sky = map != nullptr || environment.ambient.maxCoeff() > 0.0f;
        PathSample out;
        // Light reflected at the first surface splits by lobe. What arrives there along direction l is
        // weighted by f cos / pdf for hdr_color, by its diffuse lobe's share for diffuse_only and by a white
        // Lambertian's (cos / pi / pdf) for diffuse_illumination; `first*` hold these for the first bounce's
        // direction and `throughput` the product of the factors after it.
        Eigen::Vector3f firstTotal = Eigen::Vector3f::Ones(), firstDiffuse = Eigen::Vector3f::Zero(),
                        firstWhite = Eigen::Vector3f::Zero(), throughput = Eigen::Vector3f::Ones();
        // Radiance `x` reflected towards the camera by the first surface from direction l, whose BSDF value
        // there is `f` and diffuse share `fd`, per unit of the estimator's weight `w` (cos / pdf).
        auto reflectFirst = [&](const Eigen::Vector3f& x, const Eigen::Vector3f& f, const Eigen::Vector3f& fd,
                                float w) {
            out.hdr += f.cwiseProduct(x) * w;
            out.diffuseOnly += fd.cwiseProduct(x) * w;
            out.diffuseIllumination += x * (w / kPi);
        };
        // Radiance `x` arriving at the first surface along the first bounce's direction, after `throughput`.
        auto throughFirst = [&](const Eigen::Vector3f& x) {
            Eigen::Vector3f arriving = throughput.cwiseProduct(x);
            // Firefly control: a rare path that finds a small bright emitter, brought down to the limit in
            // proportion (its colour kept).
            if (settings.maxPathIntensity > 0.0f && arriving.maxCoeff() > settings.maxPathIntensity)
                arriving *= settings.maxPathIntensity / arriving.maxCoeff();
            out.hdr += firstTotal.cwiseProduct(arriving);
            out.diffuseOnly += firstDiffuse.cwiseProduct(arriving);
            out.diffuseIllumination += firstWhite.cwiseProduct(arriving);
        };
        float bsdfPdf = 0.0f, skyPdf = 0.0f; // of the last bounce's direction
        bool joinedFrom = false; // the last vertex drew light-vertex connections (so this one's lamps share)
        float pathRoughness = 0.0f; // the roughest lobe the path has come through (approximateCaustics)
        for (int depth = 0;; ++depth) {
            const RTCRayHit hit = intersect(origin, direction, tnear, tfar, rayMask, rays);
            if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
                if (depth == 0) { // an environment map is the background too
                    const Eigen::Vector3f background = map ? environment.radiance(direction) : missed;
                    out.hdr += background;
                    out.direct += background;
                } else if (sky) { // the BSDF's share of the sky (multiple importance sampling)
                    const float weight = powerHeuristic(bsdfPdf, skyPdf);
                    throughFirst(environment.radiance(direction) * weight);
                }
                break;
            }

            const Surface surface = surfaceAt(scene, hit, origin, direction);
            const Eigen::Vector3f p = surface.p, toViewer = -direction, ng = surface.ng;
            Eigen::Vector3f n = surface.n;
            SurfacePoint s = surface.s;
            const render::Material& material = *surface.material;
            if (settings.approximateCaustics)
                s.roughness = std::max(s.roughness, pathRoughness);
            if (depth == 0) {
                out.hdr += material.emissive; // emitted, not reflected: part of the specular residual
                out.direct += material.emissive;
                out.albedo = s.base;
                out.normal = n;
                out.depth = hit.ray.tfar;
                out.instance = hit.hit.instID[0] + 1;
            } else if (material.emissive.maxCoeff() > 0.0f) {
                // The BSDF's share of an emitter the last vertex also sampled (multiple importance sampling):
                // the density with which it would have drawn this point, per solid angle there.
                const float t = hit.ray.tfar, cosine = ng.dot(toViewer);
                const float pdfLight = emitters.pdfArea(material.emissive) * t * t / std::max(cosine, 1e-6f);
                throughFirst(material.emissive * powerHeuristic(bsdfPdf, pdfLight));
            }
            const Eigen::Vector3f fd = diffuse(s);
            // Shadow and bounce rays leave from just above the surface, on the viewer's side.
            const Eigen::Vector3f above = p + ng * (1e-4f * std::max(1.0f, p.cwiseAbs().maxCoeff()));
            // This surface's lamp light, as a bounce from the last vertex found it, is also what that
            // vertex's light-vertex connection draws: the two are weighed against each other.
            const bool shared = joinedFrom && shapes[surface.shape].castsShadows;
            const float cosine = ng.dot(toViewer), travelled = hit.ray.tfar;
            std::size_t lightIndex = 0;
            scene.forEachLight([&](render::LightId, const render::Light& light) {
                const std::size_t index = lightIndex++;
                Eigen::Vector3f l;
                float distance = 0.0f;
                std::array<float, 2> u{0.5f, 0.5f}; // a point of an area light; the others need none
                if (light.type == render::LightType::Rect)
                    u = random.next2();
                const Eigen::Vector3f e = lightIrradiance(light, p, u[0], u[1], l, distance);
                const float nol = n.dot(l);
                if (nol <= 0.0f || ng.dot(l) <= 0.0f || e.maxCoeff() <= 0.0f)
                    return;
                if (shadows && light.castShadows && occluded(above, l, distance, shadowMask, rays))
                    return;
                const Eigen::Vector3f f = evaluate(s, toViewer, l);
                if (depth == 0) {
                    reflectFirst(e, f, fd, nol);
                    out.direct += f.cwiseProduct(e) * nol;
                } else {
                    float weight = 1.0f;
                    if (shared) {
                        const float bounced = bsdfPdf * cosine / std::max(travelled * travelled, 1e-12f);
                        weight = powerHeuristic(bounced,
                                                lightVertexDensity(*joins, index, -l, distance, ng.dot(l)));
                    }
                    throughFirst(f.cwiseProduct(e) * (nol * weight));
                }
            });
            const bool last = depth >= settings.maxBounces;
            if (!emitters.empty()) {
                // One point of an emissive surface: a triangle by its power, then a point of it.
                const float pick = random.next();
                const auto [u1, u2] = random.next2();
                const EmitterSample e = emitters.sample(pick, u1, u2);
                const Eigen::Vector3f d = e.point - above;
                const float distance2 = d.squaredNorm(), distance = std::sqrt(distance2);
                const Eigen::Vector3f l = d / std::max(distance, 1e-12f);
                const float nol = n.dot(l), cosine = std::abs(e.normal.dot(l));
                if ((!probe || shapes[e.shape].probed) && nol > 0.0f && ng.dot(l) > 0.0f && cosine > 1e-6f &&
                    !occluded(above, l, distance, shadowMask, rays)) {
                    const float pdfLight = e.pdfArea * distance2 / cosine, pdfBsdf = pdf(s, toViewer, l);
                    const float weight = last ? 1.0f : powerHeuristic(pdfLight, pdfBsdf);
                    const Eigen::Vector3f f = evaluate(s, toViewer, l);
                    if (depth == 0)
                        reflectFirst(e.radiance, f, fd, nol / pdfLight * weight);
                    else
                        throughFirst(f.cwiseProduct(e.radiance) * (nol / pdfLight * weight));
                }
            }
            if (sky) {
                // A uniform sky is drawn by cosine, a map by its luminance (a bright sun in a photograph is
                // found by its rays, not by chance).
                Eigen::Vector3f l;
                float pdfSky = 0.0f;
                if (map) {
                    const auto [u1, u2] = random.next2();
                    pdfSky = map->sample(u1, u2, l);
                } else {
                    const auto [u1, u2] = random.next2();
                    l = cosineDirection(n, u1, u2);
                    pdfSky = n.dot(l) / kPi;
                }
                const float nol = n.dot(l);
                if (pdfSky > 0.0f && nol > 0.0f && ng.dot(l) > 0.0f &&
                    !occluded(above, l, std::numeric_limits<float>::infinity(), shadowMask, rays)) {
                    const float pdfBsdf = pdf(s, toViewer, l);
                    // At the last vertex no BSDF ray follows, so the sky sample takes the whole estimate.
                    const float weight = last ? 1.0f : powerHeuristic(pdfSky, pdfBsdf);
                    const Eigen::Vector3f f = evaluate(s, toViewer, l);
                    const Eigen::Vector3f arriving = environment.radiance(l);
                    if (depth == 0)
                        reflectFirst(arriving, f, fd, nol / pdfSky * weight);
                    else
                        throughFirst(f.cwiseProduct(arriving) * (nol / pdfSky * weight));
                }
            }
            // Light-vertex connections: a ray from a lamp to the first surface it lights (a hot spot on the
            // ceiling over a bare bulb, most of a room's light, is found wherever the lamp's rays are),
            // joined to this vertex: that surface's reflection of the lamp, arriving here. Weighed against
            // the bounce below finding the same surface (and its lamp sample there).
            const bool joinsHere =
                joins && !last && shadows && !joins->empty() && s.roughness >= kJoinedRoughness;
            if (joinsHere)
                joinLightVertex(scene, *joins, random, rays, rayMask, shadowMask, above, n, ng, s, toViewer,
                                settings,
                                [&](const Eigen::Vector3f& arriving, const Eigen::Vector3f& l, float weight) {
                                    const Eigen::Vector3f f = evaluate(s, toViewer, l);
                                    if (depth == 0)
                                        reflectFirst(arriving, f, fd, weight);
                                    else
                                        throughFirst(f.cwiseProduct(arriving) * weight);
                                });
            joinedFrom = joinsHere;
            if (last)
                break;

            Eigen::Vector3f l;
            const float lobe = random.next();
            const auto [u1, u2] = random.next2();
            if (!sample(s, toViewer, lobe, u1, u2, l) || ng.dot(l) <= 0.0f)
                break;
            pathRoughness = std::max(pathRoughness, sampledRoughness(s, lobe));
            bsdfPdf = pdf(s, toViewer, l);
            if (!(bsdfPdf > 0.0f))
                break;
            const float nol = n.dot(l);
            skyPdf = map ? map->pdf(l) : nol / kPi;
            if (depth == 0) {
                firstTotal = evaluate(s, toViewer, l) * (nol / bsdfPdf);
                firstDiffuse = fd * (nol / bsdfPdf);
                firstWhite = Eigen::Vector3f::Constant(nol / (kPi * bsdfPdf));
            } else {
                throughput = throughput.cwiseProduct(evaluate(s, toViewer, l)) * (nol / bsdfPdf);
            }
            // What the path can still add, through the largest of its weights (a white surface's included).
            const float strength = std::max(firstTotal.cwiseProduct(throughput).maxCoeff(),
                                            firstWhite.cwiseProduct(throughput).maxCoeff());
            if (depth >= 2) { // Russian roulette, keeping the estimate unbiased
                const float survive = std::clamp(strength, 0.05f, 1.0f);
                if (random.next() >= survive)
                    break;
                throughput /= survive;
            }
            if (!throughput.allFinite() || !(strength > 0.0f))
                break;
            origin = above;
            direction = l;
            tnear = 0.0f;
            tfar = std::numeric_limits<float>::infinity();
        }
        return out;
    }
};

bool ProbeScope::sees(const render::Scene& scene, const render::Instance& instance) const {
    if (!instance.affectIndirectLighting)
        return false;
    if (ignoreBelowRadius > 0.0) {
        Eigen::Vector3d centre;
        double radius = 0.0;
        scene.boundingSphere(instance, centre, radius);
        if (radius < ignoreBelowRadius)
            return false;
    }
    return within.isEmpty() || within.intersects(scene.boundingBox(instance));
}

PathTracer::PathTracer() : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice(nullptr);
    SP_CHECK(impl_->device != nullptr, InvalidState, "PathTracer: Embree could not start (error ",
             int(rtcGetDeviceError(nullptr)), ")");
    rtcSetDeviceErrorFunction(
        impl_->device,
        [](void*, RTCError code, const char* message) {
            SP_LOG("pathtrace: Embree error ", int(code), ": ", message ? message : "");
        },
        nullptr);
}

PathTracer::~PathTracer() = default;

std::uint64_t PathTracer::builds() const {
    return impl_->builds;
}

void PathTracer::render(const render::Scene& scene, const render::Camera& camera, const Settings& settings,
                        Accumulation& image) {
    camera.params.validate("PathTracer::render");
    settings.validate("PathTracer::render");
    Impl& impl = *impl_;
    impl.sync(scene);
    impl.syncEmitters(scene);
    // What the image depends on; it also seeds the random numbers, so it leaves out the scene's
    // process-unique id: the same scene and view give the same image in every run.
    const std::uint64_t signature = impl.imageHash(scene, camera, settings);
    const int width = camera.params.width, height = camera.params.height;
    if (image.signature != signature || image.width != width || image.height != height || image.sum.empty()) {
        image.width = width;
        image.height = height;
        image.sum.assign(std::size_t(width) * height * 3, 0.0);
        image.diffuseOnlySum.assign(image.sum.size(), 0.0);
        image.diffuseIlluminationSum.assign(image.sum.size(), 0.0);
        image.albedoSum.assign(image.sum.size(), 0.0);
        image.directSum.assign(image.sum.size(), 0.0);
        image.indirectSquareSum.assign(std::size_t(width) * height, 0.0);
        image.normalSum.assign(image.sum.size(), 0.0);
        image.depthSum.assign(std::size_t(width) * height, 0.0);
        image.ids.assign(std::size_t(width) * height, 0);
        image.samples = 0;
        image.signature = signature;
    }

    const double focal = camera.focalLengthPixels();
    const float aperture = float(camera.params.apertureRadius), focus = float(camera.params.focusDistance);
    const Eigen::Matrix3f rotation = camera.pose.linear().cast<float>();
    const Eigen::Vector3f eye = camera.pose.translation().cast<float>();
    const std::uint64_t firstSample = image.samples;
    std::atomic<int> nextRow{0}, rowsDone{0};
    std::atomic<std::uint64_t> rays{0};
    const LightVertices joins = settings.lightConnections ? lightVertices(scene) : LightVertices{};
    // Reported by the calling thread only (Progress is not shared between threads).
    base::Progress progress("path tracing " + std::to_string(width) + "x" + std::to_string(height) + ", " +
                                std::to_string(settings.samplesPerPixel) + " samples per pixel",
                            double(height));
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<bool> stopped{false};
    auto work = [&] {
        std::uint64_t traced = 0;
        const bool reports = std::this_thread::get_id() == caller;
        for (int y = nextRow++; y < height && !stopped; y = nextRow++, ++rowsDone) {
            for (int x = 0; x < width; ++x) {
                // Each pixel: a row of a frame at thousands of samples per pixel takes seconds, and a stop
                // (base::requestStop()) must end the frame within one; the caller's reports let the host
                // answer others meanwhile (base::setBusyHook()).
                if (base::stopRequested()) {
                    stopped = true;
                    break;
                }
                if (reports)
                    progress.set(double(rowsDone.load()) + double(x) / double(width));
                const std::size_t at = (std::size_t(y) * width + x) * 3;
                double* sum = &image.sum[at];
                double* diffuseOnly = &image.diffuseOnlySum[at];
                double* diffuseIllumination = &image.diffuseIlluminationSum[at];
                for (int k = 0; k < settings.samplesPerPixel; ++k) {
                    const std::uint64_t index = firstSample + std::uint64_t(k);
                    PathSampler random(signature ^
                                           (std::uint64_t(y) * std::uint64_t(width) + std::uint64_t(x)) *
                                               0x9E3779B97F4A7C15ull,
                                       index);
                    // Camera body frame: +X forward, +Y left, +Z up; pixel (u right, v down).
                    const auto [du, dv] = random.next2();
                    const float u = float(x) + du, v = float(y) + dv;
                    const Eigen::Vector3f local(float(focal), -(u - 0.5f * float(width)),
                                                -(v - 0.5f * float(height)));
                    // A thin lens: rays from a point of the aperture disc through the pixel's point on the
                    // focal plane (a pinhole when the aperture is 0).
                    const Eigen::Vector3f lens =
                        aperture > 0.0f ? lensPoint(random, aperture) : Eigen::Vector3f::Zero();
                    const Eigen::Vector3f toFocus = local * (focus / local.x()) - lens;
                    const Eigen::Vector3f direction = (rotation * toFocus).normalized();
                    const float axial = toFocus.x() / toFocus.norm(); // cosine to the optical axis
                    const PathSample path = impl.trace(
                        scene, camera.params.shadows, scene.environment().background, eye + rotation * lens,
                        direction, float(camera.params.nearClip) / axial,
                        float(camera.params.farClip) / axial, settings, random, traced, false, &joins);
                    if (path.hdr.allFinite() && path.diffuseOnly.allFinite() &&
                        path.diffuseIllumination.allFinite())
                        for (int c = 0; c < 3; ++c) {
                            sum[c] += path.hdr[c];
                            diffuseOnly[c] += path.diffuseOnly[c];
                            diffuseIllumination[c] += path.diffuseIllumination[c];
                        }
                    for (int c = 0; c < 3; ++c) {
                        image.albedoSum[at + std::size_t(c)] += path.albedo[c];
                        image.normalSum[at + std::size_t(c)] += path.normal[c];
                    }
                    if (path.direct.allFinite() && path.hdr.allFinite()) {
                        for (int c = 0; c < 3; ++c)
                            image.directSum[at + std::size_t(c)] += path.direct[c];
                        const double l =
                            render::luminance(Eigen::Vector3d((path.hdr - path.direct).cast<double>()));
                        image.indirectSquareSum[at / 3] += l * l;
                    }
                    image.depthSum[at / 3] += path.depth;
                    if (index == 0)
                        image.ids[at / 3] = path.instance;
                }
            }
        }
        rays += traced;
    };
    onEveryThread(work);
    if (stopped) {
        // Some pixels have this call's samples and others not: the accumulation starts again next time.
        image.sum.clear();
        image.samples = 0;
        SP_THROW(InvalidState, "PathTracer::render(): stopped before the frame was traced: the process is "
                               "shutting down");
    }
    progress.set(double(height));
    image.samples += std::uint64_t(settings.samplesPerPixel);
    impl.lastRays = rays;
}

std::uint64_t PathTracer::lightingSignature(const render::Scene& scene, const ProbeScope& scope) {
    impl_->probeScope = scope;
    impl_->syncForProbes(scene);
    return impl_->lightingHash(scene, true);
}

void PathTracer::lightProbes(const render::Scene& scene, render::IrradianceVolume& volume,
                             std::span<const std::size_t> probes, int rays, const Settings& settings,
                             const ProbeScope& scope) {
    SP_CHECK(rays >= 1 && rays <= 65536, InvalidArgument, "PathTracer::lightProbes(): rays ", rays,
             " is out of range [1, 65536]");
    settings.validate("PathTracer::lightProbes");
    for (std::size_t index : probes)
        SP_CHECK(index < volume.probes.size(), InvalidArgument, "PathTracer::lightProbes(): probe ", index,
                 " is not in a volume of ", volume.probes.size());
    Impl& impl = *impl_;
    impl.probeScope = scope;
    impl.syncForProbes(scene);
    impl.syncEmitters(scene);
    const std::uint64_t signature = impl.lightingHash(scene, true);
    const Eigen::Vector3f sky = scene.environment().ambient;
    const float spacing = float(volume.spacing);
    // The lamps' hot spots reach the probes through light-vertex connections too: found by bounce rays alone,
    // each probe's few hits of a ceiling's hot spot left it noise of its own, blotches a few probes wide.
    const LightVertices joins = settings.lightConnections ? lightVertices(scene) : LightVertices{};
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> traced{0};
    auto work = [&] {
        std::uint64_t count = 0;
        for (std::size_t k = next++; k < probes.size(); k = next++) {
            const std::size_t index = probes[k];
            const int x = int(index % std::size_t(volume.counts.x()));
            const int y = int(index / std::size_t(volume.counts.x()) % std::size_t(volume.counts.y()));
            const int z = int(index / (std::size_t(volume.counts.x()) * std::size_t(volume.counts.y())));
            const Eigen::Vector3f origin = volume.position(x, y, z).cast<float>();
            const std::uint64_t seed = signature ^ (std::uint64_t(index) * 0x9E3779B97F4A7C15ull);
            // Directions on a spherical Fibonacci lattice (even over the sphere), turned by a random angle
            // per probe so that neighbouring probes do not share the lattice's pattern.
            const float turn = 2.0f * kPi * PathSampler(~seed, 0).next();
            Eigen::Vector3f constant = Eigen::Vector3f::Zero();
            Eigen::Matrix3f linear = Eigen::Matrix3f::Zero();
            int backs = 0;
            for (int i = 0; i < rays; ++i) {
                const float cz = 1.0f - (2.0f * float(i) + 1.0f) / float(rays);
                const float r = std::sqrt(std::max(0.0f, 1.0f - cz * cz));
                const float phi = turn + float(i) * 2.39996323f; // the golden angle
                const Eigen::Vector3f direction(r * std::cos(phi), r * std::sin(phi), cz);
                bool back = false;
                impl.firstHit(origin, direction, kProbeRays, back, count);
                backs += back ? 1 : 0;
                // The rays are the probe's samples: what each draws after its first hit is stratified over
                // them.
                PathSampler random(seed, std::uint64_t(i));
                const PathSample path =
                    impl.trace(scene, true, sky, origin, direction, 0.0f,
                               std::numeric_limits<float>::infinity(), settings, random, count, true, &joins);
                if (!path.hdr.allFinite())
                    continue;
                // Bands 0 and 1 of the radiance, turned into those of the irradiance over pi (Ramamoorthi and
                // Hanrahan 2001: A0 = pi, A1 = 2 pi / 3): the mean radiance, and 2 x its first moment.
                constant += path.hdr;
                linear += 2.0f * path.hdr * direction.transpose();
            }
            render::IrradianceProbe& probe = volume.probes[index];
            probe.constant = constant / float(rays);
            probe.linear = linear / float(rays);
            const bool inside = 4 * backs > rays;
            for (int axis = 0; axis < 6; ++axis) {
                Eigen::Vector3f direction = Eigen::Vector3f::Zero();
                direction[axis / 2] = axis % 2 == 0 ? -1.0f : 1.0f;
                bool back = false;
                const float distance = impl.firstHit(origin, direction, kProbeRays, back, count) / spacing;
                probe.freeDistance[std::size_t(axis)] =
                    inside ? 0.0f : std::min(distance, render::IrradianceVolume::kMaxFreeDistance);
            }
        }
        traced += count;
    };
    onEveryThread(work);
    impl.lastRays = traced;
}

std::uint64_t PathTracer::lastRays() const {
    return impl_->lastRays;
}

} // namespace sp::pathtrace
