#include "core/render/shaders.h"

namespace sp::render::shaders {

// Positions are transformed with matrices composed in double precision on the CPU: uModelToCamera
// gives camera-relative coordinates, so depth keeps float precision far from the world origin.
const char* const kGeometryVertex = R"glsl(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
uniform mat4 uModel;              // mesh -> world
uniform mat3 uNormalMatrix;       // inverse transpose of uModel's linear part
uniform mat4 uModelToCamera;      // mesh -> camera body frame (x forward, y left, z up)
uniform mat4 uModelViewProjection;
out vec3 vWorldPosition;
out float vDepth;
out vec3 vNormal;
out vec2 vUv;
void main() {
    vWorldPosition = (uModel * vec4(aPosition, 1.0)).xyz;
    vDepth = (uModelToCamera * vec4(aPosition, 1.0)).x;
    vNormal = uNormalMatrix * aNormal;
    vUv = aUv;
    gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
}
)glsl";

const char* const kGeometryFragment = R"glsl(#version 450 core
in vec3 vWorldPosition;
in float vDepth;
in vec3 vNormal;
in vec2 vUv;
uniform vec3 uCameraPosition;
uniform vec4 uBaseColor;
uniform float uRoughness;
uniform float uMetallic;
uniform float uAo;
uniform vec3 uEmissive;
uniform uint uObjectId;
uniform uint uMaterialId;
uniform bool uHasBaseColorTexture;
uniform bool uHasRoughnessMetallicTexture;
uniform bool uHasNormalTexture;
layout(binding = 0) uniform sampler2D uBaseColorTexture;
layout(binding = 1) uniform sampler2D uRoughnessMetallicTexture;
layout(binding = 2) uniform sampler2D uNormalTexture;
layout(location = 0) out vec4 oPosition;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out float oDepth;
layout(location = 3) out vec4 oBaseColor;
layout(location = 4) out vec4 oParams;
layout(location = 5) out vec4 oEmissive;
layout(location = 6) out uvec2 oIds;

void main() {
    // Two-sided shading that does not trust the mesh's winding: the geometric normal is turned towards
    // the camera and the shading normal follows it.
    vec3 dpdx = dFdx(vWorldPosition), dpdy = dFdy(vWorldPosition);
    vec3 geometric = cross(dpdx, dpdy);
    vec3 toCamera = uCameraPosition - vWorldPosition;
    if (dot(geometric, toCamera) < 0.0) geometric = -geometric;
    vec3 n = normalize(vNormal);
    if (dot(n, geometric) < 0.0) n = -n;
    if (uHasNormalTexture) {
        // Cotangent frame (Schueler 2013) from screen derivatives (no tangent attribute needed).
        vec2 duvdx = dFdx(vUv), duvdy = dFdy(vUv);
        vec3 dp2perp = cross(dpdy, n), dp1perp = cross(n, dpdx);
        vec3 t = dp2perp * duvdx.x + dp1perp * duvdy.x;
        vec3 b = dp2perp * duvdx.y + dp1perp * duvdy.y;
        // t and b are the surface gradients of u and v up to 1 / dot(n, dpdx x dpdy); keep that sign,
        // which flips with the vertical projection flip and with the side the surface is seen from.
        float scale = sign(dot(n, cross(dpdx, dpdy))) * inversesqrt(max(max(dot(t, t), dot(b, b)), 1e-20));
        vec3 m = texture(uNormalTexture, vUv).xyz * 2.0 - 1.0;
        // Green points up in the image, i.e. towards decreasing v with the top-left uv origin.
        n = normalize(mat3(t * scale, -b * scale, n) * m);
    }
    vec3 base = uBaseColor.rgb;
    if (uHasBaseColorTexture) base *= texture(uBaseColorTexture, vUv).rgb;
    float roughness = uRoughness, metallic = uMetallic;
    if (uHasRoughnessMetallicTexture) {
        vec4 rm = texture(uRoughnessMetallicTexture, vUv);
        roughness *= rm.g;
        metallic *= rm.b;
    }
    oPosition = vec4(vWorldPosition, 1.0);
    oNormal = vec4(n, 0.0);
    oDepth = vDepth;
    oBaseColor = vec4(base, 1.0);
    oParams = vec4(roughness, metallic, uAo, 0.0);
    oEmissive = vec4(uEmissive, 0.0);
    oIds = uvec2(uObjectId, uMaterialId);
}
)glsl";

