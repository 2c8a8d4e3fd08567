// spear_render_bench: ms/frame of submit + read at 256x256 and 1920x1080, for final_color only, for
// every modality and for any further sets named on the command line, per latency mode, on a ground plane
// with N boxes, a shadowed sun and a spot light.
//
//   spear_render_bench [--boxes N] [--frames F] [--shadows RES] [--png DIR] [--ids compute|driver]
//                      [--constant-slots N] [--readback staged|direct] [--copy-threads N]
//                      [--sizes WxH,...] [--views N] [--only-given] [--modalities a,b,...]...
//                      [--textured base|all] [--spheres SEGMENTS] [--no-lods] [--point-lights N] [--gi]
//   (--shadows 0: off; each --modalities adds one set, e.g. final_color,depth,normal,object_ids, and
//   --only-given times those alone; --views N renders a rig of N views 0.3 m apart, submitted together
//   and read one after another; --readback: how latency 0 reads a large view, default the renderer's
//   choice for the device (Renderer::stagedReadback()), --copy-threads the threads its copy is split across;
//   --ids: how object and material ids are read back, default the renderer's choice for the device;
//   --constant-slots: flat varyings for the view's constants, 0 to read them all from the uniform buffer,
//   default the renderer's choice: see Renderer::constantSlots(); --textured: every box's base colour, and
//   with `all` its roughness and metallic too, multiplied by a checker texture; --spheres: the objects are
//   spheres of SEGMENTS segments around, SEGMENTS^2 triangles each, instead of boxes, with the levels of
//   detail an imported mesh gets unless --no-lods; --point-lights: N unshadowed point lights more; --gi: an
//   irradiance volume of 24 x 24 x 4 probes over the ground, of varied values, blended by the shading: its
//   cost alone, no probe lighting)
//
// --png writes the 256x256 and 1920x1080 final_color images of the scene, to look at.

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/render/gl_context.h"
#include "core/render/image_buffer.h"
#include "core/render/mesh_lods.h"
#include "core/render/primitives.h"
#include "core/render/render_target.h"
#include "core/render/renderer.h"
#include "core/render/scene.h"
#include "core/render/texture_image.h"

namespace {

using namespace sp::render;

// A width x width checker of two grey levels (`dark` and 255), 8 squares a side.
TextureImage checker(int width, std::uint8_t dark) {
    std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(width) * 4);
    for (int y = 0; y < width; ++y)
        for (int x = 0; x < width; ++x) {
            const std::uint8_t level = ((x * 8 / width) + (y * 8 / width)) % 2 == 0 ? dark : 255;
            std::uint8_t* texel = rgba.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
            texel[0] = texel[1] = texel[2] = level;
            texel[3] = 255;
        }
    return TextureImage::fromPixels(width, width, std::move(rgba));
}

