// spear_pathtrace_bench: the path tracer's throughput on a ground plane with N boxes and spheres, a sun and
// a sky, against the floor of Embree's own rtcIntersect1 loop over the same camera rays and triangles.
//
//   spear_pathtrace_bench [--boxes N] [--width W] [--height H] [--spp S] [--bounces B]
//
// Rows: the floor (primary rays only, no shading), the path tracer with primary rays only (no lights, no
// sky, 0 bounces: intersection plus shading set-up), and full paths (the sun's shadow rays, sky samples and
// B bounces). Mrays/s counts closest-hit and occlusion rays alike; every row runs on all hardware threads.

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "core/pathtrace/path_tracer.h"
#include "core/render/primitives.h"
#include "core/render/scene.h"

namespace {

using namespace sp::render;

void buildScene(Scene& scene, int boxes) {
    const MaterialId ground = scene.addMaterial({});
    scene.addInstance({scene.addMesh(primitives::plane(40, 40)), {ground}, {1}});
    const MeshId box = scene.addMesh(primitives::box({0.6f, 0.6f, 0.6f}));
    const MeshId ball = scene.addMesh(primitives::sphere(0.35f, 48, 24));
    const int side = std::max(1, int(std::ceil(std::sqrt(double(boxes)))));
    for (int i = 0; i < boxes; ++i) {
        Material m;
        m.baseColor = {0.2f + 0.6f * float((i * 37) % 11) / 10.0f, 0.2f + 0.6f * float((i * 17) % 7) / 6.0f,
                       0.2f + 0.6f * float((i * 53) % 5) / 4.0f, 1.0f};
        m.roughness = 0.2f + 0.7f * float(i % 4) / 3.0f;
        m.metallic = i % 5 == 0 ? 1.0f : 0.0f;
        Instance instance{i % 2 ? ball : box, {scene.addMaterial(m)}, {std::uint32_t(2 + i)}};
        instance.transform =
            Eigen::Translation3d(1.2 * (i % side) - 0.6 * side, 1.2 * (i / side) - 0.6 * side, 0.35);
        scene.addInstance(instance);
    }
    Light sun;
    sun.direction = Eigen::Vector3d(-0.5, -0.3, -1.0);
    sun.intensity = 3.0f;
    scene.addLight(sun);
    scene.setEnvironment({{0.3f, 0.35f, 0.45f}, {0.3f, 0.35f, 0.45f}});
}

Camera makeCamera(int width, int height, int boxes) {
    const double extent = 0.6 * std::ceil(std::sqrt(double(boxes))) + 2.0;
    Camera camera;
    const Eigen::Vector3d position(-1.4 * extent, -1.1 * extent, 0.9 * extent);
    const Eigen::Vector3d x = (Eigen::Vector3d(0, 0, 0) - position).normalized();
    const Eigen::Vector3d y = Eigen::Vector3d::UnitZ().cross(x).normalized();
    camera.pose.linear() << x, y, x.cross(y);
    camera.pose.translation() = position;
    camera.params.width = width;
    camera.params.height = height;
    camera.params.hfovDeg = 60.0;
    return camera;
}

double seconds(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The floor: the scene's triangles in one Embree scene, and `spp` jittered primary rays per pixel traced with
// rtcIntersect1 on every hardware thread, nothing else. Returns rays per second.
double embreeFloor(const Scene& scene, const Camera& camera, int spp) {
    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene rtcScene = rtcNewScene(device);
    scene.forEachInstance([&](InstanceId, const Instance& instance) {
        const MeshData& mesh = scene.mesh(instance.mesh);
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                     RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                     mesh.positions.size()));
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const Eigen::Vector3f p = instance.transform.cast<float>() * mesh.positions[i];
            std::memcpy(vertices + 3 * i, p.data(), 3 * sizeof(float));
        }
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                       RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                                       mesh.indices.size() / 3));
        std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(rtcScene, geometry);
        rtcReleaseGeometry(geometry);
    });
    rtcCommitScene(rtcScene);

    const int width = camera.params.width, height = camera.params.height;
    const float focal = float(camera.focalLengthPixels());
    const Eigen::Matrix3f rotation = camera.pose.linear().cast<float>();
    const Eigen::Vector3f eye = camera.pose.translation().cast<float>();
    std::atomic<int> nextRow{0};
    std::atomic<unsigned> hits{0};
    auto work = [&] {
        unsigned found = 0;
        std::uint32_t random = 12345;
        for (int y = nextRow++; y < height; y = nextRow++)
            for (int x = 0; x < width; ++x)
                for (int k = 0; k < spp; ++k) {
                    random = random * 1664525u + 1013904223u;
                    const float jitter = float(random >> 8) * (1.0f / 16777216.0f);
                    const Eigen::Vector3f direction =
                        (rotation * Eigen::Vector3f(focal, -(float(x) + jitter - 0.5f * float(width)),
                                                    -(float(y) + jitter - 0.5f * float(height))))
                            .normalized();
                    RTCIntersectContext context;
                    rtcInitIntersectContext(&context);
                    RTCRayHit hit{};
                    hit.ray.org_x = eye.x(), hit.ray.org_y = eye.y(), hit.ray.org_z = eye.z();
                    hit.ray.dir_x = direction.x(), hit.ray.dir_y = direction.y(),
                    hit.ray.dir_z = direction.z();
                    hit.ray.tfar = 1e30f;
                    hit.ray.mask = ~0u;
                    hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rtcIntersect1(rtcScene, &context, &hit);
                    found += hit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                }
        hits += found;
    };
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < std::max(1u, std::thread::hardware_concurrency()); ++t)
        pool.emplace_back(work);
    work();
    for (std::thread& thread : pool)
        thread.join();
    const double elapsed = seconds(start);
    rtcReleaseScene(rtcScene);
    rtcReleaseDevice(device);
    return double(width) * height * spp / elapsed;
}

} // namespace

