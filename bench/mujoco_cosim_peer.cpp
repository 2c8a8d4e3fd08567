// MuJoCo as the peer of the co-simulation benchmark (Table 3; spear's side is examples/cosim_benchmark.py):
// MuJoCo steps the dynamics and its own renderer draws every frame, offscreen through EGL with no window.
//
//   spear_mujoco_cosim_peer [--objects N] [--views 1|2] [--width W] [--height H] [--frames F] [--shadows 0|1]
//                           [--png PATH]
//
// The workload, identical on both sides:
// - frames of 1/60 s, physics in 4 substeps of 1/240 s (4 mj_step per frame);
// - a static 40 x 40 m ground plane at z = 0, rgba (0.55, 0.55, 0.5, 1);
// - N free bodies (default 4) on a grid of side ceil(sqrt(N)), 0.8 m apart and centred on the origin, resting
//   0.001 m above the ground: a box of half-extent 0.15 m for even i, a sphere of radius 0.15 m for odd i,
//   1 kg, friction 0.8, colours from (i*37)%11, (i*17)%7, (i*53)%5;
// - at frame k (t = k/60), object i is pushed at its centre of mass for the whole frame by
//   4 N * (cos(1.5 t + 2 pi i/N), sin(1.5 t + 2 pi i/N), 0) (xfrc_applied);
// - one directional sun along (-0.5, -0.3, -1) with a 2048^2 shadow map (none with --shadows 0), ambient
//   (0.1, 0.12, 0.15), no MSAA;
// - a camera rig at (R cos 0.3t, R sin 0.3t, 2.5), R = 0.4 side + 5, looking at (0, 0, 0.2); with --views 2
//   a second view 0.3 m to the right of the first, looking parallel; 60 degree horizontal field of view;
// - per frame: set the forces, move the rig, step 4 times, then for each view mjv_updateScene, mjr_render
//   and mjr_readPixels (RGB) into a buffer of that view's own.
// After 10 warm-up frames it times --frames frames (default 1000) and prints one JSON line. --png writes
// view 0's last image.

#include <mujoco/mujoco.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mujoco_egl.h"

