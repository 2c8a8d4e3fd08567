#include "core/render/shaders.h"

#include <array>
#include <functional>
#include <utility>

#include "core/render/instances.h"
#include "core/render/irradiance_volume.h"

namespace sp::render::shaders {
namespace {

// The per-view constants (FrameBlock in shaders.h, std140: every array element is a vec4 or mat4).
const char* const kFrameBlock = R"glsl(
#define MAX_LIGHTS 16
#define MAX_SHADOWS 16
layout(std140, binding = 0) uniform FrameBlock {
    vec4 uCameraPosition;
    vec4 uAmbient;
    vec4 uBackground;
    ivec4 uCounts; // x: lights, y: the view's layer, z: anisotropic taps in the shader (1: none), w: spatial samples
    vec4 uLightRadiance[MAX_LIGHTS];
    vec4 uLightPosition[MAX_LIGHTS];
    vec4 uLightDirection[MAX_LIGHTS];
    vec4 uLightCone[MAX_LIGHTS];
    mat4 uShadowMatrix[MAX_SHADOWS];
    vec4 uShadowParams[MAX_SHADOWS];
    vec4 uBackgroundFinal;
    vec4 uExposure;
    vec4 uVignette;
    vec4 uIrradianceVolume; // xyz: world position of probe (0, 0, 0); w: 1 / spacing
    vec4 uSkyDiffuse[9];    // the environment map's irradiance / pi, spherical harmonics up to band 2
    vec4 uEnvironment;      // xyz: the map's scale; w: its prefiltered chain's last level
};
// The light-clip position of p moved 1.5 shadow-map texels along n (turned towards the light), so that a
// surface does not shadow itself (per vertex: see shadowClips()), plus `slack` metres where the surface drawn
// is a coarser level of detail than the maps' (InstanceRecord::emissive.w), whose faces lie up to that far
// inside the full mesh.
vec4 offsetShadowClip(const int layer, vec3 p, vec3 n, float texel, float slack) {
    return uShadowMatrix[layer] * vec4(p + n * (1.5 * texel + slack), 1.0);
}
// The same for a perspective map (spot and rect lights), whose texel grows with the depth along the light's
// axis, which its clip w is: `texel` per metre of that depth. The depth is affine in p, so over a flat
// triangle the offset point's clip coordinates are too, and interpolating them from the vertices is exact
// (the distance to the light is not: interpolated across a wall of two triangles, its far corners' offset
// carried the points near the light past their casters, and their shadows vanished).
vec4 offsetPerspectiveShadowClip(const int layer, vec3 p, vec3 n, float texel, float slack) {
    vec4 c = uShadowMatrix[layer] * vec4(p, 1.0);
    return c + uShadowMatrix[layer] * vec4(n * (1.5 * texel * c.w + slack), 0.0);
}
)glsl";

// Material inputs of one submesh and the surface they give a fragment: base colour, roughness and
// metallic (texture x factor) and the shading normal.
const char* const kMaterialChunk = R"glsl(
in vec3 vWorldPosition;
in float vDepth;
in vec3 vNormal;
in vec2 vUv;
// The instance's material factors and ids (InstanceRecord), the same for every fragment of it.
flat in vec4 vBaseColor;
flat in vec4 vMaterial; // roughness, metallic, ambient occlusion, 1 / texture size (kBoxUv)
flat in vec4 vEmissive; // rgb, w: the shadow slack (offsetShadowClip())
flat in uvec2 vIds;     // object id, material id
flat in uint vRecord;   // the draw's InstanceRecord (Target::GBuffer, Target::Record)
layout(binding = 0) uniform sampler2D uBaseColorTexture;
layout(binding = 1) uniform sampler2D uRoughnessMetallicTexture;
layout(binding = 2) uniform sampler2D uNormalTexture;
#ifdef HAS_BOX_UV
// The material's textures repeat every 1 / vMaterial.w metres on the object's scaled box axes (box_uv.h).
in vec3 vBoxPosition;
in vec3 vBoxNormal;
// box_uv.h's boxAxes(), choosing the same axis with the same signs: the directions u and v run along.
mat2x3 boxAxes(vec3 n) {
    vec3 a = abs(n);
    if (a.z >= a.x && a.z >= a.y) return mat2x3(vec3(0.0, n.z < 0.0 ? 1.0 : -1.0, 0.0), vec3(-1.0, 0.0, 0.0));
    if (a.x >= a.y) return mat2x3(vec3(0.0, n.x < 0.0 ? -1.0 : 1.0, 0.0), vec3(0.0, 0.0, -1.0));
    return mat2x3(vec3(n.y < 0.0 ? 1.0 : -1.0, 0.0, 0.0), vec3(0.0, 0.0, -1.0));
}
#endif

#ifdef TEXTURED
// Anisotropic filtering in the shader (Renderer::shaderAnisotropy(), a software rasteriser's default): up to
// uCounts.z trilinear taps spread along the long axis of the pixel's footprint in the texture, each read at
// the level of detail of its share of that axis or of the short axis, whichever is longer. A floor at a
// grazing angle keeps its planks and grout, which one trilinear read blurs at the long axis's level. `dx`,
// `dy`: the uv's screen derivatives. An explicit level (textureLod), to which the sampler's bias still adds
// (a view's MipMapLODBias, the spatial samples' finer levels), costs llvmpipe less than gradients: 264-270
// against 288 ms for the default scene's 1080p surface pass.
vec4 anisotropicTexture(sampler2D t, vec2 uv, vec2 dx, vec2 dy) {
    vec2 size = vec2(textureSize(t, 0));
    vec2 tx = dx * size, ty = dy * size;
    float lx = dot(tx, tx), ly = dot(ty, ty);
    float longest = max(lx, ly), shortest = min(lx, ly);
    int taps = int(min(ceil(sqrt(longest / max(shortest, 1e-12)) - 0.01), float(uCounts.z)));
    taps = max(taps, 1);
    float lod = 0.5 * log2(max(max(longest / float(taps * taps), shortest), 1e-12));
    // A spatial sample's footprint is 1 / sqrt(N) of the pixel's along each axis: its taps spread over that
    // (the sampler's bias already reads its finer level), else the N samples' average blurs the texture over
    // twice the pixel.
    vec2 step = (lx >= ly ? dx : dy) / float(taps) * inversesqrt(float(max(uCounts.w, 1)));
    vec4 sum = vec4(0.0);
    for (int i = 0; i < taps; ++i)
        sum += textureLod(t, uv + step * (float(i) + 0.5 - 0.5 * float(taps)), lod);
    return sum / float(taps);
}
#endif

void evaluateSurface(out vec3 n, out vec3 base, out float roughness, out float metallic, out float ao) {
#ifdef HAS_BOX_UV
    // The gradients come from the position, which is continuous where the projection's axis changes (a box's
    // edge): the uvs' own would jump there and pick the coarsest mip level for the pixels along it.
    mat2x3 axes = boxAxes(vBoxNormal);
    vec2 uv = vBoxPosition * axes * vMaterial.w;
    vec2 duvdx = dFdx(vBoxPosition) * axes * vMaterial.w, duvdy = dFdy(vBoxPosition) * axes * vMaterial.w;
#define SURFACE_TEXTURE(t) textureGrad(t, uv, duvdx, duvdy)
#else
    vec2 uv = vUv;
#ifdef TEXTURED
    vec2 duvdx = dFdx(uv), duvdy = dFdy(uv); // here, where control flow is uniform
#endif
#define SURFACE_TEXTURE(t) texture(t, uv)
#endif
    // Base colour and roughness / metallic / occlusion: anisotropically where the view asks the shader to
    // (uCounts.z taps; 1: the sampler's own filtering). Normal maps stay with the sampler's: in the shader
    // they cost llvmpipe as much again as the other two and changed the default scene's SSIM by nothing.
#define FILTERED_TEXTURE(t) (uCounts.z > 1 ? anisotropicTexture(t, uv, duvdx, duvdy) : SURFACE_TEXTURE(t))
    // Two-sided shading that does not trust the mesh's winding: the geometric normal is turned towards
    // the camera and the shading normal follows it.
#if defined(FACING_FROM_WINDING) && !defined(HAS_NORMAL_TEXTURE)
    // The normals lie on their triangles' winding side (MeshData::windingSpread()), so the triangle's facing
    // says the same, without derivatives. The surface passes draw with a vertically flipped projection, which
    // makes a triangle wound towards the camera back-facing.
    n = normalize(vNormal);
    if (gl_FrontFacing) n = -n;
#else
    vec3 dpdx = dFdx(vWorldPosition), dpdy = dFdy(vWorldPosition);
    vec3 geometric = cross(dpdx, dpdy);
    vec3 toCamera = cameraPosition() - vWorldPosition;
    if (dot(geometric, toCamera) < 0.0) geometric = -geometric;
    n = normalize(vNormal);
    if (dot(n, geometric) < 0.0) n = -n;
#endif
#ifdef HAS_NORMAL_TEXTURE
    {
        // Cotangent frame (Schueler 2013) from screen derivatives (no tangent attribute needed).
        vec3 dp2perp = cross(dpdy, n), dp1perp = cross(n, dpdx);
        vec3 t = dp2perp * duvdx.x + dp1perp * duvdy.x;
        vec3 b = dp2perp * duvdx.y + dp1perp * duvdy.y;
        // t and b are the surface gradients of u and v up to 1 / dot(n, dpdx x dpdy); keep that sign,
        // which flips with the vertical projection flip and with the side the surface is seen from.
        float scale = sign(dot(n, cross(dpdx, dpdy))) * inversesqrt(max(max(dot(t, t), dot(b, b)), 1e-20));
        vec3 m = SURFACE_TEXTURE(uNormalTexture).xyz * 2.0 - 1.0;
        // Green points up in the image, i.e. towards decreasing v with the top-left uv origin.
        n = normalize(mat3(t * scale, -b * scale, n) * m);
    }
#endif
    base = vBaseColor.rgb;
#ifdef HAS_BASE_COLOR_TEXTURE
    base *= FILTERED_TEXTURE(uBaseColorTexture).rgb;
#endif
    roughness = vMaterial.x;
    metallic = vMaterial.y;
    ao = vMaterial.z;
#ifdef HAS_ROUGHNESS_METALLIC_TEXTURE
    vec4 rm = FILTERED_TEXTURE(uRoughnessMetallicTexture); // occlusion, roughness, metallic (Material)
    ao *= rm.r;
    roughness *= rm.g;
    metallic *= rm.b;
#endif
}
)glsl";

