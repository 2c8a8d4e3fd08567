// MuJoCo's own renderer as a peer for bench/bench_camera.py: the same scene as the camera benchmark (a
// 40 x 40 m ground, N boxes of 0.6 m with the same placement, a shadowed sun and spot light), rendered
// offscreen through EGL with no window and no MSAA (offsamples 0), shadow maps on. Times per frame:
// mjv_updateScene, mjr_render + mjr_readPixels (RGB) and mjr_render + mjr_readPixels (RGB + depth).
//
//   spear_mujoco_peer [--boxes N] [--frames F] [--shadows RES]
//
// The OpenGL context comes from bench/mujoco_egl.h (EGL, compatibility profile, no window).

#include <mujoco/mujoco.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mujoco_egl.h"

namespace {

[[noreturn]] void fail(const std::string& what) {
    sp::bench::failPeer("spear_mujoco_peer", what);
}

// Same placement and colours as core/render/bench/render_bench.cpp and bench/bench_camera.py.
std::string sceneXml(int boxes, int shadows) {
    std::string xml =
        "<mujoco><visual><quality shadowsize=\"" + std::to_string(shadows) +
        "\" offsamples=\"0\"/><global offwidth=\"1920\" offheight=\"1080\"/>"
        "<headlight ambient=\"0.1 0.12 0.15\" diffuse=\"0 0 0\" specular=\"0 0 0\"/></visual>"
        "<worldbody><geom type=\"plane\" size=\"20 20 0.1\" rgba=\"0.55 0.55 0.5 1\"/>"
        "<light directional=\"true\" castshadow=\"true\" pos=\"0 0 10\" dir=\"-0.5 -0.3 -1\"/>"
        "<light directional=\"false\" castshadow=\"true\" pos=\"0 0 6\" dir=\"0.2 0.1 -1\" cutoff=\"45\"/>";
    const int side = std::max(1, int(std::ceil(std::sqrt(double(boxes)))));
    char buffer[512];
    for (int i = 0; i < boxes; ++i) {
        const double x = 1.2 * (i % side) - 0.6 * side, y = 1.2 * (i / side) - 0.6 * side,
                     z = 0.3 + 0.4 * (i % 3);
        std::snprintf(
            buffer, sizeof buffer,
            "<geom type=\"box\" size=\"0.3 0.3 0.3\" pos=\"%g %g %g\" euler=\"0 0 %g\" rgba=\"%g %g %g 1\"/>",
            x, y, z, 0.3 * i, 0.2 + 0.6 * ((i * 37) % 11) / 10.0, 0.2 + 0.6 * ((i * 17) % 7) / 6.0,
            0.2 + 0.6 * ((i * 53) % 5) / 4.0);
        xml += buffer;
    }
    // Looking at the origin from the benchmark's camera position; MuJoCo cameras look along their -Z,
    // with X right and Y up (xyaxes).
    const double extent = 0.6 * std::ceil(std::sqrt(double(boxes))) + 2.0;
    const double p[3] = {-1.4 * extent, -1.1 * extent, 0.9 * extent};
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const double f[3] = {-p[0] / n, -p[1] / n, -p[2] / n};
    double r[3] = {f[1], -f[0], 0.0}; // forward x (0, 0, 1)
    const double rn = std::sqrt(r[0] * r[0] + r[1] * r[1]);
    r[0] /= rn;
    r[1] /= rn;
    const double u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
    std::snprintf(buffer, sizeof buffer,
                  "<camera name=\"cam\" pos=\"%g %g %g\" xyaxes=\"%g %g %g %g %g %g\"/>", p[0], p[1], p[2],
                  r[0], r[1], r[2], u[0], u[1], u[2]);
    xml += buffer;
    return xml + "</worldbody></mujoco>";
}

double ms(std::chrono::steady_clock::duration d) {
    return std::chrono::duration<double, std::milli>(d).count();
}

} // namespace

int main(int argc, char** argv) {
    int boxes = 64, frames = 10, shadows = 2048;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--boxes") && i + 1 < argc)
            boxes = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--shadows") && i + 1 < argc)
            shadows = std::atoi(argv[++i]);
        else
            fail("usage: spear_mujoco_peer [--boxes N] [--frames F] [--shadows RES]");
    }
    const char* kind = sp::bench::makeMujocoEglContext("spear_mujoco_peer");
    std::printf("mujoco %s on EGL %s\n", mj_versionString(), kind);
    mjModel* model = sp::bench::loadMjcfString("spear_mujoco_peer", sceneXml(boxes, shadows));
    mjData* data = mj_makeData(model);
    mj_forward(model, data);

    sp::bench::MujocoVisual visual;
    sp::bench::makeMujocoVisual("spear_mujoco_peer", model, 2000, visual);
    mjvCamera camera;
    mjv_defaultCamera(&camera);
    camera.type = mjCAMERA_FIXED;
    camera.fixedcamid = 0;
    std::printf("%d boxes, shadow maps %d, no MSAA, %d timed frames after 3 warm-up frames\n", boxes, shadows,
                frames);

    const int sizes[2][2] = {{256, 256}, {1920, 1080}};
    for (const auto& size : sizes) {
        const int width = size[0], height = size[1];
        // MuJoCo's fovy is vertical: match the benchmark's 60 degree horizontal field of view.
        model->cam_fovy[0] = 2.0 * std::atan(std::tan(M_PI / 6.0) * height / width) * 180.0 / M_PI;
        const mjrRect viewport{0, 0, width, height};
        std::vector<unsigned char> rgb(size_t(width) * height * 3);
        std::vector<float> depth(size_t(width) * height);
        for (int withDepth = 0; withDepth < 2; ++withDepth) {
            double update = 0, render = 0;
            for (int frame = 0; frame < frames + 3; ++frame) {
                const auto t0 = std::chrono::steady_clock::now();
                mjv_updateScene(model, data, &visual.option, nullptr, &camera, mjCAT_ALL, &visual.scene);
                const auto t1 = std::chrono::steady_clock::now();
                mjr_render(viewport, &visual.scene, &visual.context);
                mjr_readPixels(rgb.data(), withDepth ? depth.data() : nullptr, viewport, &visual.context);
                const auto t2 = std::chrono::steady_clock::now();
                if (frame >= 3) {
                    update += ms(t1 - t0);
                    render += ms(t2 - t1);
                }
            }
            std::printf("mujoco %4dx%-4d %-9s render+read %8.2f ms/frame  (updateScene %.2f ms)\n", width,
                        height, withDepth ? "rgb+depth" : "rgb", render / frames, update / frames);
        }
    }
    sp::bench::freeMujocoVisual(visual);
    mj_deleteData(data);
    mj_deleteModel(model);
    return 0;
}
