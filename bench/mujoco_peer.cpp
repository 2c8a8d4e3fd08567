// MuJoCo's own renderer as a peer for bench/bench_camera.py: the same scene as the camera benchmark (a
// 40 x 40 m ground, N boxes of 0.6 m with the same placement, a shadowed sun and spot light), rendered
// offscreen through EGL with no window and no MSAA (offsamples 0), shadow maps on. Times per frame:
// mjv_updateScene, mjr_render + mjr_readPixels (RGB) and mjr_render + mjr_readPixels (RGB + depth).
//
//   spear_mujoco_peer [--boxes N] [--frames F] [--shadows RES]
//
// MuJoCo's renderer needs a compatibility-profile context (fixed-function calls); EGL gives one on the
// first hardware device or on Mesa's surfaceless platform (llvmpipe) when there is none.

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

[[noreturn]] void fail(const std::string& what) {
    std::fprintf(stderr, "spear_mujoco_peer: %s\n", what.c_str());
    std::exit(1);
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

void makeEglContext() {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto platformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!platformDisplay)
        fail("EGL has no eglGetPlatformDisplayEXT");
    EGLDisplay display = EGL_NO_DISPLAY;
    const char* kind = "surfaceless";
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices && queryDevices(16, devices, &count)) {
        auto queryString =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        for (EGLint i = 0; i < count && display == EGL_NO_DISPLAY; ++i) {
            const char* extensions = queryString ? queryString(devices[i], EGL_EXTENSIONS) : nullptr;
            if (extensions && std::strstr(extensions, "EGL_MESA_device_software"))
                continue; // prefer hardware; software is what the surfaceless platform gives anyway
            display = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            kind = "device";
        }
    }
    if (display == EGL_NO_DISPLAY)
        display = platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr))
        fail("no EGL display");
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE,
                                       EGL_PBUFFER_BIT,
                                       EGL_RENDERABLE_TYPE,
                                       EGL_OPENGL_BIT,
                                       EGL_RED_SIZE,
                                       8,
                                       EGL_GREEN_SIZE,
                                       8,
                                       EGL_BLUE_SIZE,
                                       8,
                                       EGL_DEPTH_SIZE,
                                       24,
                                       EGL_NONE};
    EGLConfig config;
    EGLint configs = 0;
    eglChooseConfig(display, configAttributes, &config, 1, &configs);
    if (!eglBindAPI(EGL_OPENGL_API))
        fail("eglBindAPI(EGL_OPENGL_API) failed");
    // MuJoCo uses fixed-function OpenGL: ask for a compatibility profile (the default).
    EGLContext context =
        eglCreateContext(display, configs ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, nullptr);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        fail("cannot create or make current a compatibility-profile OpenGL context on EGL");
    std::printf("mujoco %s on EGL %s\n", mj_versionString(), kind);
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
    makeEglContext();
    char error[1000] = "";
    mjVFS vfs;
    mj_defaultVFS(&vfs);
    const std::string xml = sceneXml(boxes, shadows);
    if (mj_makeEmptyFileVFS(&vfs, "scene.xml", int(xml.size())))
        fail("cannot create the in-memory MJCF file");
    std::memcpy(vfs.filedata[vfs.nfile - 1], xml.data(), xml.size());
    mjModel* model = mj_loadXML("scene.xml", &vfs, error, sizeof error);
    if (!model)
        fail(std::string("mj_loadXML: ") + error);
    mjData* data = mj_makeData(model);
    mj_forward(model, data);

    mjvScene scene;
    mjvCamera camera;
    mjvOption option;
    mjrContext context;
    mjv_defaultScene(&scene);
    mjv_defaultCamera(&camera);
    mjv_defaultOption(&option);
    mjr_defaultContext(&context);
    mjv_makeScene(model, &scene, 2000);
    mjr_makeContext(model, &context, mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &context);
    if (context.currentBuffer != mjFB_OFFSCREEN)
        fail("the offscreen buffer is not supported by this OpenGL context");
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
                mjv_updateScene(model, data, &option, nullptr, &camera, mjCAT_ALL, &scene);
                const auto t1 = std::chrono::steady_clock::now();
                mjr_render(viewport, &scene, &context);
                mjr_readPixels(rgb.data(), withDepth ? depth.data() : nullptr, viewport, &context);
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
    mjr_freeContext(&context);
    mjv_freeScene(&scene);
    mj_deleteData(data);
    mj_deleteModel(model);
    mj_deleteVFS(&vfs);
    return 0;
}
