#pragma once
// Screen-space ambient occlusion of a rasterised view: ground-truth ambient occlusion (GTAO; Jimenez, Wu,
// Pesce, Jarabo, "Practical Real-Time Strategies for Accurate Indirect Occlusion", 2016). The irradiance
// probes light the scene at their spacing (0.5 m at Medium); what is finer, a corner, the floor under a
// table, the gap between a shelf and a wall, the probes light as if it were open. GTAO measures, from the
// view's depth, how much of each pixel's cosine-weighted hemisphere the nearby surfaces hide, within
// CameraParams::ambientOcclusionRadius metres, and the shading scales the indirect and sky light by it (never
// the lights', which have their shadow maps), as Unreal's SSAO does.
//
// Three passes, before the surface pass that shades: the view's depth drawn alone (at half the resolution
// above kFullResolutionPixels), the occlusion of each texel (two slices, four steps each way, the slices
// turned by a 4 x 4 pattern of angles), and a 4 x 4 blur that averages the pattern away without crossing
// depth edges and applies the intensity. The shading loads the texel under its pixel
// (shaders::kScreenOcclusionUnit, an image: a software rasteriser's filtered texture read costs several image
// loads; the blur has made the texels smooth). Needs a current context.

namespace sp::render {

class ShaderProgram;

class ScreenOcclusion {
  public:
    // Views of at most this many pixels take their occlusion at full resolution, larger ones at half
    // (640 x 480 at 320 x 240, 1080p at 960 x 540): the occlusion is smooth, and a software rasteriser pays
    // per texel.
    static constexpr long kFullResolutionPixels = 320L * 240L;
    static int scaleFor(int width, int height) {
        return long(width) * long(height) > kFullResolutionPixels ? 2 : 1;
    }

    ScreenOcclusion(int viewWidth, int viewHeight);
    ~ScreenOcclusion();
    ScreenOcclusion(const ScreenOcclusion&) = delete;
    ScreenOcclusion& operator=(const ScreenOcclusion&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    // The framebuffer the depth pass draws Target::Depth into (an R32F texture and a depth buffer).
    unsigned depthFbo() const { return depthFbo_; }
    // Runs the occlusion and blur passes (shaders::screenOcclusionFragment() and
    // screenOcclusionBlurFragment(), the renderer's) on what the depth pass drew: `focalLength` in texels,
    // `radius` in metres, `intensity` in [0, 1] (1 - intensity * (1 - occlusion) is stored).
    void compute(ShaderProgram& occlusion, ShaderProgram& blur, float focalLength, float radius,
                 float intensity);
    // The result (R8, width() x height()), for the shading to read.
    unsigned texture() const { return occlusion_; }

  private:
    int width_ = 0;
    int height_ = 0;
    unsigned depth_ = 0;       // R32F, metres along the optical axis (0: background)
    unsigned depthBuffer_ = 0; // the depth pass's depth test
    unsigned depthFbo_ = 0;
    unsigned raw_ = 0; // R8, before the blur
    unsigned rawFbo_ = 0;
    unsigned occlusion_ = 0; // R8, blurred, intensity applied
    unsigned occlusionFbo_ = 0;
    unsigned emptyVao_ = 0;
};

} // namespace sp::render