namespace {

constexpr const char* kProgram = "spear_mujoco_cosim_peer";
constexpr int kSubsteps = 4;
constexpr double kFrameSeconds = 1.0 / 60.0;
constexpr int kWarmupFrames = 10;
constexpr double kHalfExtent = 0.15;  // box half-extent and sphere radius, metres
constexpr double kForceNewtons = 4.0; // magnitude of each object's push
constexpr double kViewOffset = 0.3;   // view 1 sits this far right of view 0, metres

struct Options {
    int objects = 4, views = 1, width = 1920, height = 1080, frames = 1000;
    bool shadows = true;
    std::string png;
};

[[noreturn]] void fail(const std::string& what) {
    sp::bench::failPeer(kProgram, what);
}

int gridSide(int objects) {
    return std::max(1, int(std::ceil(std::sqrt(double(objects)))));
}

std::string sceneXml(const Options& options) {
    char buffer[1024];
    std::snprintf(
        buffer, sizeof buffer,
        "<mujoco model=\"cosim\"><option timestep=\"%.17g\"/>"
        // Room for every contact of 64 resting objects (the default 100 drops contacts).
        "<size nconmax=\"2000\" njmax=\"8000\"/>"
        "<visual><quality shadowsize=\"2048\" offsamples=\"0\"/>"
        "<global offwidth=\"%d\" offheight=\"%d\"/>"
        "<headlight ambient=\"0.1 0.12 0.15\" diffuse=\"0 0 0\" specular=\"0 0 0\"/></visual>"
        "<worldbody>"
        "<geom name=\"ground\" type=\"plane\" size=\"20 20 0.1\" rgba=\"0.55 0.55 0.5 1\" "
        "friction=\"0.8 0.005 0.0001\"/>"
        "<light name=\"sun\" directional=\"true\" castshadow=\"%s\" pos=\"0 0 10\" dir=\"-0.5 -0.3 -1\"/>",
        kFrameSeconds / kSubsteps, options.width, options.height, options.shadows ? "true" : "false");
    std::string xml = buffer;
    const int side = gridSide(options.objects);
    for (int i = 0; i < options.objects; ++i) {
        const double x = 0.8 * (i % side) - 0.4 * (side - 1), y = 0.8 * (i / side) - 0.4 * (side - 1),
                     z = kHalfExtent + 0.001;
        const bool box = i % 2 == 0;
        std::snprintf(buffer, sizeof buffer,
                      "<body name=\"object_%d\" pos=\"%.17g %.17g %.17g\"><freejoint/>"
                      "<geom type=\"%s\" size=\"%.17g %.17g %.17g\" mass=\"1\" friction=\"0.8 0.005 0.0001\" "
                      "rgba=\"%.17g %.17g %.17g 1\"/></body>",
                      i, x, y, z, box ? "box" : "sphere", kHalfExtent, kHalfExtent, kHalfExtent,
                      0.2 + 0.6 * ((i * 37) % 11) / 10.0, 0.2 + 0.6 * ((i * 17) % 7) / 6.0,
                      0.2 + 0.6 * ((i * 53) % 5) / 4.0);
        xml += buffer;
    }
    return xml + "</worldbody></mujoco>";
}

Options parseOptions(int argc, char** argv) {
    Options options;
    const char* usage =
        "usage: spear_mujoco_cosim_peer [--objects N] [--views 1|2] [--width W] [--height H] [--frames F] "
        "[--shadows 0|1] [--png PATH]";
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc)
            fail(usage);
        const char* value = argv[++i];
        if (flag == "--png") {
            options.png = value;
            continue;
        }
        char* end = nullptr;
        const long number = std::strtol(value, &end, 10);
        if (*value == '\0' || *end != '\0' || number < 0 || number > 100000)
            fail(flag + " takes a count, got '" + value + "'");
        if (flag == "--objects")
            options.objects = int(number);
        else if (flag == "--views")
            options.views = int(number);
        else if (flag == "--width")
            options.width = int(number);
        else if (flag == "--height")
            options.height = int(number);
        else if (flag == "--frames")
            options.frames = int(number);
        else if (flag == "--shadows" && number <= 1)
            options.shadows = number == 1;
        else
            fail(usage);
    }
    if (options.objects < 1 || options.frames < 1 || options.width < 1 || options.height < 1)
        fail("--objects, --frames, --width and --height must be at least 1");
    if (options.views != 1 && options.views != 2)
        fail("--views must be 1 or 2, got " + std::to_string(options.views));
    return options;
}

// Places a free camera at `position` looking at `target`: MuJoCo's free camera sits `distance` behind its
// look-at point along the direction given by azimuth (from +X toward +Y) and elevation (up from the XY
// plane).
void placeFreeCamera(const std::array<double, 3>& position, const std::array<double, 3>& target,
                     mjvCamera& camera) {
    const double d[3] = {target[0] - position[0], target[1] - position[1], target[2] - position[2]};
    const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    camera.type = mjCAMERA_FREE;
    for (int a = 0; a < 3; ++a)
        camera.lookat[a] = target[a];
    camera.distance = distance;
    camera.azimuth = std::atan2(d[1], d[0]) * 180.0 / M_PI;
    camera.elevation = std::asin(d[2] / distance) * 180.0 / M_PI;
}

// The rig at time t: view 0 at the rig, view 1 (if any) kViewOffset to its right, looking parallel.
void moveRig(double t, int side, int views, mjvCamera* cameras) {
    const double radius = 0.4 * side + 5.0;
    const std::array<double, 3> position{radius * std::cos(0.3 * t), radius * std::sin(0.3 * t), 2.5};
    const std::array<double, 3> target{0.0, 0.0, 0.2};
    placeFreeCamera(position, target, cameras[0]);
    if (views < 2)
        return;
    // right = normalize(forward x (0, 0, 1)) = normalize(forward.y, -forward.x, 0)
    const double fx = target[0] - position[0], fy = target[1] - position[1];
    const double norm = std::sqrt(fx * fx + fy * fy);
    const double rx = kViewOffset * fy / norm, ry = -kViewOffset * fx / norm;
    placeFreeCamera({position[0] + rx, position[1] + ry, position[2]},
                    {target[0] + rx, target[1] + ry, target[2]}, cameras[1]);
}

