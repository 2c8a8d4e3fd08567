#include "core/render/gl_context.h"

// EGL comes straight from libEGL (extension entry points through eglGetProcAddress). This file does
// not include GL headers (libepoxy's and Khronos' EGL headers cannot share a translation unit): the
// few GL queries below go through eglGetProcAddress.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/error.h"
#include "core/base/log.h"

namespace sp::render {
namespace {

bool hasExtension(const char* extensions, std::string_view name) {
    if (extensions == nullptr)
        return false;
    std::string_view all(extensions);
    std::size_t pos = 0;
    while ((pos = all.find(name, pos)) != std::string_view::npos) {
        std::size_t end = pos + name.size();
        if ((pos == 0 || all[pos - 1] == ' ') && (end == all.size() || all[end] == ' '))
            return true;
        pos = end;
    }
    return false;
}

std::string eglErrorString() {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "0x%04x", static_cast<unsigned>(eglGetError()));
    return buffer;
}

struct EglExtensions {
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
};

const EglExtensions& eglExtensions() {
    static const EglExtensions extensions = [] {
        EglExtensions e;
        e.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        e.queryDeviceString =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        e.getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        return e;
    }();
    return extensions;
}

std::vector<EGLDeviceEXT> queryDevices() {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExtensions, "EGL_EXT_device_enumeration") &&
        !hasExtension(clientExtensions, "EGL_EXT_device_base"))
        return {};
    const auto eglQueryDevicesEXT = eglExtensions().queryDevices;
    if (eglQueryDevicesEXT == nullptr)
        return {};
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0)
        return {};
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    eglQueryDevicesEXT(count, devices.data(), &count);
    devices.resize(static_cast<std::size_t>(count));
    return devices;
}

// Mesa lists its software rasterizer as a device too; everything else is hardware.
bool isSoftwareDevice(EGLDeviceEXT device) {
    if (eglExtensions().queryDeviceString == nullptr)
        return false;
    const char* extensions = eglExtensions().queryDeviceString(device, EGL_EXTENSIONS);
    return hasExtension(extensions, "EGL_MESA_device_software");
}

// Initializes display and creates a 4.5 core context on it; returns null (with a reason) on failure.
EGLContext createCoreContext(EGLDisplay display, std::string& whyNot) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        whyNot = "eglInitialize failed (" + eglErrorString() + ")";
        return EGL_NO_CONTEXT;
    }
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
        whyNot = "display lacks EGL_KHR_surfaceless_context";
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        whyNot = "eglBindAPI(EGL_OPENGL_API) failed";
        return EGL_NO_CONTEXT;
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(extensions, "EGL_KHR_no_config_context")) {
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint numConfigs = 0;
        if (!eglChooseConfig(display, configAttribs, &config, 1, &numConfigs) || numConfigs < 1) {
            whyNot = "no EGL config renders OpenGL";
            return EGL_NO_CONTEXT;
        }
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) {
        whyNot = "eglCreateContext(OpenGL 4.5 core) failed (" + eglErrorString() + ")";
    }
    return context;
}

constexpr unsigned kGlVendor = 0x1F00, kGlRenderer = 0x1F01, kGlVersion = 0x1F02;
constexpr unsigned kGlMajorVersion = 0x821B, kGlMinorVersion = 0x821C;

std::string glString(unsigned name) {
    using GetString = const unsigned char* (*)(unsigned);
    auto getString = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
    const auto* value = getString ? reinterpret_cast<const char*>(getString(name)) : nullptr;
    return value ? value : "";
}

int glInteger(unsigned name) {
    using GetIntegerv = void (*)(unsigned, int*);
    auto getIntegerv = reinterpret_cast<GetIntegerv>(eglGetProcAddress("glGetIntegerv"));
    int value = 0;
    if (getIntegerv)
        getIntegerv(name, &value);
    return value;
}

} // namespace