// `textured`: "" (flat materials), "base" (each box's base colour times a checker) or "all" (also its
// roughness and metallic, glTF's green and blue channels).
// `sphereSegments` > 0: the objects are spheres of that many segments around (and half as many rings), a
// scene of finely tessellated meshes, instead of boxes.
void buildScene(Scene& scene, int boxes, const std::string& textured, int sphereSegments, bool lods,
                int pointLights) {
    MeshId ground = scene.addMesh(primitives::plane(40, 40));
    std::optional<TextureId> baseTexture, roughnessMetallicTexture;
    if (!textured.empty())
        baseTexture = scene.addTexture(checker(64, 96));
    if (textured == "all")
        roughnessMetallicTexture = scene.addTexture(checker(64, 128), TextureEncoding::Linear);
    MeshId box = scene.addMesh(
        sphereSegments > 0 ? primitives::sphere(0.35f, sphereSegments, std::max(2, sphereSegments / 2))
                           : primitives::box({0.6f, 0.6f, 0.6f}));
    // The levels of detail an imported mesh gets (mesh_lods.h), unless --no-lods.
    if (lods) {
        std::vector<MeshLod> levels;
        for (auto& [level, error] : simplifiedLods(scene.mesh(box)))
            levels.push_back({scene.addMesh(std::move(level)), error});
        scene.setMeshLods(box, std::move(levels));
    }
    Material groundMaterial;
    groundMaterial.baseColor = {0.55f, 0.55f, 0.5f, 1.0f};
    groundMaterial.roughness = 0.9f;
    scene.addInstance({ground, {scene.addMaterial(groundMaterial)}, {1}});
    const int side = std::max(1, int(std::ceil(std::sqrt(double(boxes)))));
    for (int i = 0; i < boxes; ++i) {
        Material m;
        m.baseColor = {0.2f + 0.6f * float((i * 37) % 11) / 10.0f, 0.2f + 0.6f * float((i * 17) % 7) / 6.0f,
                       0.2f + 0.6f * float((i * 53) % 5) / 4.0f, 1.0f};
        m.roughness = 0.2f + 0.7f * float(i % 4) / 3.0f;
        m.metallic = i % 5 == 0 ? 1.0f : 0.0f;
        m.baseColorTexture = baseTexture;
        m.roughnessMetallicTexture = roughnessMetallicTexture;
        Instance instance{box, {scene.addMaterial(m)}, {std::uint32_t(2 + i)}};
        instance.transform = Eigen::Translation3d(1.2 * (i % side) - 0.6 * side,
                                                  1.2 * (i / side) - 0.6 * side, 0.3 + 0.4 * (i % 3)) *
                             Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitZ());
        scene.addInstance(instance);
    }
    Light sun;
    sun.direction = Eigen::Vector3d(-0.5, -0.3, -1.0);
    sun.intensity = 3.0f;
    scene.addLight(sun);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = Eigen::Vector3d(0, 0, 6);
    spot.direction = Eigen::Vector3d(0.2, 0.1, -1);
    spot.intensity = 30.0f;
    scene.addLight(spot);
    // --point-lights: unshadowed point lights of 8 m range in a ring 3 m up.
    for (int i = 0; i < pointLights; ++i) {
        Light point;
        point.type = LightType::Point;
        const double angle = 2.0 * M_PI * i / pointLights;
        point.position = Eigen::Vector3d(4.0 * std::cos(angle), 4.0 * std::sin(angle), 3.0);
        point.intensity = 8.0f;
        point.range = 8.0f;
        point.castShadows = false;
        scene.addLight(point);
    }
    scene.setEnvironment({{0.1f, 0.12f, 0.15f}, {0.3f, 0.35f, 0.45f}});
}

// The items of "a,b,c".
std::vector<std::string> commaSeparated(const std::string& list) {
    std::vector<std::string> items;
    for (std::string rest = list; !rest.empty();) {
        const std::size_t comma = rest.find(',');
        items.push_back(rest.substr(0, comma));
        rest = comma == std::string::npos ? std::string() : rest.substr(comma + 1);
    }
    return items;
}

Camera makeCamera(int width, int height, int boxes, int shadowResolution) {
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
    camera.params.shadows = shadowResolution > 0;
    camera.params.shadowResolution = shadowResolution > 0 ? shadowResolution : 1024;
    return camera;
}

} // namespace