const char* const kShadowVertex = R"glsl(#version 450 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uModelLightProjection;
void main() { gl_Position = uModelLightProjection * vec4(aPosition, 1.0); }
)glsl";

const char* const kShadowFragment = R"glsl(#version 450 core
void main() {}
)glsl";

// One triangle covering the viewport; no vertex buffer.
const char* const kFullscreenVertex = R"glsl(#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)glsl";

// Deferred shading, Karis 2013 ("Real shading in Unreal Engine 4"): GGX distribution, Smith-Schlick
// visibility with k = (roughness + 1)^2 / 8, Schlick Fresnel with the spherical Gaussian exponent; the
// ambient sky term uses Karis' analytic environment BRDF approximation.
const char* const kLightingFragment = R"glsl(#version 450 core
#define MAX_LIGHTS 16
#define MAX_SHADOWS 4
const float PI = 3.14159265358979;
layout(binding = 0) uniform sampler2D gPosition;
layout(binding = 1) uniform sampler2D gNormal;
layout(binding = 3) uniform sampler2D gBaseColor;
layout(binding = 4) uniform sampler2D gParams;
layout(binding = 5) uniform sampler2D gEmissive;
layout(binding = 7) uniform sampler2DArrayShadow uShadowMaps;
uniform vec3 uCameraPosition;
uniform vec3 uAmbient;
uniform vec3 uBackground;
uniform int uLightCount;
uniform int uLightType[MAX_LIGHTS];         // 0 directional, 1 point, 2 spot
uniform vec3 uLightRadiance[MAX_LIGHTS];    // colour * intensity
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightDirection[MAX_LIGHTS];   // unit, the direction light travels
uniform float uLightRange[MAX_LIGHTS];      // 0 = unbounded
uniform vec2 uLightCone[MAX_LIGHTS];        // cos(inner), cos(outer)
uniform int uLightShadow[MAX_LIGHTS];       // shadow map layer or -1
uniform mat4 uShadowMatrix[MAX_SHADOWS];    // world -> light clip
uniform float uShadowTexel[MAX_SHADOWS];    // world size of a texel (per metre of distance if perspective)
uniform bool uShadowPerspective[MAX_SHADOWS];
layout(location = 0) out vec4 oHdr;
layout(location = 1) out vec4 oDiffuseIllumination;
layout(location = 2) out vec4 oDiffuseOnly;
layout(location = 3) out vec4 oSpecularResidual;

float dGgx(float noh, float a) {
    float a2 = a * a;
    float d = noh * noh * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}
float g1Schlick(float nox, float k) { return nox / (nox * (1.0 - k) + k); }
vec3 fSchlick(vec3 f0, float voh) { return f0 + (1.0 - f0) * exp2((-5.55473 * voh - 6.98316) * voh); }
vec3 envBrdfApprox(vec3 f0, float roughness, float nov) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * nov)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return f0 * ab.x + ab.y;
}
// Rounds to float16 so that diffuse_only = albedo * diffuse_illumination holds for the stored values.
vec3 toHalf(vec3 v) {
    return vec3(unpackHalf2x16(packHalf2x16(v.xy)), unpackHalf2x16(packHalf2x16(vec2(v.z, 0.0))).x);
}