// A unit vector's octahedral coordinates (Cigolle et al. 2014): the lower hemisphere folded over the
// diagonals. The G-buffer quantises them; a compact normal target holds them (decodeOctahedralNormals()).
const char* const kOctahedralChunk = R"glsl(
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }
vec2 octahedral(vec3 n) {
    vec2 e = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z < 0.0 ? (1.0 - abs(e.yx)) * signNotZero(e) : e;
}
)glsl";

// The G-buffer texel (Target::GBuffer, R32UI): the shading normal in octahedral form (Cigolle et al. 2014),
// two 11-bit signed coordinates in bits 0-21 (within 0.05 degrees), and the draw's record in bits 22-31; all
// ones marks a pixel its fragment shaded (kGBufferRecords).
const char* const kGBufferChunk = R"glsl(
uint gbufferEncode(vec3 n, uint record) {
    vec2 e = octahedral(n);
    uvec2 q = uvec2(round(clamp(e, -1.0, 1.0) * 1023.0) + 1023.0); // 0 .. 2046
    return q.x | (q.y << 11) | (record << 22);
}
vec3 gbufferNormal(uint bits) {
    vec2 e = (vec2(bits & 0x7ffu, (bits >> 11) & 0x7ffu) - 1023.0) / 1023.0;
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
    return normalize(n);
}
)glsl";

// The G-buffer's material texel (Target::GBufferMaterial, RG32UI) of a textured draw: the base colour's
// square root, then roughness, in x and metallic and ambient occlusion in y, 8 bits each. The square root
// spends the bits where the eye does, like sRGB's curve (steps under 1% relative above 0.1), for one sqrt and
// one multiply instead of its pow() each way.
const char* const kGBufferMaterialChunk = R"glsl(
uvec2 gbufferMaterialEncode(vec3 base, float roughness, float metallic, float ao) {
    return uvec2(packUnorm4x8(vec4(sqrt(clamp(base, 0.0, 1.0)), roughness)),
                 packUnorm4x8(vec4(metallic, ao, 0.0, 0.0)));
}
void gbufferMaterialDecode(uvec2 bits, out vec3 base, out float roughness, out float metallic, out float ao) {
    vec4 a = unpackUnorm4x8(bits.x), b = unpackUnorm4x8(bits.y);
    base = a.rgb * a.rgb;
    roughness = a.a;
    metallic = b.x;
    ao = b.y;
}
)glsl";

const char* const kIrradianceChunk = R"glsl(
// The irradiance probes (IrradianceVolume::packed(): two texels per probe along x) and their blend at a
// point, mirrored by IrradianceVolume::radiance(), which says why each weight is there. In fragment and compute
// shaders, image loads rather than texel fetches: llvmpipe runs a sampler's general path for every fetched
// pixel (see shadowFactor()); a vertex shader, where images are optional, fetches texels.
#ifdef PROBES_BY_TEXTURE
layout(binding = IRRADIANCE_TEXTURE_UNIT) uniform usampler3D uIrradianceProbes;
#define PROBE_SIZE textureSize(uIrradianceProbes, 0)
#define PROBE_LOAD(c) texelFetch(uIrradianceProbes, c, 0)
#else
layout(binding = IRRADIANCE_IMAGE_UNIT, rgba32ui) uniform readonly uimage3D uIrradianceProbes;
#define PROBE_SIZE imageSize(uIrradianceProbes)
#define PROBE_LOAD(c) imageLoad(uIrradianceProbes, c)
#endif
void irradianceBlend(vec3 p, vec3 n, out vec3 constant, out mat3 linear) {
    ivec3 counts = PROBE_SIZE / ivec3(2, 1, 1);
    vec3 g = clamp((p - uIrradianceVolume.xyz) * uIrradianceVolume.w + n * IRRADIANCE_NORMAL_OFFSET, vec3(0.0),
                   vec3(counts - 1));
    ivec3 base = min(ivec3(g), counts - 2);
    vec3 f = g - vec3(base);
    constant = vec3(0.0);
    linear = mat3(0.0);
    float total = 0.0;
    for (int i = 0; i < 8; ++i) {
        ivec3 o = ivec3(i & 1, (i >> 1) & 1, i >> 2);
        ivec3 c = base + o;
        vec3 t = mix(1.0 - f, f, vec3(o));
        vec3 d = g - vec3(c); // from the probe to the point, in cells
        uvec4 a = PROBE_LOAD(ivec3(2 * c.x, c.y, c.z));
        uvec4 b = PROBE_LOAD(ivec3(2 * c.x + 1, c.y, c.z));
        vec4 free0 = unpackUnorm4x8(b.z) * IRRADIANCE_MAX_FREE;
        vec2 free1 = unpackUnorm4x8(b.w).xy * IRRADIANCE_MAX_FREE;
        vec3 reach = mix(vec3(free0.x, free0.z, free1.x), vec3(free0.y, free0.w, free1.y),
                         greaterThanEqual(d, vec3(0.0)));
        vec3 excess = abs(d) - reach;
        float visible = clamp(1.0 - 4.0 * max(max(excess.x, excess.y), excess.z), 0.0, 1.0);
        float len = length(d);
        float front = (len > 1e-4 ? dot(-d, n) / len : 1.0) * 0.5 + 0.5;
        float w = t.x * t.y * t.z * (visible * (front * front + 0.2) + 1e-3);
        vec2 h0 = unpackHalf2x16(a.x), h1 = unpackHalf2x16(a.y), h2 = unpackHalf2x16(a.z);
        vec2 h3 = unpackHalf2x16(a.w), h4 = unpackHalf2x16(b.x), h5 = unpackHalf2x16(b.y);
        constant += w * vec3(h0, h1.x);
        linear += w * mat3(vec3(h1.y, h2), vec3(h3, h4.x), vec3(h4.y, h5));
        total += w;
    }
    float inverse = 1.0 / total;
    constant *= inverse;
    linear *= inverse;
}
)glsl";

// The environment map (environment_map.h): directions to its equirectangular coordinates (row 0 the zenith,
// the centre column +X, clockwise seen from above), the diffuse term from its spherical harmonics
// (Ramamoorthi and Hanrahan 2001) and the specular term from its chain prefiltered by roughness (Karis 2013).
const char* const kEnvironmentChunk = R"glsl(
layout(binding = ENVIRONMENT_SPECULAR_UNIT) uniform sampler2D uEnvironmentSpecular;
vec2 environmentUv(vec3 d) {
    const float INV_PI = 0.318309886183791;
    // atan(0, 0) is undefined in GLSL: straight up or down (a mirror floor seen from above) reads u = 0.5.
    return vec2(0.5 - atan(d.y, abs(d.x) + abs(d.y) > 0.0 ? d.x : 1.0) * (0.5 * INV_PI),
                acos(clamp(d.z, -1.0, 1.0)) * INV_PI);
}
vec3 skyDiffuse(vec3 n) {
    vec3 r = uSkyDiffuse[0].xyz * 0.282095 +
             (uSkyDiffuse[1].xyz * n.y + uSkyDiffuse[2].xyz * n.z + uSkyDiffuse[3].xyz * n.x) * 0.488603 +
             (uSkyDiffuse[4].xyz * (n.x * n.y) + uSkyDiffuse[5].xyz * (n.y * n.z) +
              uSkyDiffuse[7].xyz * (n.x * n.z)) * 1.092548 +
             uSkyDiffuse[6].xyz * (0.315392 * (3.0 * n.z * n.z - 1.0)) +
             uSkyDiffuse[8].xyz * (0.546274 * (n.x * n.x - n.y * n.y));
    return max(r, 0.0);
}
vec3 skySpecular(vec3 r, float roughness) {
    return textureLod(uEnvironmentSpecular, environmentUv(r), roughness * uEnvironment.w).rgb * uEnvironment.xyz;
}
)glsl";

// The environment map along the ray through a pixel (window coordinates of its centre), for the passes that
// draw the background: they declare uClipToOffset (clip space to the world position relative to the camera)
// and uSize (the framebuffer's size); uBackgroundLod is the full map's level whose texels are about a pixel.
const char* const kEnvironmentBackgroundChunk = R"glsl(
layout(binding = ENVIRONMENT_BACKGROUND_UNIT) uniform sampler2D uEnvironmentBackground;
uniform float uBackgroundLod;
vec3 backgroundRadiance(vec2 pixelCentre) {
    // Through the point on the near plane: at the far plane w is a difference of nearly equal terms.
    vec4 o = uClipToOffset * vec4(pixelCentre / vec2(uSize) * 2.0 - 1.0, -1.0, 1.0);
    return textureLod(uEnvironmentBackground, environmentUv(normalize(o.xyz / o.w)), uBackgroundLod).rgb *
           uEnvironment.xyz;
}
)glsl";

// Karis 2013 ("Real shading in Unreal Engine 4"): GGX distribution, Smith-Schlick visibility with
// k = (roughness + 1)^2 / 8, Schlick Fresnel with the spherical Gaussian exponent; the ambient sky term
// uses Karis' analytic environment BRDF approximation.
const char* const kShadingChunk = R"glsl(
const float PI = 3.14159265358979;
// Depths, compared in shadowFactor(); SHADOW_FORMAT is the maps' image format (see ShadowMaps).
layout(binding = 0, SHADOW_FORMAT) uniform readonly image2DArray uShadowMaps;

vec3 fSchlick(vec3 f0, float voh) {
    float m = 1.0 - voh, m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}
vec3 envBrdfApprox(vec3 f0, float roughness, float nov) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * nov)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return f0 * ab.x + ab.y;
}
// Rounds to float16 so that diffuse_only = albedo * diffuse_illumination holds for the stored values
// (only when diffuse_only is written; colour skips the conversions).
vec3 toHalf(vec3 v) {
#ifndef EXACT_INTRINSICS
    return v;
#endif
    return vec3(unpackHalf2x16(packHalf2x16(v.xy)), unpackHalf2x16(packHalf2x16(vec2(v.z, 0.0))).x);
}