void setForces(mjData* data, int objects, double t) {
    for (int i = 0; i < objects; ++i) {
        const double phase = 2.0 * M_PI * i / objects;
        mjtNum* wrench = data->xfrc_applied + 6 * (i + 1); // body 0 is the world
        wrench[0] = kForceNewtons * std::cos(1.5 * t + phase);
        wrench[1] = kForceNewtons * std::sin(1.5 * t + phase);
        wrench[2] = wrench[3] = wrench[4] = wrench[5] = 0.0;
    }
}

double ms(std::chrono::steady_clock::duration d) {
    return std::chrono::duration<double, std::milli>(d).count();
}

} // namespace

int main(int argc, char** argv) {
    const Options options = parseOptions(argc, argv);
    sp::bench::makeMujocoEglContext(kProgram);
    mjModel* model = sp::bench::loadMjcfString(kProgram, sceneXml(options));
    // MuJoCo's fovy is vertical: match the workload's 60 degree horizontal field of view.
    model->vis.global.fovy =
        float(2.0 * std::atan(std::tan(M_PI / 6.0) * options.height / options.width) * 180.0 / M_PI);
    mjData* data = mj_makeData(model);
    mj_forward(model, data);

    sp::bench::MujocoVisual visual;
    sp::bench::makeMujocoVisual(kProgram, model, options.objects + 16, visual);
    mjvCamera cameras[2];
    mjv_defaultCamera(&cameras[0]);
    mjv_defaultCamera(&cameras[1]);
    const mjrRect viewport{0, 0, options.width, options.height};
    std::vector<std::vector<unsigned char>> images(
        options.views, std::vector<unsigned char>(size_t(options.width) * options.height * 3));
    const int side = gridSide(options.objects);

    double physicsMs = 0, renderMs = 0, frameMs = 0;
    for (int frame = 0; frame < kWarmupFrames + options.frames; ++frame) {
        const double t = frame * kFrameSeconds;
        const auto start = std::chrono::steady_clock::now();
        setForces(data, options.objects, t);
        moveRig(t, side, options.views, cameras);
        for (int step = 0; step < kSubsteps; ++step)
            mj_step(model, data);
        const auto stepped = std::chrono::steady_clock::now();
        for (int view = 0; view < options.views; ++view) {
            mjv_updateScene(model, data, &visual.option, nullptr, &cameras[view], mjCAT_ALL, &visual.scene);
            mjr_render(viewport, &visual.scene, &visual.context);
            mjr_readPixels(images[view].data(), nullptr, viewport, &visual.context);
        }
        const auto rendered = std::chrono::steady_clock::now();
        if (frame >= kWarmupFrames) {
            physicsMs += ms(stepped - start);
            renderMs += ms(rendered - stepped);
            frameMs += ms(rendered - start);
        }
    }

    if (!options.png.empty()) {
        // OpenGL's rows run bottom to top.
        stbi_flip_vertically_on_write(1);
        if (!stbi_write_png(options.png.c_str(), options.width, options.height, 3, images[0].data(),
                            options.width * 3))
            fail("cannot write '" + options.png + "'");
    }
    std::string device = sp::bench::currentGlRenderer();
    std::replace(device.begin(), device.end(), '"', '\'');
    std::printf(
        "{\"peer\": \"mujoco\", \"version\": \"%s\", \"objects\": %d, \"views\": %d, \"width\": %d, "
        "\"height\": %d, \"frames\": %d, \"ms_per_frame\": %.4f, \"physics_ms\": %.4f, \"render_ms\": "
        "%.4f, \"device\": \"%s\"}\n",
        mj_versionString(), options.objects, options.views, options.width, options.height, options.frames,
        frameMs / options.frames, physicsMs / options.frames, renderMs / options.frames, device.c_str());

    sp::bench::freeMujocoVisual(visual);
    mj_deleteData(data);
    mj_deleteModel(model);
    return 0;
}
