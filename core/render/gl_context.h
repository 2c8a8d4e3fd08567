#pragma once
// A headless OpenGL 4.5 core context on EGL, with no window and no surface.
//
// Device selection: EGL devices are enumerated (EGL_EXT_device_enumeration); the first hardware device
// (one that is not Mesa's software device, e.g. an NVIDIA GPU) is preferred. Without one, Mesa's
// surfaceless platform is used (llvmpipe on a machine with no GPU). SPEAR_EGL_DEVICE=<index> forces
// device <index>; SPEAR_EGL_DEVICE=surfaceless forces the surfaceless platform.

#include <string>

namespace sp::render {

// Which EGL display the context was created on, and what GL reports about itself.
struct ContextReport {
    std::string kind;      // "device" or "surfaceless"
    int deviceIndex = -1;  // index in eglQueryDevicesEXT's list; -1 for surfaceless
    int deviceCount = 0;   // devices that eglQueryDevicesEXT listed
    std::string vendor;    // GL_VENDOR
    std::string renderer;  // GL_RENDERER
    std::string version;   // GL_VERSION
    bool software = false; // a rasteriser running on the CPU (llvmpipe, softpipe, SwiftShader)
};

// Options for GlContext::create(); an empty `device` reads SPEAR_EGL_DEVICE, then auto-selects.
struct GlContextOptions {
    std::string device; // "", "auto", "surfaceless" or a device index such as "0"
};

class GlContext {
  public:
    // Creates the context and makes it current on the calling thread. Throws sp::InvalidState when no
    // OpenGL 4.5 core context can be created, sp::InvalidArgument for a bad SPEAR_EGL_DEVICE value.
    explicit GlContext(const GlContextOptions& options = {});
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    // Makes this context current on the calling thread (GL objects are only valid while it is).
    void makeCurrent() const;

    const ContextReport& report() const { return report_; }

  private:
    void* display_ = nullptr;
    void* context_ = nullptr;
    ContextReport report_;
};

} // namespace sp::render