// One bilinear percentage-closer tap at s, the point's shadow-map coordinates ([0, 1]^3, after the
// normal offset): the four texels around the point are loaded, clamped to the map's edge, compared with
// the point's depth and the results blended bilinearly. Four imageLoads rather than one textureGather:
// llvmpipe runs a sampler's general path (wrap modes, formats, filtering state) for every gathered pixel,
// and the loads cost far less (spear_render_bench, 1080p final_color with a shadowed sun and spot light:
// 38-40 -> 35-37 ms, 33-35 with 16-bit maps); on a GPU both are a few instructions.
float shadowTap(const int layer, float size, vec3 s) {
    if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0)))) return 1.0;
    vec2 t = s.xy * size - 0.5;
    vec2 cell = floor(t);
    vec2 f = t - cell;
    ivec2 c0 = max(ivec2(cell), 0), c1 = min(ivec2(cell) + 1, int(size) - 1);
    int z = firstShadowLayer() + layer; // the scene's maps are a run of layers of a shared array
    vec4 d = vec4(imageLoad(uShadowMaps, ivec3(c0.x, c0.y, z)).r, imageLoad(uShadowMaps, ivec3(c1.x, c0.y, z)).r,
                  imageLoad(uShadowMaps, ivec3(c0.x, c1.y, z)).r, imageLoad(uShadowMaps, ivec3(c1.x, c1.y, z)).r);
    vec4 lit = vec4(greaterThanEqual(d, vec4(s.z))); // lit where the point is not behind the map's depth
    // a + t (b - a) rather than mix(), which a driver may expand to a (1 - t) + b t: exactly 1.0 where all
    // four texels are lit, as a program without the lookups has it (see shadow_reach.h).
    float near = lit.x + f.x * (lit.y - lit.x), far = lit.z + f.x * (lit.w - lit.z);
    return near + f.y * (far - near);
}
float shadowFactor(const int layer, vec3 s) { return shadowTap(layer, shadowSize(layer), s); }
// A point light's shadow at p (n turned towards the light): its maps are the six faces of a cube around it,
// +x, -x, +y, -y, +z, -z from layer `first`; the face is the one along the major axis of p - light, and
// its coordinates are computed here (a triangle may span faces, so the vertex shader cannot interpolate
// them). Every map has the resolution of the first (ShadowMaps), so the size is read there.
float pointShadowFactor(const int first, vec3 light, vec3 p, vec3 n, float slack) {
    vec3 q = p - light, a = abs(q);
    int face = a.x >= a.y && a.x >= a.z ? (q.x >= 0.0 ? 0 : 1) : a.y >= a.z ? (q.y >= 0.0 ? 2 : 3) : (q.z >= 0.0 ? 4 : 5);
    int layer = first + face;
    vec4 c = offsetPerspectiveShadowClip(layer, p, n, uShadowParams[layer].x, slack);
    return shadowTap(layer, shadowSize(0), (c.xyz / c.w) * 0.5 + 0.5);
}


struct Shaded {
    vec3 hdr;                 // linear radiance towards the camera
    vec3 diffuseIllumination; // of a white Lambertian surface, rounded to float16
    vec3 diffuseOnly;         // base * (1 - metallic) * diffuseIllumination
};

// The HDR and intrinsic targets of a shaded point.
void writeShaded(Shaded s) {
#ifdef OUT_Hdr
    oHdr = halfTarget(vec4(s.hdr, 1.0));
#endif
#ifdef OUT_DiffuseIllumination
    oDiffuseIllumination = halfTarget(vec4(s.diffuseIllumination, 1.0));
#endif
#ifdef OUT_DiffuseOnly
    oDiffuseOnly = halfTarget(vec4(s.diffuseOnly, 1.0));
#endif
#ifdef OUT_SpecularResidual
    oSpecularResidual = halfTarget(vec4(s.hdr - s.diffuseOnly, 1.0));
#endif
}

struct Surface {
    vec3 p, n, v, f0;
    float nov, a2, k;
    float specularScale; // a2 / (4 PI (nov (1 - k) + k)): see accumulate()
};

// Adds one light of irradiance e (at normal incidence) from direction l: D * G * F / (4 nol nov), times
// the irradiance e * nol. With D = a2 / (PI d^2), d = noh^2 (a2 - 1) + 1, and G the product of
// g1Schlick(nol) and g1Schlick(nov), the nol and nov cancel:
//   D * G / (4 nov) = specularScale * nol / (d^2 (nol (1 - k) + k)),
// specularScale = a2 / (4 PI (nov (1 - k) + k)) being the point's (see shade()). One division a light
// instead of six: a software rasteriser's divisions share one unit and were the shading's costliest
// instructions.
void accumulateSpecular(Surface s, vec3 l, vec3 e, float nol, inout vec3 specular) {
    vec3 h = normalize(s.v + l);
    float noh = max(dot(s.n, h), 0.0), voh = max(dot(s.v, h), 0.0);
    float d = noh * noh * (s.a2 - 1.0) + 1.0;
    float dg = s.specularScale * nol / (d * d * (nol * (1.0 - s.k) + s.k));
    specular += dg * fSchlick(s.f0, voh) * e;
}
void accumulate(Surface s, vec3 l, vec3 e, float nol, inout vec3 irradiance, inout vec3 specular) {
    irradiance += e * nol;
    accumulateSpecular(s, l, e, nol, specular);
}

// A rect light of radiance `radiance` whose corners are c +- ex +- ey from the point (c its centre), shining
// along cross(ex, ey). Its diffuse term is exact: the cosine-weighted solid angle of the rectangle clipped to
// the surface's horizon (Lambert's formula for a polygon), so that soft light falls off as the path tracer's
// does. Its specular term is a point light at the rectangle's point nearest the mirror ray, the lobe
// widened by the light's size and scaled to keep its energy (Karis 2013, "representative point").
void rectLight(Surface s, vec3 c, vec3 ex, vec3 ey, vec3 radiance, inout vec3 irradiance, inout vec3 specular) {
    vec3 nl = normalize(cross(ex, ey));
    if (dot(c, nl) >= 0.0)
        return; // behind the panel: it shines one way
    vec3 corners[4] = vec3[4](c - ex - ey, c + ex - ey, c + ex + ey, c - ex + ey);
    vec3 clipped[5];
    int count = 0;
    for (int i = 0; i < 4; ++i) { // Sutherland-Hodgman against the horizon plane
        vec3 a = corners[i], b = corners[(i + 1) & 3];
        float da = dot(a, s.n), db = dot(b, s.n);
        if (da > 0.0)
            clipped[count++] = a;
        if ((da > 0.0) != (db > 0.0))
            clipped[count++] = a + (b - a) * (da / (da - db));
    }
    float cosineSolidAngle = 0.0;
    for (int i = 0; i < count; ++i) { // each edge's angle (atan2: exact for small ones) times its normal's cosine
        vec3 a = clipped[i], b = clipped[i + 1 < count ? i + 1 : 0];
        vec3 g = cross(a, b);
        float len = length(g);
        if (len > 0.0)
            cosineSolidAngle += atan(len, dot(a, b)) * dot(g, s.n) / len;
    }
    irradiance += radiance * abs(0.5 * cosineSolidAngle);

    vec3 r = reflect(-s.v, s.n);
    float rn = dot(r, nl);
    vec3 q = rn < -1e-4 ? r * (dot(c, nl) / rn) : c; // the mirror ray meets the panel's plane at q
    vec3 offset = q - c;
    q = c + ex * clamp(dot(offset, ex) / dot(ex, ex), -1.0, 1.0) + ey * clamp(dot(offset, ey) / dot(ey, ey), -1.0, 1.0);
    float alpha = sqrt(s.a2);
    q = mix(q, c, s.a2); // a wide lobe sees the whole panel, not its brightest point: towards the centre
    float dist2 = max(dot(q, q), 1e-8);
    float dist = sqrt(dist2);
    vec3 l = q / dist;
    float nol = dot(s.n, l), cosLight = -dot(l, nl);
    if (nol > 0.0 && cosLight > 0.0) {
        float area = 4.0 * length(ex) * length(ey);
        float widened = min(alpha + sqrt(area / PI) / (2.0 * dist), 1.0);
        float energy = (alpha / widened) * (alpha / widened);
        accumulateSpecular(s, l, radiance * (area * cosLight / max(dist2, 1e-4) * energy), nol, specular);
    }
}
)glsl";

// Exposure, tone curve (ACES: Narkowicz's fit; Reinhard; linear clamp, TONE_CURVE 0, 1, 2) and the sRGB OETF.
// PIXEL_CENTRE is the pixel's window position (gl_FragCoord.xy unless a compute pass defines it).
// The sRGB OETF; above the linear segment, 1.055 c^(1/2.4) - 0.055 is fitted with square roots (within
// 0.25 of one 8-bit step), which cost a software rasteriser far less than pow(). Used by the tone curve and
// the background passes (the resolve encodes exactly: resolveFragment()).
const char* const kSrgbEncodeChunk = R"glsl(
vec3 srgbEncode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
    vec3 curve = 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * c;
    return mix(c * 12.92, curve, step(vec3(0.0031308), c));
}
)glsl";

const std::string kToneChunk = std::string(kSrgbEncodeChunk) + R"glsl(
#ifndef PIXEL_CENTRE
#define PIXEL_CENTRE gl_FragCoord.xy
#endif
vec3 aces(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec4 toneMapped(vec3 hdr) {
    vec3 x = max(hdr, 0.0) * exposureGains();
#ifdef VIGNETTE
    // The cos^4 falloff of the pixel's ray (tone.h, Vignette); row 0 of the image is GL's bottom row.
    vec4 vignette = vignetteParams();
    vec2 d = (PIXEL_CENTRE - vignette.zw) / vignette.y;
    float cos2 = 1.0 / (1.0 + dot(d, d));
    x *= 1.0 + (cos2 * cos2 - 1.0) * vignette.x;
#endif
#if TONE_CURVE == 0
    vec3 mapped = aces(x);
#elif TONE_CURVE == 1
    vec3 mapped = x / (1.0 + x);
#else
    vec3 mapped = clamp(x, 0.0, 1.0);
#endif
    return vec4(srgbEncode(mapped), 1.0);
}
)glsl";