GlContext::GlContext(const GlContextOptions& options) {
    std::string choice = options.device;
    if (choice.empty()) {
        const char* env = std::getenv("SPEAR_EGL_DEVICE");
        choice = env ? env : "auto";
    }
    std::vector<EGLDeviceEXT> devices = queryDevices();
    report_.deviceCount = static_cast<int>(devices.size());

    int forcedIndex = -1;
    if (choice != "auto" && choice != "surfaceless") {
        char* end = nullptr;
        long index = std::strtol(choice.c_str(), &end, 10);
        SP_CHECK(
            end != choice.c_str() && *end == '\0' && index >= 0, InvalidArgument,
            "GlContext::GlContext(): SPEAR_EGL_DEVICE must be 'auto', 'surfaceless' or a device index, got '",
            choice, "'");
        SP_CHECK(index < static_cast<long>(devices.size()), InvalidArgument,
                 "GlContext::GlContext(): SPEAR_EGL_DEVICE=", index, " but EGL lists ", devices.size(),
                 " device(s)");
        forcedIndex = static_cast<int>(index);
    }

    std::string reasons;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    auto tryDevice = [&](int index) {
        EGLDisplay candidate =
            eglExtensions().getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(index)], nullptr);
        std::string whyNot = "eglGetPlatformDisplayEXT failed";
        EGLContext created =
            candidate != EGL_NO_DISPLAY ? createCoreContext(candidate, whyNot) : EGL_NO_CONTEXT;
        if (created == EGL_NO_CONTEXT) {
            reasons += " device " + std::to_string(index) + ": " + whyNot + ";";
            return false;
        }
        display = candidate;
        context = created;
        report_.kind = "device";
        report_.deviceIndex = index;
        return true;
    };

    if (forcedIndex >= 0) {
        tryDevice(forcedIndex);
    } else if (choice == "auto") {
        for (int i = 0; i < static_cast<int>(devices.size()) && context == EGL_NO_CONTEXT; ++i)
            if (!isSoftwareDevice(devices[std::size_t(i)]))
                tryDevice(i);
    }
    if (context == EGL_NO_CONTEXT && forcedIndex < 0) {
        EGLDisplay candidate = eglExtensions().getPlatformDisplay
                                   ? eglExtensions().getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA,
                                                                        EGL_DEFAULT_DISPLAY, nullptr)
                                   : EGL_NO_DISPLAY;
        std::string whyNot = "eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA) failed";
        EGLContext created =
            candidate != EGL_NO_DISPLAY ? createCoreContext(candidate, whyNot) : EGL_NO_CONTEXT;
        if (created != EGL_NO_CONTEXT) {
            display = candidate;
            context = created;
            report_.kind = "surfaceless";
        } else {
            reasons += " surfaceless: " + whyNot + ";";
        }
    }
    SP_CHECK(context != EGL_NO_CONTEXT, InvalidState,
             "GlContext::GlContext(): no OpenGL 4.5 core context could be created (SPEAR_EGL_DEVICE='",
             choice, "'):", reasons);

    display_ = display;
    context_ = context;
    makeCurrent();
    report_.vendor = glString(kGlVendor);
    report_.renderer = glString(kGlRenderer);
    for (const char* rasteriser : {"llvmpipe", "softpipe", "SwiftShader"})
        report_.software = report_.software || report_.renderer.find(rasteriser) != std::string::npos;
    report_.version = glString(kGlVersion);
    const int major = glInteger(kGlMajorVersion), minor = glInteger(kGlMinorVersion);
    if (major * 10 + minor < 45) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        SP_THROW(InvalidState, "GlContext::GlContext(): need OpenGL 4.5 core, the ", report_.kind,
                 " context is ", report_.version, " (", report_.renderer, ")");
    }
    // Once per process and device: a process with many worlds makes a context for each.
    const std::string chosen =
        report_.kind +
        (report_.deviceIndex >= 0 ? " " + std::to_string(report_.deviceIndex) : std::string()) + " of " +
        std::to_string(report_.deviceCount) + " device(s): " + report_.vendor + " | " + report_.renderer +
        " | " + report_.version;
    static std::mutex mutex;
    static std::set<std::string> logged;
    const std::lock_guard<std::mutex> lock(mutex);
    if (logged.insert(chosen).second)
        SP_LOG("render: EGL ", chosen);
}

GlContext::~GlContext() {
    if (context_ == nullptr)
        return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    // No eglTerminate: EGL displays are per-process singletons that other contexts may still use.
    eglDestroyContext(display_, context_);
}

void GlContext::makeCurrent() const {
    if (eglGetCurrentContext() == context_) // worlds sharing a context make it current at every step
        return;
    SP_CHECK(eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_), InvalidState,
             "GlContext::makeCurrent(): eglMakeCurrent failed (", eglErrorString(), ")");
}

} // namespace sp::render
