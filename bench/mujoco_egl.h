#pragma once
// What the MuJoCo benchmark peers (mujoco_peer.cpp, mujoco_cosim_peer.cpp) share: loading a model from
// MJCF text, MuJoCo's offscreen rendering state, and the OpenGL context it draws into: EGL with no
// window, on the first hardware device, or on Mesa's surfaceless platform (llvmpipe) when there is
// none. MuJoCo's renderer uses fixed-function calls, so the context is a compatibility profile (EGL's
// default for the OpenGL API).

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace sp::bench {

/// Prints "<program>: <what>" and exits with status 1.
[[noreturn]] inline void failPeer(const char* program, const std::string& what) {
    std::fprintf(stderr, "%s: %s\n", program, what.c_str());
    std::exit(1);
}

/// Makes a compatibility-profile OpenGL context current with no surface; returns "device" or
/// "surfaceless" (which EGL platform it came from). Exits through failPeer() when there is none.
inline const char* makeMujocoEglContext(const char* program) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto platformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!platformDisplay)
        failPeer(program, "EGL has no eglGetPlatformDisplayEXT");
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
        failPeer(program, "no EGL display");
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
        failPeer(program, "eglBindAPI(EGL_OPENGL_API) failed");
    // MuJoCo uses fixed-function OpenGL: ask for a compatibility profile (the default).
    EGLContext context =
        eglCreateContext(display, configs ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, nullptr);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        failPeer(program, "cannot create or make current a compatibility-profile OpenGL context on EGL");
    return kind;
}

/// Compiles MJCF text (through an in-memory file, as MuJoCo 2.2 has no loader from a string); exits
/// through failPeer() with MuJoCo's message when it does not compile.
inline mjModel* loadMjcfString(const char* program, const std::string& xml) {
    mjVFS vfs;
    mj_defaultVFS(&vfs);
    if (mj_makeEmptyFileVFS(&vfs, "scene.xml", int(xml.size())))
        failPeer(program, "cannot create the in-memory MJCF file");
    std::memcpy(vfs.filedata[vfs.nfile - 1], xml.data(), xml.size());
    char error[1000] = "";
    mjModel* model = mj_loadXML("scene.xml", &vfs, error, sizeof error);
    mj_deleteVFS(&vfs);
    if (!model)
        failPeer(program, std::string("mj_loadXML: ") + error);
    return model;
}

/// MuJoCo's visualisation state for one model: the abstract scene, default options, and a rendering
/// context bound to the offscreen buffer (sized by the model's <global offwidth/offheight>).
struct MujocoVisual {
    mjvScene scene;
    mjvOption option;
    mjrContext context;
};

/// Makes the scene (room for maxGeoms geoms) and the offscreen rendering context of `model` in the current
/// OpenGL context; exits through failPeer() when the offscreen buffer is not supported.
inline void makeMujocoVisual(const char* program, const mjModel* model, int maxGeoms, MujocoVisual& visual) {
    mjv_defaultScene(&visual.scene);
    mjv_defaultOption(&visual.option);
    mjr_defaultContext(&visual.context);
    mjv_makeScene(model, &visual.scene, maxGeoms);
    mjr_makeContext(model, &visual.context, mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &visual.context);
    if (visual.context.currentBuffer != mjFB_OFFSCREEN)
        failPeer(program, "the offscreen buffer is not supported by this OpenGL context");
}

/// Frees what makeMujocoVisual() made.
inline void freeMujocoVisual(MujocoVisual& visual) {
    mjr_freeContext(&visual.context);
    mjv_freeScene(&visual.scene);
}

/// GL_RENDERER of the current context ("llvmpipe (LLVM 15.0.6, 256 bits)", a GPU's name), looked up through
/// EGL so that the peers need not link an OpenGL library of their own (MuJoCo loads one itself).
inline std::string currentGlRenderer() {
    using GetString = const unsigned char* (*)(unsigned int);
    constexpr unsigned int kGlRenderer = 0x1F01; // GL_RENDERER
    auto getString = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
    const unsigned char* name = getString ? getString(kGlRenderer) : nullptr;
    return name ? reinterpret_cast<const char*>(name) : "unknown";
}

} // namespace sp::bench