// Positions are transformed with matrices composed in double precision on the CPU (InstanceRecord): the
// depth row gives the distance along the optical axis from camera-relative coordinates, so depth keeps
// float precision far from the world origin. The instance's fields arrive as instanced attributes
// (instanceAttributes()).
const char* const kSurfaceVertex = R"glsl(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
out vec3 vWorldPosition;
out float vDepth;
out vec3 vNormal;
out vec2 vUv;
flat out vec4 vBaseColor;
flat out vec4 vMaterial;
flat out vec4 vEmissive;
flat out uvec2 vIds;
flat out uint vRecord;
#ifdef HAS_BOX_UV
out vec3 vBoxPosition;
out vec3 vBoxNormal;
#endif
// The attribute pass draws the geometry again against the surface pass's depth, with another program:
// both must compute the same depth bit for bit.
invariant gl_Position;
void main() {
    vec4 p = vec4(aPosition, 1.0);
    vWorldPosition = vec3(dot(iModelRow0, p), dot(iModelRow1, p), dot(iModelRow2, p));
    vDepth = dot(iDepthRow, p);
    // Normals transform by the inverse transpose of the model's linear part; its cofactor matrix (columns
    // c1 x c2, c2 x c0, c0 x c1) is that times the determinant, a scale that normalize() removes and
    // whose sign the two-sided shading ignores (normals are turned towards the camera and the light).
    vec3 c0 = vec3(iModelRow0.x, iModelRow1.x, iModelRow2.x);
    vec3 c1 = vec3(iModelRow0.y, iModelRow1.y, iModelRow2.y);
    vec3 c2 = vec3(iModelRow0.z, iModelRow1.z, iModelRow2.z);
    vNormal = mat3(cross(c1, c2), cross(c2, c0), cross(c0, c1)) * aNormal;
    vUv = aUv;
#ifdef HAS_BOX_UV
    // The object's scaled frame (box_uv.h): its own axes, in metres.
    vec3 scale = vec3(length(c0), length(c1), length(c2));
    vBoxPosition = aPosition * scale;
    vBoxNormal = aNormal / scale;
#endif
    vBaseColor = iBaseColor;
    vMaterial = iMaterial;
    vEmissive = iEmissive;
    vIds = iIds.xy;
    vRecord = iIds.z;
    gl_Position = iModelViewProjection * p;
#ifdef VERTEX_IRRADIANCE
    {
        // The probes' light for the normal and the mirror direction of the side the camera sees, evaluated
        // here and interpolated: two varyings rather than the blend's four (the probes hold bands 0 and 1,
        // smooth over a probe spacing, so what a pixel's own normal would add is second order).
        vec3 toCamera = uCameraPosition.xyz - vWorldPosition;
        vec3 n = normalize(vNormal);
        if (dot(n, toCamera) < 0.0) n = -n;
        vec3 constant;
        mat3 linear;
        irradianceBlend(vWorldPosition, n, constant, linear);
        vAmbientDiffuse = max(constant + linear * n, 0.0);
        vAmbientSpecular = max(constant + linear * reflect(-normalize(toCamera), n), 0.0);
    }
#endif
    SHADOW_CLIPS
    CONSTANT_COPIES
    VIEW_LAYER
}
)glsl";

const char* const kSurfaceMain = R"glsl(
void main() {
    vec3 n, base;
    float roughness, metallic, ao;
    evaluateSurface(n, base, roughness, metallic, ao);
#ifdef OUT_Position
    oPosition = vec4(vWorldPosition, 1.0);
#endif
#ifdef OUT_Normal
    oNormal = normalTarget(n);
#endif
#ifdef OUT_Depth
    oDepth = vDepth;
#endif
#ifdef OUT_BaseColor
    oBaseColor = halfTarget(vec4(base, 1.0));
#endif
#ifdef OUT_Params
    oParams = halfTarget(vec4(roughness, metallic, ao, 0.0));
#endif
#ifdef OUT_Ids
    oIds = vIds;
#endif
#ifdef OUT_Record
    oRecord = vRecord + 1u;
#endif
#ifdef OUT_GBuffer
#ifdef FORWARD
    oGBuffer = 0xffffffffu; // shaded here (past kGBufferRecords, or no room for the material): the compute pass skips it
#else
    oGBuffer = gbufferEncode(n, vRecord);
#endif
#endif
#if defined(OUT_GBufferMaterial) && !defined(FORWARD) && defined(TEXTURED)
    oGBufferMaterial = gbufferMaterialEncode(base, roughness, metallic, ao);
#endif
#ifdef FORWARD
#ifdef EXACT_INTRINSICS
    // Shade with the inputs as the float16 targets store them (see toHalf()).
    base = toHalf(base);
    metallic = unpackHalf2x16(packHalf2x16(vec2(metallic, 0.0))).x;
#endif
    Shaded s = shade(vWorldPosition, n, base, roughness, metallic, ao * screenOcclusion(gl_FragCoord.xy, base),
                     vEmissive.rgb, vEmissive.w);
    writeShaded(s);
#ifdef OUT_FinalColor
    oFinalColor = toneMapped(s.hdr);
#endif
#endif
}
)glsl";

// The instanced attributes of InstanceRecord, at the locations instances.h gives them.
std::string instanceAttributes() {
    auto at = [](unsigned location) { return "layout(location = " + std::to_string(location) + ") in "; };
    return at(kInstanceModelViewProjection) + "mat4 iModelViewProjection;\n" + at(kInstanceModelRows) +
           "vec4 iModelRow0;\n" + at(kInstanceModelRows + 1) + "vec4 iModelRow1;\n" +
           at(kInstanceModelRows + 2) + "vec4 iModelRow2;\n" + at(kInstanceDepthRow) + "vec4 iDepthRow;\n" +
           at(kInstanceBaseColor) + "vec4 iBaseColor;\n" + at(kInstanceMaterial) + "vec4 iMaterial;\n" +
           at(kInstanceEmissive) + "vec4 iEmissive;\n" + at(kInstanceIds) + "uvec4 iIds;\n";
}

// What a float16 target and the normal target store of a value: halfTarget() and normalTarget().
const char* const kFloatEncodings = R"glsl(
vec4 halfTarget(vec4 v) { return v; }
vec4 normalTarget(vec3 n) { return vec4(n, 0.0); }
)glsl";
// Compact targets (PassSet::compactTargets): a float16 target holds its channels' float16 bits, as
// packHalf2x16 rounds them; the normal target a unit vector's octahedral coordinates.
const char* const kCompactEncodings = R"glsl(
uvec4 halfTarget(vec4 v) {
    uvec2 p = uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw));
    return uvec4(p.x & 0xffffu, p.x >> 16, p.y & 0xffffu, p.y >> 16);
}
vec2 normalTarget(vec3 n) { return octahedral(n); }
)glsl";

// halfTarget() and normalTarget() for float or compact targets, and what they use.
std::string encodings(bool compact) {
    return std::string(kOctahedralChunk) + (compact ? kCompactEncodings : kFloatEncodings);
}

// The GLSL type of a target's fragment output.
const char* outputType(Target target, bool compact) {
    if (target == Target::Ids || target == Target::GBufferMaterial)
        return "uvec2";
    if (target == Target::GBuffer || target == Target::Record)
        return "uint";
    if (target == Target::Depth)
        return "float";
    if (compact && target == Target::Normal)
        return "vec2";
    if (compact && (kHalfTargets & targetBit(target)) != 0)
        return "uvec4";
    return "vec4";
}

// "#define OUT_<Target>" and "layout(location = k) out <type> o<Target>;" for each target in the mask,
// at consecutive locations in Target order (the order Framebuffers attaches them in), and the encodings.
std::string outputs(TargetMask targets, bool compact) {
    std::string text = encodings(compact);
    int location = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((targets & (TargetMask(1) << t)) == 0)
            continue;
        const auto target = static_cast<Target>(t);
        const std::string name(targetName(target));
        const char* type = outputType(target, compact);
        text += "#define OUT_" + name + "\nlayout(location = " + std::to_string(location++) + ") out " +
                type + " o" + name + ";\n";
    }
    return text;
}

// The shadow-map layers a layout samples through the vertex shader's interpolated coordinates (a point
// light's faces are looked up per pixel: pointShadowFactor()).
std::vector<int> shadowLayers(const ShadingLayout& lights) {
    std::vector<int> layers;
    for (const LightSlot& light : lights.lights)
        if (light.shadowLayer >= 0 && light.type != LightType::Point)
            layers.push_back(light.shadowLayer);
    return layers;
}

// "out vec4 vShadowClipK;" (or "in") for each layer a forward variant samples: only those are interpolated.
std::string shadowClipDeclarations(bool forward, const ShadingLayout& lights, const char* direction) {
    std::string text;
    if (forward)
        for (int layer : shadowLayers(lights))
            text += std::string(direction) + " vec4 vShadowClip" + std::to_string(layer) + ";\n";
    return text;
}

// The GLSL for the offset clip coordinates of the point p (with normal n turned towards the light) in a
// light's shadow map: a directional light's texel is fixed, a spot or rect light's grows with the depth
// (uShadowParams[layer].x: per metre).
std::string offsetShadowClipCall(const LightSlot& light, const std::string& p, const std::string& n,
                                 const std::string& slack) {
    const std::string layer = std::to_string(light.shadowLayer);
    return std::string(light.type == LightType::Directional ? "offsetShadowClip("
                                                            : "offsetPerspectiveShadowClip(") +
           layer + ", " + p + ", " + n + ", uShadowParams[" + layer + "].x, " + slack + ")";
}

// The forward vertex shader's shadow-map coordinates for each shadowed light, in homogeneous form
// (x, y, z already mapped to [0, 1] times w): the vertex moved 1.5 texels along its normal, turned
// towards the light, then projected. Interpolating them is exact over a flat triangle for a directional light
// (affine) and for a spot or rect light (projective, divided per fragment; its offset grows with the depth,
// which is affine too: offsetPerspectiveShadowClip()), and spares every fragment a matrix product.
std::string shadowClips(const ShadingLayout& lights) {
    std::string text;
    for (std::size_t i = 0; i < lights.lights.size(); ++i) {
        const LightSlot& light = lights.lights[i];
        if (light.shadowLayer < 0 || light.type == LightType::Point)
            continue;
        const std::string at = "[" + std::to_string(i) + "]", layer = std::to_string(light.shadowLayer);
        const std::string toLight = light.type == LightType::Directional
                                        ? "-uLightDirection" + at + ".xyz"
                                        : "uLightPosition" + at + ".xyz - vWorldPosition";
        text += " { vec3 l = " + toLight +
                "; vec3 n = normalize(vNormal); if (dot(n, l) < 0.0) n = -n; vec4 c = " +
                offsetShadowClipCall(light, "vWorldPosition", "n", "iEmissive.w") + "; vShadowClip" + layer +
                " = vec4((c.xyz + c.w) * 0.5, c.w); }";
    }
    return text;
}

// Where a program reads the per-view constants (ShadingLayout::constantSlots). With slots to spend, the
// vertex shader copies them from FrameBlock into flat varyings: fFrame (camera position, ambient, exposure
// gains, vignette), fShadowSizes (each map's resolution, by layer) and fLights, for as many lights as fit.
// Lights past the budget, and every constant when there is none, are read from FrameBlock.
struct ConstantPlan {
    bool flat = false;
    int frameSlots = 0;         // fFrame elements: 1 (camera position) without shading, 3 with, 4 vignetted
    bool shadowSizes = false;   // fShadowSizes is written (a shaded variant with shadows)
    std::vector<int> lightSlot; // each light's first fLights element, -1 where it reads FrameBlock
    int lightSlots = 0;         // fLights elements
};

// fLights elements of a light: radiance (and a spot's cos(outer) in w), then a directional light's
// direction, or a point, spot or rect light's position and 1 / range, then a spot's direction and
// 1 / (cos(inner) - cos(outer)), or a rect's two half extents (FrameBlock's values, element for element).
int lightSlotCount(LightType type) {
    return type == LightType::Rect ? 4 : type == LightType::Spot ? 3 : 2;
}