int main(int argc, char** argv) {
    int boxes = 64, width = 640, height = 480, spp = 16, bounces = 4;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i];
        const int value = std::atoi(argv[i + 1]);
        if (flag == "--boxes")
            boxes = value;
        else if (flag == "--width")
            width = value;
        else if (flag == "--height")
            height = value;
        else if (flag == "--spp")
            spp = value;
        else if (flag == "--bounces")
            bounces = value;
        else {
            std::fprintf(stderr, "usage: %s [--boxes N] [--width W] [--height H] [--spp S] [--bounces B]\n",
                         argv[0]);
            return 2;
        }
    }
    Scene scene;
    buildScene(scene, boxes);
    const Camera camera = makeCamera(width, height, boxes);
    std::printf(
        "scene: ground, %d boxes and spheres, a sun and a sky; %dx%d, %d samples per pixel, %u threads\n",
        boxes, width, height, spp, std::max(1u, std::thread::hardware_concurrency()));

    const double floor = embreeFloor(scene, camera, spp);

    sp::pathtrace::PathTracer tracer;
    sp::pathtrace::Accumulation warm;
    tracer.render(scene, camera, {1, 0}, warm); // builds the geometry outside the timings

    Scene primaryOnly; // the same geometry without lights or sky: primary rays and shading set-up only
    buildScene(primaryOnly, boxes);
    primaryOnly.forEachLight([&](LightId id, const Light&) { primaryOnly.removeLight(id); });
    primaryOnly.setEnvironment({{0.0f, 0.0f, 0.0f}, {0.3f, 0.35f, 0.45f}});
    sp::pathtrace::Accumulation primaryImage;
    tracer.render(primaryOnly, camera, {1, 0}, primaryImage);
    auto start = std::chrono::steady_clock::now();
    tracer.render(primaryOnly, camera, {spp, 0}, primaryImage);
    const double primary = double(tracer.lastRays()) / seconds(start);

    sp::pathtrace::Accumulation image;
    start = std::chrono::steady_clock::now();
    tracer.render(scene, camera, {spp, bounces}, image);
    const double elapsed = seconds(start);
    const double full = double(tracer.lastRays()) / elapsed;
    const double samples = double(width) * height * spp / elapsed;

    std::printf("%-52s %10s %8s\n", "", "Mrays/s", "/ floor");
    std::printf("%-52s %10.2f %8.2f\n", "Embree rtcIntersect1 loop, primary rays (floor)", floor / 1e6, 1.0);
    std::printf("%-52s %10.2f %8.2f\n", "path tracer, primary rays only", primary / 1e6, primary / floor);
    char label[96];
    std::snprintf(label, sizeof label, "path tracer, full paths (%d bounces, NEE, MIS)", bounces);
    std::printf("%-52s %10.2f %8.2f\n", label, full / 1e6, full / floor);
    std::printf("full paths: %.2f Msamples/s, %.1f rays per sample, %.2f s for %d spp\n", samples / 1e6,
                double(tracer.lastRays()) / (double(width) * height * spp), elapsed, spp);
    return 0;
}
