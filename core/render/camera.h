#pragma once
// Camera intrinsics/settings and the GL matrices derived from them. Pure logic, no GL.
//
// Convention: world is right-handed, Z up, metres. The camera looks along its local +X, +Y is left and
// +Z is up (ROS REP-103 body frame); `pose` maps camera to world. Depth is the distance along +X.

#include <array>
#include <span>
#include <string>

#include <Eigen/Geometry>

namespace sp::render {

enum class ToneMap { Aces, Reinhard, Linear };

// Anti-aliasing of final_color. The exact modalities (depth, ids, normals, ...) are never filtered.
enum class AntiAliasing {
    None,
    // FXAA on the CPU as final_color is read back (fxaa.h): edges found and blended by their luma.
    Fxaa,
    // Multisampling: the shaded modalities (final_color, hdr_color, the intrinsic images) are drawn with
    // msaaSamples coverage samples a pixel and averaged (final_color in linear light); the exact modalities
    // are drawn apart, single-sampled (PassSet::samples).
    Msaa,
};

// Settings of one camera; validate() throws sp::InvalidArgument naming the bad field.
struct CameraParams {
    int width = 640;         // pixels
    int height = 480;        // pixels
    double hfovDeg = 90.0;   // horizontal field of view, degrees, in (0, 180)
    double nearClip = 0.05;  // metres, > 0
    double farClip = 1000.0; // metres, > nearClip
    float exposure = 1.0f;   // linear multiplier applied to hdr_color before the tone curve
    // Per-channel gains of white balance, applied with exposure (whiteBalanceGains(); 1, 1, 1: none).
    Eigen::Vector3f whiteBalance = Eigen::Vector3f::Ones();
    ToneMap toneMap = ToneMap::Aces; // tone curve for final_color
    bool shadows = true;             // render shadow maps for shadow-casting lights
    int shadowResolution = 1024;     // shadow map size in texels, in [16, 8192]
    // Depth of field, path tracer only: a thin lens of this radius (metres; 0 = a pinhole, all sharp)
    // focused at focusDistance metres along the optical axis.
    double apertureRadius = 0.0;
    double focusDistance = 10.0;
    // Natural vignetting of final_color, in [0, 1]: a pixel's exposure is scaled by
    // mix(1, cos^4(angle of its ray to the optical axis), vignetteIntensity) (tone.h, Vignette).
    float vignetteIntensity = 0.0f;
    // Indirect light from the scene's irradiance volume where it has one (Scene::setIrradianceVolume);
    // false shades with the environment's uniform ambient term instead.
    bool globalIllumination = true;
    // Anti-aliasing of final_color (none by default here: a library renders exactly what it is asked; the
    // engine's camera sensor turns FXAA on).
    AntiAliasing antiAliasing = AntiAliasing::None;
    // Samples a pixel with AntiAliasing::Msaa: 2, 4 or 8 (at most what the device offers:
    // Renderer::maxSamples(), 4 on llvmpipe).
    int msaaSamples = 4;
    // Spatial samples of the shaded modalities: 1 (none), 2, 4, 8 or 16. The shaded targets are drawn that
    // many times, each time with every pixel sampling the scene at another point of its square
    // (spatialSamplePattern()), and averaged (final_color in linear light): supersampling, which filters what
    // multisampling cannot (shading, specular highlights, shadow edges, texture detail). Above 1 it stands in
    // for Msaa's coverage samples (each moved pass multisampled would widen a pixel's footprint past its
    // square); FXAA still filters the averaged image. The exact modalities are drawn apart: one value a
    // pixel, at its centre (PassSet::spatialSamples).
    int spatialSamples = 1;
    // Texture samples along a pixel's footprint at most (anisotropic filtering of the material textures): 1
    // trilinear, up to 16; 0 takes the renderer's default (Renderer::anisotropicFiltering()).
    int maxAnisotropy = 0;
    // Added to the level of detail the material textures are read at, in levels, [-2, 2] (0 by default).
    // A pixel's true value is the mean of the texture over its footprint, a box one pixel wide (what the
    // path tracer and a supersampled view compute); trilinear filtering at the level whose texels are a pixel
    // wide spreads each texel over its neighbours and blends in the next coarser level, about twice as wide.
    // A level finer (-1) matches natural textures better (the default scene: SSIM against the path tracer
    // about 0.02 higher, closer to a 17 x 17 supersampled view with every anti-aliasing setting), but a
    // single sample of a finer level aliases on patterns a few pixels across (a checkerboard's squares: the
    // mean difference from supersampling doubles), hence 0, as in Unreal. Spatial samples read
    // log2 sqrt(N) levels finer than this.
    float mipBias = 0.0f;
    // Screen-space ambient occlusion of the indirect and sky light (screen_occlusion.h): how much of the
    // occlusion found is applied, in [0, 1] (0, the default here: none, and its passes do not run), and how
    // far from a point it looks for the surfaces that hide its hemisphere, metres in (0, 100].
    float ambientOcclusionIntensity = 0.0f;
    float ambientOcclusionRadius = 0.5f;

    void validate(const char* function) const;
};

std::string toneMapName(ToneMap toneMap);

// A camera pose plus its settings.
struct Camera {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity(); // camera-to-world
    CameraParams params;
    // Where in its square each pixel samples the scene, in pixels right and down from its centre (each in
    // (-0.5, 0.5)): moves the projection (projectionMatrix()) by that much. Zero but for the renderer's
    // spatial samples.
    Eigen::Vector2d subpixelOffset = Eigen::Vector2d::Zero();

    // World-to-GL-eye matrix (GL eye looks along -Z with +Y up).
    Eigen::Matrix4d viewMatrix() const;
    // GL clip-space projection. flipY renders image row 0 at the bottom of the framebuffer, so that
    // glReadPixels returns the top image row first.
    Eigen::Matrix4d projectionMatrix(bool flipY) const;
    // The view frustum's six planes (a, b, c, d with a·x + b·y + c·z + d >= 0 inside; unit normals).
    std::array<Eigen::Vector4d, 6> frustumPlanes() const;
    // Focal lengths in pixels (fx from the horizontal FOV, square pixels).
    double focalLengthPixels() const;
    // Projects a world point to continuous pixel coordinates (u right, v down, pixel centres at +0.5)
    // and returns its depth along the optical axis.
    Eigen::Vector3d project(const Eigen::Vector3d& world) const;
};

// The points each pixel samples with CameraParams::spatialSamples `count` (1, 2, 4, 8 or 16), right and down
// from its centre in pixels: the centre for 1; else one sample in each row and each column of a count x count
// grid (edges near the horizontal and the vertical are resolved in count steps), spread over the square
// (camera.cpp says which patterns).
std::span<const Eigen::Vector2d> spatialSamplePattern(int count);

} // namespace sp::render