ConstantPlan planConstants(bool forward, const ShadingLayout& layout) {
    ConstantPlan plan;
    plan.frameSlots = !forward ? 1 : layout.vignette ? 4 : 3;
    plan.shadowSizes = forward && !shadowLayers(layout).empty();
    // Per-vertex indirect light takes two varyings of the budget (vAmbientDiffuse, vAmbientSpecular).
    const int volume = forward && layout.irradiance == IrradianceBlend::PerVertex ? 2 : 0;
    int left = layout.constantSlots - plan.frameSlots - (plan.shadowSizes ? 1 : 0) - volume;
    plan.flat = left >= 0;
    plan.lightSlot.assign(layout.lights.size(), -1);
    if (!plan.flat || !forward)
        return plan;
    for (std::size_t i = 0; i < layout.lights.size(); ++i) {
        const int count = lightSlotCount(layout.lights[i].type);
        if (count > left)
            break; // the rest read FrameBlock, in order, so that the plan is a prefix of the lights
        plan.lightSlot[i] = plan.lightSlots;
        plan.lightSlots += count;
        left -= count;
    }
    return plan;
}

// The GLSL expressions for one light's constants (vec3 radiance, position, direction; float 1 / range;
// vec2 cos(outer), 1 / (cos(inner) - cos(outer)): see FrameBlock), from fLights or FrameBlock.
struct LightTerms {
    std::string radiance, position, inverseRange, direction, cone;
    std::string halfUp; // a rect light's (its half right is `direction`)
};

LightTerms lightTerms(const ShadingLayout& layout, const ConstantPlan& plan, std::size_t i) {
    const int k = plan.lightSlot[i];
    if (k < 0) {
        const std::string at = "[" + std::to_string(i) + "]";
        return {"uLightRadiance" + at + ".xyz",  "uLightPosition" + at + ".xyz", "uLightPosition" + at + ".w",
                "uLightDirection" + at + ".xyz", "uLightCone" + at + ".xy",      "uLightCone" + at + ".xyz"};
    }
    auto slot = [](int element, const char* swizzle) {
        return "fLights[" + std::to_string(element) + "]." + swizzle;
    };
    if (layout.lights[i].type == LightType::Directional)
        return {slot(k, "xyz"), "", "", slot(k + 1, "xyz"), "", ""};
    if (layout.lights[i].type == LightType::Rect)
        return {slot(k, "xyz"),    slot(k + 1, "xyz"), slot(k + 1, "w"), slot(k + 2, "xyz"), "",
                slot(k + 3, "xyz")};
    return {slot(k, "xyz"),
            slot(k + 1, "xyz"),
            slot(k + 1, "w"),
            slot(k + 2, "xyz"),
            "vec2(" + slot(k, "w") + ", " + slot(k + 2, "w") + ")",
            ""};
}

// The flat varyings of a plan ("out" in the vertex shader, "in" in the fragment shader).
std::string constantDeclarations(const ConstantPlan& plan, const char* direction) {
    if (!plan.flat)
        return "";
    const std::string flat = std::string("flat ") + direction + " vec4 ";
    std::string text = flat + "fFrame[" + std::to_string(plan.frameSlots) + "];\n";
    if (plan.shadowSizes)
        text += flat + "fShadowSizes;\n";
    if (plan.lightSlots > 0)
        text += flat + "fLights[" + std::to_string(plan.lightSlots) + "];\n";
    return text;
}

// The vertex shader's copies from FrameBlock into the flat varyings.
std::string constantCopies(const ShadingLayout& layout, const ConstantPlan& plan) {
    if (!plan.flat)
        return "";
    std::string text = " fFrame[0] = uCameraPosition;";
    if (plan.frameSlots >= 3)
        text += " fFrame[1] = uAmbient; fFrame[2] = uExposure;";
    if (plan.frameSlots == 4)
        text += " fFrame[3] = uVignette;";
    if (plan.shadowSizes)
        text += " fShadowSizes = vec4(uShadowParams[0].y, uShadowParams[1].y, uShadowParams[2].y,"
                " uShadowParams[3].y);";
    for (std::size_t i = 0; i < layout.lights.size(); ++i) {
        const int k = plan.lightSlot[i];
        if (k < 0)
            continue;
        const std::string at = "[" + std::to_string(i) + "]";
        auto slot = [&](int offset) { return " fLights[" + std::to_string(k + offset) + "] = "; };
        switch (layout.lights[i].type) {
        case LightType::Directional:
            text += slot(0) + "uLightRadiance" + at + ";" + slot(1) + "uLightDirection" + at + ";";
            break;
        case LightType::Point:
            text += slot(0) + "uLightRadiance" + at + ";" + slot(1) + "uLightPosition" + at + ";";
            break;
        case LightType::Spot:
            text += slot(0) + "vec4(uLightRadiance" + at + ".xyz, uLightCone" + at + ".x);" + slot(1) +
                    "uLightPosition" + at + ";" + slot(2) + "vec4(uLightDirection" + at + ".xyz, uLightCone" +
                    at + ".y);";
            break;
        case LightType::Rect:
            text += slot(0) + "uLightRadiance" + at + ";" + slot(1) + "uLightPosition" + at + ";" + slot(2) +
                    "uLightDirection" + at + ";" + slot(3) + "uLightCone" + at + ";";
            break;
        }
    }
    return text;
}

// The fragment shader's accessors of the view's constants (cameraPosition(), ambientRadiance(),
// exposureGains(), vignetteParams(), shadowSize(layer), firstShadowLayer()), from the flat varyings or
// FrameBlock.
std::string constantAccessors(const ConstantPlan& plan) {
    const bool frame = plan.flat && plan.frameSlots >= 3, vignette = plan.flat && plan.frameSlots == 4;
    const bool sizes = plan.flat && plan.shadowSizes;
    auto accessor = [](const char* signature, const std::string& value) {
        return std::string(signature) + " { return " + value + "; }\n";
    };
    return accessor("vec3 cameraPosition()", plan.flat ? "fFrame[0].xyz" : "uCameraPosition.xyz") +
           accessor("int firstShadowLayer()", plan.flat ? "int(fFrame[0].w)" : "int(uCameraPosition.w)") +
           accessor("vec3 ambientRadiance()", frame ? "fFrame[1].xyz" : "uAmbient.xyz") +
           accessor("vec3 exposureGains()", frame ? "fFrame[2].xyz" : "uExposure.xyz") +
           accessor("vec4 vignetteParams()", vignette ? "fFrame[3]" : "uVignette") +
           accessor("float shadowSize(const int layer)",
                    sizes ? "fShadowSizes[layer]" : "uShadowParams[layer].y");
}

// The GLSL that scales a point, spot or rect light's irradiance e by its range window, (1 - (d / range)^4)^2,
// of the distance `dist` (the light's terms hold 1 / range).
std::string rangeWindow(const LightTerms& terms, const std::string& indent) {
    return indent + "float r = dist * " + terms.inverseRange + ";\n" + indent +
           "float w = clamp(1.0 - r * r * r * r, 0.0, 1.0);\n" + indent + "e *= w * w;\n";
}

// The GLSL that scales e by a shadowed light's shadow factor at p: from the vertex shader's interpolated
// coordinates (see shadowClips()), or with `perPixelShadows` computed here the same way, `n` being the GLSL
// for the normal turned towards the light. Only a perspective map's coordinates need the division by w.
std::string shadowLookup(const LightSlot& light, bool perPixelShadows, const std::string& n,
                         const std::string& indent) {
    const std::string layer = std::to_string(light.shadowLayer);
    std::string text, clip = "vShadowClip" + layer;
    if (perPixelShadows) {
        text = indent + "vec4 sc = " + offsetShadowClipCall(light, "p", n, "slack") + ";\n" + indent +
               "sc = vec4((sc.xyz + sc.w) * 0.5, sc.w);\n";
        clip = "sc";
    }
    const std::string coordinates =
        light.type == LightType::Directional ? clip + ".xyz" : clip + ".xyz / " + clip + ".w";
    return text + indent + "e *= shadowFactor(" + layer + ", " + coordinates + ");\n";
}

