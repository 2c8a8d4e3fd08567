#pragma once
// GLSL 4.50 sources of the render passes (raw string literals in shaders.cpp).

namespace sp::render::shaders {

inline constexpr int kMaxLights = 16;    // must match MAX_LIGHTS in the lighting shader
inline constexpr int kMaxShadowMaps = 4; // must match MAX_SHADOWS in the lighting shader

// G-buffer attachments (location = index) written by the geometry pass.
enum GBufferTarget { GPosition, GNormal, GDepth, GBaseColor, GParams, GEmissive, GIds, GBufferTargetCount };
// Lighting pass outputs.
enum LightingTarget { LHdr, LDiffuseIllumination, LDiffuseOnly, LSpecularResidual, LightingTargetCount };

extern const char* const kGeometryVertex;
extern const char* const kGeometryFragment;
extern const char* const kShadowVertex;
extern const char* const kShadowFragment;
extern const char* const kFullscreenVertex;
extern const char* const kLightingFragment;
extern const char* const kTonemapFragment;

} // namespace sp::render::shaders