float shadowFactor(int layer, vec3 p, vec3 n, float distanceToLight) {
    float texel = uShadowTexel[layer] * (uShadowPerspective[layer] ? distanceToLight : 1.0);
    vec4 clip = uShadowMatrix[layer] * vec4(p + n * (1.5 * texel), 1.0);
    vec3 s = clip.xyz / clip.w * 0.5 + 0.5;
    if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0)))) return 1.0;
    vec2 step = 1.0 / vec2(textureSize(uShadowMaps, 0).xy);
    float lit = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            lit += texture(uShadowMaps, vec4(s.xy + vec2(dx, dy) * step, float(layer), s.z));
    return lit / 9.0;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(gPosition, pixel, 0);
    if (position.w == 0.0) {
        oHdr = vec4(uBackground, 1.0);
        oDiffuseIllumination = vec4(0.0, 0.0, 0.0, 1.0);
        oDiffuseOnly = vec4(0.0, 0.0, 0.0, 1.0);
        oSpecularResidual = vec4(uBackground, 1.0);
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(gNormal, pixel, 0).xyz;
    vec3 base = texelFetch(gBaseColor, pixel, 0).rgb;
    vec4 params = texelFetch(gParams, pixel, 0);
    float roughness = params.x, metallic = params.y, ao = params.z;
    vec3 emissive = texelFetch(gEmissive, pixel, 0).rgb;

    vec3 v = normalize(uCameraPosition - p);
    float nov = max(dot(n, v), 1e-4);
    vec3 f0 = mix(vec3(0.04), base, metallic);
    float a = max(roughness * roughness, 0.002);
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;

    vec3 irradiance = vec3(0.0);
    vec3 specular = vec3(0.0);
    for (int i = 0; i < uLightCount; ++i) {
        vec3 l;
        vec3 e = uLightRadiance[i];
        float dist = 1.0;
        if (uLightType[i] == 0) {
            l = -uLightDirection[i];
        } else {
            vec3 d = uLightPosition[i] - p;
            dist = length(d);
            l = d / max(dist, 1e-6);
            e /= max(dist * dist, 1e-4);
            if (uLightRange[i] > 0.0) {
                float w = clamp(1.0 - pow(dist / uLightRange[i], 4.0), 0.0, 1.0);
                e *= w * w;
            }
            if (uLightType[i] == 2) {
                float cd = dot(-l, uLightDirection[i]);
                float t = clamp((cd - uLightCone[i].y) / max(uLightCone[i].x - uLightCone[i].y, 1e-4), 0.0, 1.0);
                e *= t * t;
            }
        }
        float nol = dot(n, l);
        if (nol <= 0.0) continue;
        if (uLightShadow[i] >= 0) e *= shadowFactor(uLightShadow[i], p, n, dist);
        irradiance += e * nol;
        vec3 h = normalize(v + l);
        float noh = max(dot(n, h), 0.0), voh = max(dot(v, h), 0.0);
        // D * G * F / (4 nol nov), times the irradiance e * nol.
        specular += dGgx(noh, a) * g1Schlick(nol, k) * g1Schlick(nov, k) * fSchlick(f0, voh) / (4.0 * nov) * e;
    }
    vec3 diffuseIllumination = toHalf(irradiance / PI + uAmbient * ao);
    vec3 diffuseOnly = base * (1.0 - metallic) * diffuseIllumination;
    vec3 hdr = diffuseOnly + specular + envBrdfApprox(f0, roughness, nov) * uAmbient * ao + emissive;
    oHdr = vec4(hdr, 1.0);
    oDiffuseIllumination = vec4(diffuseIllumination, 1.0);
    oDiffuseOnly = vec4(diffuseOnly, 1.0);
    oSpecularResidual = vec4(hdr - diffuseOnly, 1.0);
}
)glsl";

const char* const kTonemapFragment = R"glsl(#version 450 core
layout(binding = 0) uniform sampler2D uHdr;
uniform float uExposure;
uniform int uToneMap;  // 0 ACES (Narkowicz fit), 1 Reinhard, 2 linear clamp
layout(location = 0) out vec4 oColor;
vec3 aces(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec3 srgbEncode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() {
    vec3 x = max(texelFetch(uHdr, ivec2(gl_FragCoord.xy), 0).rgb, 0.0) * uExposure;
    vec3 mapped = uToneMap == 0 ? aces(x) : uToneMap == 1 ? x / (1.0 + x) : clamp(x, 0.0, 1.0);
    oColor = vec4(srgbEncode(mapped), 1.0);
}
)glsl";

} // namespace sp::render::shaders