// shade(): the shading of one surface point by the layout's lights, unrolled with each light's type,
// range and shadow layer fixed, and the sky term. The shadow-map coordinates are the vertex shader's,
// interpolated (shadowClips()), or with `perPixelShadows` (the compute lighting pass, which has no vertices)
// computed here the same way from the point and its normal.
std::string shadeFunction(const ShadingLayout& layout, const ConstantPlan& plan,
                          bool perPixelShadows = false) {
    std::string text = R"glsl(
Shaded shade(vec3 p, vec3 n, vec3 base, float roughness, float metallic, float ao, vec3 emissive, float slack) {
    Surface s;
    s.p = p;
    s.n = n;
    s.v = normalize(cameraPosition() - p);
    s.nov = max(dot(n, s.v), 1e-4);
    s.f0 = mix(vec3(0.04), base, metallic);
    float a = max(roughness * roughness, 0.002);
    s.a2 = a * a;
    s.k = (roughness + 1.0) * (roughness + 1.0) * 0.125;
    s.specularScale = s.a2 / (4.0 * PI * (s.nov * (1.0 - s.k) + s.k));
    vec3 irradiance = vec3(0.0), specular = vec3(0.0);
)glsl";
    for (std::size_t i = 0; i < layout.lights.size(); ++i) {
        const LightSlot& light = layout.lights[i];
        const LightTerms terms = lightTerms(layout, plan, i);
        text += "    {\n";
        if (light.type == LightType::Rect) { // its own shading (see rectLight())
            text += "        vec3 c = " + terms.position + " - p;\n";
            text += "        float dist = length(c);\n";
            text += "        vec3 e = " + terms.radiance + ";\n";
            if (light.ranged) // the window of its centre's distance, as a point light's
                text += rangeWindow(terms, "        ");
            if (light.shadowLayer >= 0) // as a spot light's map, from the panel's centre
                text += shadowLookup(light, perPixelShadows, "(dot(n, c) < 0.0 ? -n : n)", "        ");
            text += "        rectLight(s, c, " + terms.direction + ", " + terms.halfUp +
                    ", e, irradiance, specular);\n    }\n";
            continue;
        }
        if (light.type == LightType::Directional) {
            text += "        vec3 l = -" + terms.direction + ";\n";
            text += "        vec3 e = " + terms.radiance + ";\n";
        } else {
            // One division (the inverse distance) where l = d / dist and e = radiance / dist^2 took six.
            text += "        vec3 d = " + terms.position + " - p;\n";
            text += "        float dist = length(d);\n";
            text += "        float inverse = 1.0 / max(dist, 1e-6);\n";
            text += "        vec3 l = d * inverse;\n";
            text += "        vec3 e = " + terms.radiance + " * min(inverse * inverse, 1e4);\n";
            if (light.ranged) // windowed inverse square
                text += rangeWindow(terms, "        ");
            if (light.type == LightType::Spot) { // cone: cos(outer), 1 / (cos(inner) - cos(outer))
                text += "        vec2 cone = " + terms.cone + ";\n";
                text += "        float t = clamp((dot(-l, " + terms.direction +
                        ") - cone.x) * cone.y, 0.0, 1.0);\n";
                text += "        e *= t * t;\n";
            }
        }
        text += "        float nol = dot(n, l);\n        if (nol > 0.0) {\n";
        if (light.shadowLayer >= 0 && light.type == LightType::Point) // n faces the light (nol > 0)
            text += "            e *= pointShadowFactor(" + std::to_string(light.shadowLayer) + ", " +
                    terms.position + ", p, n, slack);\n";
        else if (light.shadowLayer >= 0) // n faces the light here (nol > 0), as the vertex shader turns it
            text += shadowLookup(light, perPixelShadows, "n", "            ");
        text += "            accumulate(s, l, e, nol, irradiance, specular);\n        }\n    }\n";
    }
    text += R"glsl(    Shaded result;
#if defined(IRRADIANCE_VOLUME) || defined(VERTEX_IRRADIANCE)
    // Indirect light from the probes: the diffuse term for n, the specular one for the mirror direction;
    // blended here, or at the vertices and interpolated (VERTEX_IRRADIANCE, see surfaceVertex()).
#ifdef VERTEX_IRRADIANCE
    vec3 ambientDiffuse = vAmbientDiffuse, ambientSpecular = vAmbientSpecular;
#else
    vec3 volumeConstant;
    mat3 volumeLinear;
    irradianceBlend(p, n, volumeConstant, volumeLinear);
    vec3 ambientDiffuse = max(volumeConstant + volumeLinear * n, 0.0);
    vec3 ambientSpecular = max(volumeConstant + volumeLinear * reflect(-s.v, n), 0.0);
#endif
#elif defined(ENVIRONMENT_MAP)
    vec3 ambientDiffuse = skyDiffuse(n), ambientSpecular = skySpecular(reflect(-s.v, n), roughness);
#else
    vec3 ambientDiffuse = ambientRadiance(), ambientSpecular = ambientDiffuse;
#endif
    result.diffuseIllumination = toHalf(irradiance * (1.0 / PI) + ambientDiffuse * ao);
    result.diffuseOnly = base * (1.0 - metallic) * result.diffuseIllumination;
    result.hdr = result.diffuseOnly + specular + envBrdfApprox(s.f0, roughness, s.nov) * ambientSpecular * ao + emissive;
    return result;
}
)glsl";
    return text;
}

} // namespace

std::string ShadingLayout::key() const {
    std::string key;
    for (const LightSlot& light : lights) {
        if (!key.empty())
            key += '.';
        key += light.type == LightType::Directional ? 'D' : light.type == LightType::Point ? 'P' : 'S';
        if (light.shadowLayer >= 0)
            key += std::to_string(light.shadowLayer);
        if (light.ranged)
            key += 'r';
    }
    if (floatShadowMaps)
        key += ".f";
    if (vignette)
        key += ".v";
    key += ".t" + std::to_string(static_cast<int>(toneMap));
    if (constantSlots > 0)
        key += ".c" + std::to_string(constantSlots);
    if (irradiance != IrradianceBlend::None)
        key += irradiance == IrradianceBlend::PerPixel ? ".g" : vertexProbeImages ? ".gvi" : ".gv";
    if (environmentMap)
        key += ".e";
    if (screenOcclusionScale > 0)
        key += ".o" + std::to_string(screenOcclusionScale);
    return key;
}

std::string shadowVertex(bool layered) {
    if (!layered)
        return "#version 450 core\n" + instanceAttributes() + R"glsl(
layout(location = 0) in vec3 aPosition;
void main() { gl_Position = iModelViewProjection * vec4(aPosition, 1.0); }
)glsl";
    return "#version 450 core\n#extension GL_ARB_shader_viewport_layer_array : require\n" +
           instanceAttributes() +
           R"glsl(
layout(location = 0) in vec3 aPosition;
uniform int uLayer; // the map's layer of the layered framebuffer (ShadowLayers)
void main() {
    gl_Position = iModelViewProjection * vec4(aPosition, 1.0);
    gl_Layer = uLayer;
}
)glsl";
}

// Stores the depth test's own value, polygon offset included (see ShadowMaps).
const char* const kShadowFragment = R"glsl(#version 450 core
layout(location = 0) out float oDepth;
void main() { oDepth = clamp(gl_FragCoord.z, 0.0, 1.0); } // clamped: see GL_DEPTH_CLAMP in shadow_maps.cpp
)glsl";

std::string idChannelCompute(bool layered) {
    std::string text = "#version 450 core\n";
    text += layered ? "#define LAYERED\n" : "";
    return text + R"glsl(layout(local_size_x = 16, local_size_y = 16) in;
#ifdef LAYERED
layout(binding = 1, rg32ui) uniform readonly uimage2DArray uIds;
uniform int uLayer; // the view's layer of a page of shared framebuffers
#else
layout(binding = 1, rg32ui) uniform readonly uimage2D uIds;
#endif
layout(std430, binding = 0) writeonly buffer PackedIds { uint packedIds[]; };
uniform int uChannel;
uniform ivec2 uSize;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= uSize.x || p.y >= uSize.y) return;
#ifdef LAYERED
    packedIds[p.y * uSize.x + p.x] = imageLoad(uIds, ivec3(p, uLayer))[uChannel];
#else
    packedIds[p.y * uSize.x + p.x] = imageLoad(uIds, p)[uChannel];
#endif
}
)glsl";
}

std::string backgroundVertex(bool layered) {
    std::string text = "#version 450 core\n";
    if (layered)
        text += std::string("#extension GL_ARB_shader_viewport_layer_array : require\n#define LAYERED\n") +
                kFrameBlock;
    return text + R"glsl(
// One triangle covering the viewport, on the far plane (depth 1: it passes GL_LEQUAL where nothing was drawn).
void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 1.0, 1.0);
#ifdef LAYERED
    gl_Layer = uCounts.y; // the view's layer of a page of shared framebuffers
#endif
}
)glsl";
}

// "#define TONE_CURVE k" for kToneChunk.
std::string toneCurveDefine(ToneMap toneMap) {
    return "#define TONE_CURVE " + std::to_string(static_cast<int>(toneMap)) + "\n";
}

// irradianceBlend() and its constants, for the fragment or compute shading (`byTexture` false) or a vertex
// shader (texel fetches).
std::string irradianceChunk(bool byTexture) {
    return std::string(byTexture ? "#define PROBES_BY_TEXTURE\n" : "") + "#define IRRADIANCE_IMAGE_UNIT " +
           std::to_string(kIrradianceImageUnit) + "\n#define IRRADIANCE_TEXTURE_UNIT " +
           std::to_string(kIrradianceTextureUnit) + "\n#define IRRADIANCE_NORMAL_OFFSET " +
           std::to_string(IrradianceVolume::kNormalOffset) + "\n#define IRRADIANCE_MAX_FREE " +
           std::to_string(IrradianceVolume::kMaxFreeDistance) + "\n" + kIrradianceChunk;
}

// The view's screen-space ambient occlusion at a pixel (its intensity applied), filtered from the texture
// of ScreenOcclusion: rows run down the image there as in the shaded targets, whose projection is flipped
// alike.
// The light the occluders themselves reflect into the hidden part of the hemisphere makes up for some of it,
// the more the brighter the surface (a white room's corners are barely darker): GTAO's multiple-bounce fit
// for the albedo (Jimenez et al. 2016, section 5), here of its luminance.
const char* const kScreenOcclusionChunk = R"glsl(
layout(binding = SCREEN_OCCLUSION_UNIT, r8) readonly uniform image2D uScreenOcclusion;
float screenOcclusion(vec2 pixel, vec3 albedo) {
    float x = imageLoad(uScreenOcclusion, ivec2(pixel) / SCREEN_OCCLUSION_SCALE).r;
    float rho = dot(albedo, vec3(0.2126, 0.7152, 0.0722));
    float a = 2.0404 * rho - 0.3324, b = -4.7951 * rho + 0.6417, c = 2.7552 * rho + 0.6903;
    return max(x, ((x * a + b) * x + c) * x);
}
)glsl";

// The defines of the shading and tone chunks for a layout: the shadow maps' image format, the vignette and
// the tone curve.
std::string shadingDefines(const ShadingLayout& lights) {
    std::string text = std::string("#define SHADOW_FORMAT ") + (lights.floatShadowMaps ? "r32f" : "r16") +
                       "\n" + (lights.vignette ? "#define VIGNETTE\n" : "") + toneCurveDefine(lights.toneMap);
    if (lights.irradiance == IrradianceBlend::PerPixel)
        text += "#define IRRADIANCE_VOLUME\n";
    else if (lights.irradiance == IrradianceBlend::PerVertex)
        text += "#define VERTEX_IRRADIANCE\n";
    if (lights.environmentMap)
        text += "#define ENVIRONMENT_MAP\n";
    if (lights.screenOcclusionScale > 0)
        text += "#define SCREEN_OCCLUSION_UNIT " + std::to_string(kScreenOcclusionUnit) +
                "\n#define SCREEN_OCCLUSION_SCALE " + std::to_string(lights.screenOcclusionScale) + "\n" +
                kScreenOcclusionChunk;
    else
        text += "#define screenOcclusion(pixel, albedo) 1.0\n";
    return text;
}

// The environment chunk and its texture unit (after FrameBlock), and with `background` the background's.
std::string environmentChunk(bool background = false) {
    std::string text = "#define ENVIRONMENT_SPECULAR_UNIT " + std::to_string(kEnvironmentSpecularUnit) +
                       "\n" + kEnvironmentChunk;
    if (background)
        text += "#define ENVIRONMENT_BACKGROUND_UNIT " + std::to_string(kEnvironmentBackgroundUnit) + "\n" +
                kEnvironmentBackgroundChunk;
    return text;
}