int main(int argc, char** argv) {
    int boxes = 64, frames = 10, shadows = 2048, constantSlots = -1, copyThreads = 0, views = 1, spheres = 0,
        pointLights = 0;
    bool onlyGiven = false, lods = true, gi = false;
    std::string pngDir, ids, readback, textured, sizesArg = "256x256,1920x1080";
    // The sets timed: a label and the modalities.
    std::vector<std::pair<std::string, ModalitySet>> sets = {
        {"final_color", ModalitySet{Modality::FinalColor}}, {"all (14)", ModalitySet::all()}};
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--boxes") && i + 1 < argc)
            boxes = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--shadows") && i + 1 < argc)
            shadows = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--png") && i + 1 < argc)
            pngDir = argv[++i];
        else if (!std::strcmp(argv[i], "--ids") && i + 1 < argc &&
                 (!std::strcmp(argv[i + 1], "compute") || !std::strcmp(argv[i + 1], "driver")))
            ids = argv[++i];
        else if (!std::strcmp(argv[i], "--point-lights") && i + 1 < argc)
            pointLights = std::max(0, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--gi"))
            gi = true;
        else if (!std::strcmp(argv[i], "--no-lods"))
            lods = false;
        else if (!std::strcmp(argv[i], "--spheres") && i + 1 < argc)
            spheres = std::max(3, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--textured") && i + 1 < argc &&
                 (!std::strcmp(argv[i + 1], "base") || !std::strcmp(argv[i + 1], "all")))
            textured = argv[++i];
        else if (!std::strcmp(argv[i], "--constant-slots") && i + 1 < argc)
            constantSlots = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--readback") && i + 1 < argc &&
                 (!std::strcmp(argv[i + 1], "staged") || !std::strcmp(argv[i + 1], "direct")))
            readback = argv[++i];
        else if (!std::strcmp(argv[i], "--copy-threads") && i + 1 < argc)
            copyThreads = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc)
            sizesArg = argv[++i];
        else if (!std::strcmp(argv[i], "--views") && i + 1 < argc)
            views = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--only-given"))
            onlyGiven = true;
        else if (!std::strcmp(argv[i], "--modalities") && i + 1 < argc) {
            const std::string list = argv[++i];
            const ModalitySet set = ModalitySet::fromNames(commaSeparated(list)); // throws on an unknown name
            sets.emplace_back(list, set);
        } else {
            std::fprintf(
                stderr,
                "usage: %s [--boxes N] [--frames F] [--shadows RES] [--png DIR] [--ids compute|driver] "
                "[--constant-slots N] [--readback staged|direct] [--copy-threads N] [--sizes WxH,...] "
                "[--views N] [--only-given] [--modalities a,b,...] [--textured base|all] [--spheres "
                "SEGMENTS] [--no-lods] [--point-lights N]\n",
                argv[0]);
            return 2;
        }
    }
    if (onlyGiven)
        sets.erase(sets.begin(), sets.begin() + 2);
    std::vector<std::pair<int, int>> sizes;
    for (const std::string& size : commaSeparated(sizesArg)) {
        int width = 0, height = 0;
        if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width <= 0 || height <= 0) {
            std::fprintf(stderr, "%s: --sizes wants WxH[,WxH...], got '%s'\n", argv[0], size.c_str());
            return 2;
        }
        sizes.emplace_back(width, height);
    }
    GlContext context;
    Renderer renderer(context);
    if (!ids.empty())
        renderer.setPackIdsOnGpu(ids == "compute");
    if (constantSlots >= 0)
        renderer.setConstantSlots(constantSlots);
    if (!readback.empty())
        renderer.setStagedReadback(readback == "staged");
    if (copyThreads > 0)
        renderer.setReadbackThreads(copyThreads);
    Scene scene;
    buildScene(scene, boxes, textured, spheres, lods, pointLights);
    if (gi) {
        auto volume = std::make_shared<IrradianceVolume>();
        volume->counts = {24, 24, 4};
        volume->spacing = 40.0 / 23.0;
        volume->origin = {-20.0, -20.0, -0.3};
        volume->probes.resize(std::size_t(volume->counts.prod()));
        for (std::size_t i = 0; i < volume->probes.size(); ++i) {
            IrradianceProbe& probe = volume->probes[i];
            probe.constant = Eigen::Vector3f(0.2f + 0.01f * float(i % 7), 0.2f, 0.25f);
            probe.linear.col(2) = Eigen::Vector3f::Constant(0.05f);
            probe.freeDistance.fill(i % 5 == 0 ? 0.5f : IrradianceVolume::kMaxFreeDistance);
        }
        scene.setIrradianceVolume(std::move(volume));
    }
    std::printf(
        "device: %s (%s), %d boxes, shadow maps %d, ids read by %s, %d constant slots, latency-0 readback "
        "%s, copies on %d thread(s), %d view(s), %d timed frames after 3 warm-up frames%s\n",
        context.report().renderer.c_str(), context.report().kind.c_str(), boxes, shadows,
        renderer.packIdsOnGpu() ? "compute" : "driver", renderer.constantSlots(),
        renderer.stagedReadback() ? "staged" : "direct", renderer.readbackThreads(), views, frames,
        textured.empty()     ? ""
        : textured == "base" ? ", boxes with base-colour textures"
                             : ", boxes with base-colour and roughness-metallic textures");
    std::printf(
        "%-10s %-12s %-8s %10s   per pass, ms/frame: shadow surface lighting readback (GL timer / CPU)\n",
        "size", "modalities", "latency", "ms/frame");
    for (auto [width, height] : sizes) {
        // The views of a rig: the first at the bench's camera, the others 0.3 m apart to its right.
        std::vector<Camera> cameras(std::size_t(views), makeCamera(width, height, boxes, shadows));
        for (std::size_t v = 1; v < cameras.size(); ++v)
            cameras[v].pose.translation() -= 0.3 * double(v) * cameras[v].pose.linear().col(1);
        for (const auto& [label, modalities] : sets) {
            for (int latency = 0; latency <= RenderTarget::kMaxLatency; ++latency) {
                std::vector<std::unique_ptr<RenderTarget>> targets;
                std::vector<RenderTarget::Submission> submissions;
                for (const Camera& camera : cameras) {
                    targets.push_back(std::make_unique<RenderTarget>(renderer, modalities, latency));
                    submissions.push_back({targets.back().get(), &scene, &camera});
                }
                std::vector<Frame> viewFrames(cameras.size());
                // One frame of the rig: every view submitted in one batch, then each read.
                auto renderFrame = [&] {
                    RenderTarget::submitAll(submissions);
                    for (std::size_t v = 0; v < targets.size(); ++v)
                        targets[v]->read(viewFrames[v]);
                };
                Frame& frame = viewFrames.front();
                for (int i = 0; i < 3; ++i)
                    renderFrame();
                renderer.resetStats();
                const auto start = std::chrono::steady_clock::now();
                for (int i = 0; i < frames; ++i)
                    renderFrame();
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                        .count() /
                    frames;
                std::printf("%4dx%-5d %-12s %-8d %10.2f  ", width, height, label.c_str(), latency, ms);
                for (const PassTime& pass : renderer.stats().passTimes)
                    std::printf(" %6.2f/%-6.2f", pass.samples ? pass.gpuMs / double(pass.samples) : 0.0,
                                pass.cpuMs / frames);
                if (latency == 0 && epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) {
                    // Fragment shader runs of one more frame (the still scene's shadow maps are reused, so
                    // they are the surface passes'), per pixel of the views: overdraw and quad overshading.
                    GLuint query = 0;
                    glGenQueries(1, &query);
                    glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query);
                    renderFrame();
                    glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
                    GLuint64 invocations = 0;
                    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &invocations);
                    glDeleteQueries(1, &query);
                    std::printf("  fragment shader runs per pixel %.2f",
                                double(invocations) / (double(width) * height * double(views)));
                }
                std::printf("\n");
                std::fflush(stdout);
                if (!pngDir.empty() && label == "final_color" && latency == 0) {
                    const ImageBuffer& color = frame.get(Modality::FinalColor);
                    writePng(pngDir + "/bench_" + std::to_string(width) + "x" + std::to_string(height) +
                                 ".png",
                             width, height, 4, reinterpret_cast<const std::uint8_t*>(color.bytes.data()));
                }
            }
        }
    }
    return 0;
}