// Fragment outputs of `targets` at consecutive locations in Target order, named o0, o1, ..., and the body
// that assigns each the GLSL expression `value` gives it (an empty one leaves the output unassigned).
std::pair<std::string, std::string>
locatedOutputs(TargetMask targets, bool compact,
               const std::function<std::string(Target, const std::string&)>& value) {
    std::string declarations, body;
    int location = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((targets & (TargetMask(1) << t)) == 0)
            continue;
        const auto target = static_cast<Target>(t);
        const std::string index = std::to_string(location++);
        declarations +=
            "layout(location = " + index + ") out " + outputType(target, compact) + " o" + index + ";\n";
        if (const std::string v = value(target, index); !v.empty())
            body += " o" + index + " = " + v + ";";
    }
    return {declarations, body};
}

std::string backgroundFragment(int location, ToneMap toneMap) {
    std::string text = "#version 450 core\n#define VIGNETTE\n" + toneCurveDefine(toneMap);
    text += "layout(location = " + std::to_string(location) + ") out vec4 oFinalColor;\n";
    text += kFrameBlock;
    text += constantAccessors(ConstantPlan{});
    text += kToneChunk;
    return text + "void main() { oFinalColor = toneMapped(uBackground.xyz); }\n";
}

std::string environmentBackgroundFragment(TargetMask targets, ToneMap toneMap, bool compact) {
    std::string text = "#version 450 core\n#define VIGNETTE\n" + toneCurveDefine(toneMap);
    text += encodings(compact);
    text += kFrameBlock;
    text += constantAccessors(ConstantPlan{});
    text += kToneChunk;
    text += "uniform mat4 uClipToOffset;\nuniform ivec2 uSize;\n" + environmentChunk(true);
    const auto [declarations, body] = locatedOutputs(targets, compact, [](Target target, const std::string&) {
        if (target == Target::Hdr ||
            target == Target::SpecularResidual) // all of a background pixel is residual
            return std::string("halfTarget(vec4(c, 1.0))");
        return std::string(target == Target::FinalColor ? "toneMapped(c)" : "");
    });
    return text + declarations + "void main() { vec3 c = backgroundRadiance(gl_FragCoord.xy);" + body +
           " }\n";
}

std::string resolveFragment(TargetMask targets, int samples, int layers) {
    // FETCH(s, p, i): the i-th of the pixel's SAMPLES samples.
    std::string text = "#version 450 core\n";
    if (layers > 1)
        text += "#define SAMPLES " + std::to_string(layers) +
                "\n#define SAMPLER sampler2DArray\n#define FETCH(s, p, i) texelFetch(s, ivec3(p, i), 0)\n";
    else
        text += "#define SAMPLES " + std::to_string(samples) +
                "\n#define SAMPLER sampler2DMS\n#define FETCH(s, p, i) texelFetch(s, p, i)\n";
    // The exact curves both ways, not the shading's fitted encode: a resolve of resolves (spatial samples
    // each multisampled) would otherwise add the fit's bias (up to a quarter step) at each, and one pass a
    // frame pays little for pow().
    text += R"glsl(
vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}
vec3 srgbEncode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}
)glsl";
    int unit = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t)
        if ((targets & (TargetMask(1) << t)) != 0) {
            text += "layout(binding = " + std::to_string(kResolveTextureUnit + unit) +
                    ") uniform SAMPLER uS" + std::to_string(unit) + ";\n";
            ++unit;
        }
    const auto [declarations, body] =
        locatedOutputs(targets, false, [](Target target, const std::string& index) {
            const std::string sampler = "uS" + index;
            if (target == Target::FinalColor)
                return "finalAverage(" + sampler + ", p)";
            return "average(" + sampler + ", p)";
        });
    text += R"glsl(
vec4 average(SAMPLER s, ivec2 p) {
    vec4 sum = vec4(0.0);
    for (int i = 0; i < SAMPLES; ++i)
        sum += FETCH(s, p, i);
    return sum / float(SAMPLES);
}
vec4 finalAverage(SAMPLER s, ivec2 p) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < SAMPLES; ++i)
        sum += srgbToLinear(FETCH(s, p, i).rgb);
    return vec4(srgbEncode(sum / float(SAMPLES)), 1.0);
}
)glsl";
    return text + declarations + "void main() { ivec2 p = ivec2(gl_FragCoord.xy);" + body + " }\n";
}

std::string clearFragment(TargetMask targets, bool compact) {
    std::string text = "#version 450 core\nuniform vec4 uClear[" + std::to_string(kTargetCount) + "];\n";
    text += encodings(compact);
    const auto [declarations, body] =
        locatedOutputs(targets, compact, [&](Target target, const std::string& index) {
            if (target == Target::Ids || target == Target::GBufferMaterial)
                return std::string("uvec2(0u)");
            if (target == Target::GBuffer || target == Target::Record) // (none: 0)
                return std::string("0u");
            const std::string value = "uClear[" + index + "]";
            if (target == Target::Depth)
                return value + ".x";
            if (compact && target == Target::Normal)
                return "vec2(" + std::to_string(kNoOctahedralNormal) + ")";
            if ((kHalfTargets & targetBit(target)) != 0)
                return "halfTarget(" + value + ")";
            return value;
        });
    return text + declarations + "void main() {" + body + " }\n";
}

std::string computeLighting(TargetMask targets, const ShadingLayout& lights, bool materials) {
    std::string text =
        "#version 450 core\nlayout(local_size_x = " + std::to_string(kComputeLightingGroupSize) +
        ", local_size_y = " + std::to_string(kComputeLightingGroupSize) + ") in;\n";
    text += shadingDefines(lights);
    if ((targets & targetBit(Target::FinalColor)) != 0)
        text += "#define STORE_FinalColor\n"; // not OUT_*: those name fragment outputs (writeShaded())
    if ((targets & targetBit(Target::Hdr)) != 0)
        text += "#define STORE_Hdr\n";
    text += kFrameBlock;
    ConstantPlan plan; // every constant from FrameBlock
    plan.lightSlot.assign(lights.lights.size(), -1);
    text += constantAccessors(plan);
    // InstanceRecord (instances.h) in std430: 192 bytes, every field at its C++ offset.
    text += "struct Record {\n    float mvp[16];\n    float modelRows[12];\n    float depthRow[4];\n"
            "    vec4 baseColor;\n    vec4 material;\n    vec4 emissive;\n    uvec4 ids;\n};\n";
    text += "layout(std430, binding = " + std::to_string(kRecordsBinding) +
            ") readonly buffer Records { Record records[]; };\n";
    text += "layout(binding = " + std::to_string(kDepthTextureUnit) + ") uniform sampler2D uDepthBuffer;\n";
    text += "layout(binding = " + std::to_string(kGBufferImageUnit) +
            ", r32ui) uniform readonly uimage2D uGBuffer;\n";
    if (materials)
        text += "#define GBUFFER_MATERIAL\nlayout(binding = " + std::to_string(kGBufferMaterialImageUnit) +
                ", rg32ui) uniform readonly uimage2D uGBufferMaterial;\n";
    text += "layout(binding = " + std::to_string(kFinalColorImageUnit) +
            ", rgba8) uniform writeonly image2D uFinalColor;\n";
    text +=
        "layout(binding = " + std::to_string(kHdrImageUnit) + ", rgba16f) uniform writeonly image2D uHdr;\n";
    text +=
        R"glsl(uniform mat4 uClipToOffset; // clip space -> world position minus the camera's (float precision)
uniform ivec2 uSize;
vec2 gPixelCentre;
#define PIXEL_CENTRE gPixelCentre
)glsl";
    text += kOctahedralChunk;
    text += kGBufferChunk;
    text += kGBufferMaterialChunk;
    text += kShadingChunk;
    if (lights.irradiance == IrradianceBlend::PerPixel)
        text += irradianceChunk(false);
    if (lights.environmentMap)
        text += environmentChunk(true);
    text += shadeFunction(lights, plan, true);
    text += kToneChunk;
    return text + R"glsl(
void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= uSize.x || pixel.y >= uSize.y) return;
    gPixelCentre = vec2(pixel) + 0.5;
    float z = texelFetch(uDepthBuffer, pixel, 0).r;
    if (z >= 1.0) { // background: cleared, but for a vignetted final_color (see backgroundFragment())
#ifdef ENVIRONMENT_MAP // or an environment map's (see environmentBackgroundFragment())
        vec3 c = backgroundRadiance(gPixelCentre);
#ifdef STORE_Hdr
        imageStore(uHdr, pixel, vec4(c, 1.0));
#endif
#ifdef STORE_FinalColor
        imageStore(uFinalColor, pixel, toneMapped(c));
#endif
#elif defined(VIGNETTE) && defined(STORE_FinalColor)
        imageStore(uFinalColor, pixel, toneMapped(uBackground.xyz));
#endif
        return;
    }
    uint g = imageLoad(uGBuffer, pixel).x;
    if (g == 0xffffffffu) return; // shaded by its fragment
    uint record = g >> 22;
    vec4 offset = uClipToOffset * vec4(gPixelCentre / vec2(uSize) * 2.0 - 1.0, z * 2.0 - 1.0, 1.0);
    vec3 p = cameraPosition() + offset.xyz / offset.w;
    vec4 material = records[record].material;
    vec3 base = records[record].baseColor.rgb;
    float roughness = material.x, metallic = material.y, ao = material.z;
#ifdef GBUFFER_MATERIAL
    if ((records[record].ids.w & 1u) != 0u) // a textured material's, at this pixel
        gbufferMaterialDecode(imageLoad(uGBufferMaterial, pixel).xy, base, roughness, metallic, ao);
#endif
    Shaded s = shade(p, gbufferNormal(g), base, roughness, metallic, ao * screenOcclusion(gPixelCentre, base),
                     records[record].emissive.rgb, records[record].emissive.w);
#ifdef STORE_Hdr
    imageStore(uHdr, pixel, vec4(s.hdr, 1.0));
#endif
#ifdef STORE_FinalColor
    imageStore(uFinalColor, pixel, toneMapped(s.hdr));
#endif
}
)glsl";
}

std::string surfaceVertex(bool forward, const ShadingLayout& lights, bool layered, bool boxUv) {
    std::string text = "#version 450 core\n";
    if (boxUv)
        text += "#define HAS_BOX_UV\n";
    if (layered) // the view's layer of a page of shared framebuffers
        text += "#extension GL_ARB_shader_viewport_layer_array : require\n#define VIEW_LAYER gl_Layer = "
                "uCounts.y;\n";
    else
        text += "#define VIEW_LAYER\n";
    text += kFrameBlock;
    text += instanceAttributes();
    const ConstantPlan plan = planConstants(forward, lights);
    text += "#define SHADOW_CLIPS" + (forward ? shadowClips(lights) : std::string()) + "\n";
    text += "#define CONSTANT_COPIES" + constantCopies(lights, plan) + "\n";
    text += shadowClipDeclarations(forward, lights, "out");
    text += constantDeclarations(plan, "out");
    if (forward && lights.irradiance == IrradianceBlend::PerVertex)
        text += "#define VERTEX_IRRADIANCE\n" + irradianceChunk(!lights.vertexProbeImages) +
                "out vec3 vAmbientDiffuse;\nout vec3 vAmbientSpecular;\n";
    return text + kSurfaceVertex;
}

std::string surfaceFragment(TargetMask targets, bool forward, unsigned materialFeatures,
                            const ShadingLayout& lights, bool compact) {
    std::string text = "#version 450 core\n";
    // Depth-test before the shader (it writes no depth and discards nothing), so hidden fragments never
    // run it: with draws front to back, shading; against the surface pass's depth, the attribute pass.
    text += "layout(early_fragment_tests) in;\n";
    if (forward)
        text += "#define FORWARD\n";
    if (forward && (targets & targetBit(Target::DiffuseOnly)) != 0)
        text += "#define EXACT_INTRINSICS\n";
    if (materialFeatures & kBaseColorTexture)
        text += "#define HAS_BASE_COLOR_TEXTURE\n";
    if (materialFeatures & kRoughnessMetallicTexture)
        text += "#define HAS_ROUGHNESS_METALLIC_TEXTURE\n";
    if (materialFeatures & kNormalTexture)
        text += "#define HAS_NORMAL_TEXTURE\n";
    if (materialFeatures & kTextureFeatures)
        text += "#define TEXTURED\n";
    if (materialFeatures & kFacingFromWinding)
        text += "#define FACING_FROM_WINDING\n";
    if (materialFeatures & kBoxUv)
        text += "#define HAS_BOX_UV\n";
    text += outputs(targets, compact);
    text += kFrameBlock;
    const ConstantPlan plan = planConstants(forward, lights);
    text += constantDeclarations(plan, "in");
    text += constantAccessors(plan);
    text += shadowClipDeclarations(forward, lights, "in");
    text += kMaterialChunk;
    if ((targets & targetBit(Target::GBuffer)) != 0)
        text += kGBufferChunk; // after outputs(), which gives it octahedral()
    if ((targets & targetBit(Target::GBufferMaterial)) != 0)
        text += kGBufferMaterialChunk;
    if (forward) {
        text += shadingDefines(lights);
        text += kShadingChunk;
        if (lights.irradiance == IrradianceBlend::PerPixel)
            text += irradianceChunk(false);
        else if (lights.irradiance == IrradianceBlend::PerVertex)
            text += "in vec3 vAmbientDiffuse;\nin vec3 vAmbientSpecular;\n";
        if (lights.environmentMap)
            text += environmentChunk();
        text += shadeFunction(lights, plan);
        text += kToneChunk;
    }
    return text + kSurfaceMain;
}

// GTAO (screen_occlusion.h). Positions are the camera's, x right and y down the image (its rows), z along the
// optical axis: a texel's depth d at (texel + 0.5 - size / 2) * d / f. For each slice (a screen direction
// turned by the pixel's place in a 4 x 4 pattern), the highest horizon on each side within the radius, as
// the cosine of its angle to the view vector, samples past the radius fading to none; then the
// cosine-weighted visible arc between the two horizons, clamped to the normal's hemisphere, by the paper's
// closed form, weighted by the length of the normal projected into the slice. Over all slice directions an
// open hemisphere sums to 1, but not slice by slice, and a pixel has two: their sum is divided by what it
// would be open, so that a plane is unoccluded whichever of the pattern's angles the blur averages (it
// leaves out texels across depth edges, and a floor at a grazing angle has them between its rows).
std::string screenOcclusionFragment() {
    return R"glsl(#version 450 core
// Image loads: a software rasteriser's texel fetch takes its general sampler path, several times slower.
layout(binding = 0, r32f) readonly uniform image2D uDepth; // metres along the optical axis, 0: background
uniform vec3 uCamera; // focal length in texels, radius in metres, the largest radius in texels
layout(location = 0) out float oOcclusion;
const float PI = 3.14159265;
const int SLICES = 2;
const int STEPS = 4;
// A 4 x 4 Bayer matrix: neighbouring texels take distant angles, and any 4 x 4 block takes all 16.
const float ORDER[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
ivec2 gSize;

vec3 position(ivec2 texel, float depth) {
    return vec3((vec2(texel) + 0.5 - 0.5 * vec2(gSize)) * (depth / uCamera.x), depth);
}
// acos to within 7e-5 rad (Abramowitz and Stegun 4.4.45): a software rasteriser's acos is several times
// the cost, and each slice takes three.
float fastAcos(float x) {
    float a = abs(x);
    float r = sqrt(1.0 - a) * (1.5707288 + a * (-0.2121144 + a * (0.0742610 - 0.0187293 * a)));
    return x < 0.0 ? PI - r : r;
}
float depthAt(ivec2 texel) {
    return imageLoad(uDepth, clamp(texel, ivec2(0), gSize - 1)).r;
}

void main() {
    gSize = imageSize(uDepth);
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float d = depthAt(texel);
    float radius = uCamera.y * uCamera.x / max(d, 1e-6); // texels
    if (d <= 0.0 || radius < 1.0) { // the background, or a radius under a texel: nothing to find
        oOcclusion = 1.0;
        return;
    }
    radius = min(radius, uCamera.z);
    vec3 p = position(texel, d);
    // The normal from the depth: on each axis the neighbour nearer in depth, so as not to reach across an edge.
    float left = depthAt(texel - ivec2(1, 0)), right = depthAt(texel + ivec2(1, 0));
    float up = depthAt(texel - ivec2(0, 1)), down = depthAt(texel + ivec2(0, 1));
    vec3 dx = abs(right - d) < abs(left - d) ? position(texel + ivec2(1, 0), right) - p
                                             : p - position(texel - ivec2(1, 0), left);
    vec3 dy = abs(down - d) < abs(up - d) ? position(texel + ivec2(0, 1), down) - p
                                          : p - position(texel - ivec2(0, 1), up);
    vec3 v = normalize(-p);
    vec3 n = cross(dx, dy);
    n = dot(n, n) > 0.0 ? normalize(n) : v;
    if (dot(n, v) < 0.0)
        n = -n;
    float order = ORDER[(texel.x & 3) + 4 * (texel.y & 3)];
    float angleOffset = (order + 0.5) / 16.0;
    float stepOffset = fract(order * 0.3125 + 0.25); // another spread of the same 16 values
    float radius2 = uCamera.y * uCamera.y;
    float visibility = 0.0, open = 0.0;
    for (int slice = 0; slice < SLICES; ++slice) {
        float phi = (float(slice) + angleOffset) * (PI / float(SLICES));
        vec3 direction = vec3(cos(phi), sin(phi), 0.0);
        vec3 ortho = normalize(direction - dot(direction, v) * v);
        vec3 axis = cross(ortho, v);
        vec3 projected = n - axis * dot(n, axis);
        float projectedLength = length(projected);
        if (projectedLength < 1e-4)
            continue;
        float cosN = clamp(dot(projected, v) / projectedLength, -1.0, 1.0);
        float angleN = (dot(projected, ortho) < 0.0 ? -1.0 : 1.0) * fastAcos(cosN);
        float horizon[2];
        for (int side = 0; side < 2; ++side) {
            float highest = -1.0;
            vec2 along = (side == 0 ? 1.0 : -1.0) * direction.xy;
            for (int i = 0; i < STEPS; ++i) {
                float distance = max(radius * (float(i) + stepOffset) / float(STEPS), float(i + 1));
                ivec2 at = ivec2(floor(vec2(texel) + 0.5 + along * distance));
                if (any(lessThan(at, ivec2(0))) || any(greaterThanEqual(at, gSize)))
                    break;
                float sampled = imageLoad(uDepth, at).r;
                if (sampled <= 0.0)
                    continue;
                vec3 delta = position(at, sampled) - p;
                float length2 = dot(delta, delta);
                // A point on or under the tangent plane hides nothing; rounded to a texel's centre, off the
                // slice, its angle would (on a floor at a grazing angle, a few percent).
                float above = dot(delta, n);
                if (above <= 0.0 || above * above <= 4e-4 * length2) // within 0.02 of its length
                    continue;
                float cosine = dot(delta, v) * inversesqrt(max(length2, 1e-12));
                // Full weight to half the radius (squared), none past it: far surfaces occlude nothing.
                float falloff = clamp(2.0 - 2.0 * length2 / radius2, 0.0, 1.0);
                highest = max(highest, mix(-1.0, cosine, falloff));
            }
            horizon[side] = highest;
        }
        float h0 = angleN + max(-fastAcos(horizon[1]) - angleN, -0.5 * PI);
        float h1 = angleN + min(fastAcos(horizon[0]) - angleN, 0.5 * PI);
        float sinN = sin(angleN);
        visibility += projectedLength * 0.25 *
                      ((-cos(2.0 * h0 - angleN) + cosN + 2.0 * h0 * sinN) +
                       (-cos(2.0 * h1 - angleN) + cosN + 2.0 * h1 * sinN));
        open += projectedLength * (cosN + angleN * sinN); // the same with both horizons at the tangent plane
    }
    oOcclusion = open > 0.0 ? clamp(visibility / open, 0.0, 1.0) : 1.0;
}
)glsl";
}

// The blur of ScreenOcclusion: the 4 x 4 block around each texel (one of each of the pattern's angles), only
// the texels within 10 % of its depth (a floor seen at a grazing angle changes by a few percent a texel; an
// object's edge by more), then 1 - intensity * (1 - occlusion).
std::string screenOcclusionBlurFragment() {
    return R"glsl(#version 450 core
layout(binding = 0, r32f) readonly uniform image2D uDepth;
layout(binding = 1, r8) readonly uniform image2D uRaw;
uniform float uIntensity;
layout(location = 0) out float oOcclusion;

void main() {
    ivec2 size = imageSize(uRaw);
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float d = imageLoad(uDepth, texel).r;
    if (d <= 0.0) {
        oOcclusion = 1.0;
        return;
    }
    float sum = 0.0, weight = 0.0;
    for (int y = -1; y <= 2; ++y)
        for (int x = -1; x <= 2; ++x) {
            ivec2 at = clamp(texel + ivec2(x, y), ivec2(0), size - 1);
            float sampled = imageLoad(uDepth, at).r;
            if (sampled > 0.0 && abs(sampled - d) < 0.1 * d) {
                sum += imageLoad(uRaw, at).r;
                weight += 1.0;
            }
        }
    oOcclusion = 1.0 - uIntensity * (1.0 - sum / max(weight, 1.0));
}
)glsl";
}

} // namespace sp::render::shaders
