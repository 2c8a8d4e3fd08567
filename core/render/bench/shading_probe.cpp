// spear_shading_probe: GPU time of the same per-pixel shading arithmetic run as a full-screen fragment pass
// and as a compute pass over a 1920x1080 RGBA8 image, and of each with a constant output (the cost of
// covering the image alone). A data-centre GPU runs fragment shaders on a few graphics-capable units and
// compute shaders on all of them; the ratio says what shading in compute (a visibility or thin G-buffer
// pass, then a compute lighting pass) could gain on a given device before building it.
//
//   spear_shading_probe [--frames F] [--lights L] [--width W] [--height H] [--quad PX]
//
// The shading is the surface pass's in kind: L lights, each a GGX specular and Lambertian term behind four
// shadow-map loads (a 2048x2048 R16 layer), the sky term, ACES and the sRGB curve, on a surface made up
// from the pixel's position. Then the cost of covering the image in each output format a G-buffer might use
// (outputCosts()), against the depth buffer the surface pass uses (D32F) and, for the G-buffer's format,
// against others.

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/render/gl_context.h"
#include "core/render/shader_program.h"

namespace {

using namespace sp::render;

std::string shadingChunk(int lights) {
    return "#define LIGHTS " + std::to_string(lights) + "\n" + R"glsl(
layout(binding = 1, r16) uniform readonly image2D uShadow;
uniform vec2 uSize;
const float PI = 3.14159265358979;
float dGgx(float noh, float a) { float a2 = a * a; float d = noh * noh * (a2 - 1.0) + 1.0; return a2 / (PI * d * d); }
float g1(float x, float k) { return x / (x * (1.0 - k) + k); }
vec3 fSchlick(vec3 f0, float voh) { float m = 1.0 - voh, m2 = m * m; return f0 + (1.0 - f0) * (m2 * m2 * m); }
vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
    return mix(c * 12.92, 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * c,
               step(vec3(0.0031308), c));
}
float shadowTap(vec2 uv, float z) {
    vec2 t = uv * 2048.0 - 0.5, cell = floor(t), f = t - cell;
    ivec2 c0 = clamp(ivec2(cell), ivec2(0), ivec2(2047)), c1 = min(c0 + 1, ivec2(2047));
    vec4 d = vec4(imageLoad(uShadow, c0).r, imageLoad(uShadow, ivec2(c1.x, c0.y)).r,
                  imageLoad(uShadow, ivec2(c0.x, c1.y)).r, imageLoad(uShadow, c1).r);
    vec4 lit = vec4(greaterThanEqual(d, vec4(z)));
    float near = lit.x + f.x * (lit.y - lit.x), far = lit.z + f.x * (lit.w - lit.z);
    return near + f.y * (far - near);
}
vec4 shadePixel(vec2 pixel) {
    vec2 q = pixel / uSize * 2.0 - 1.0;
    vec3 p = vec3(q * 4.0, 0.3 * sin(q.x * 7.0) * cos(q.y * 5.0));
    vec3 n = normalize(vec3(-2.1 * cos(q.x * 7.0) * cos(q.y * 5.0), 1.5 * sin(q.x * 7.0) * sin(q.y * 5.0), 1.0));
    vec3 v = normalize(vec3(-3.0, -2.0, 4.0) - p);
    vec3 base = vec3(0.5 + 0.4 * q.x, 0.5, 0.5 - 0.4 * q.y);
    float roughness = 0.3 + 0.5 * fract(q.x * 3.0), metallic = step(0.8, fract(q.y * 2.0));
    float nov = max(dot(n, v), 1e-4), a = max(roughness * roughness, 0.002), k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    vec3 f0 = mix(vec3(0.04), base, metallic), irradiance = vec3(0.0), specular = vec3(0.0);
    for (int i = 0; i < LIGHTS; ++i) {
        vec3 l = normalize(vec3(cos(float(i) * 2.1), sin(float(i) * 2.1), 1.5));
        vec3 e = vec3(3.0);
        float nol = dot(n, l);
        if (nol > 0.0) {
            e *= shadowTap(fract(p.xy * 0.1 + 0.5 + float(i) * 0.13), 0.5 + 0.1 * p.z);
            irradiance += e * nol;
            vec3 h = normalize(v + l);
            float noh = max(dot(n, h), 0.0), voh = max(dot(v, h), 0.0);
            specular += dGgx(noh, a) * g1(nol, k) * g1(nov, k) * fSchlick(f0, voh) / (4.0 * nov) * e;
        }
    }
    vec3 hdr = base * (1.0 - metallic) * (irradiance / PI + vec3(0.3)) + specular;
    return vec4(srgb(aces(hdr)), 1.0);
}
)glsl";
}

const char* const kFullScreenVertex = R"glsl(#version 450 core
void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)glsl";

std::string fragmentSource(int lights, bool shade) {
    return "#version 450 core\nlayout(location = 0) out vec4 oColor;\n" + shadingChunk(lights) +
           (shade ? "void main() { oColor = shadePixel(gl_FragCoord.xy); }\n"
                  : "void main() { oColor = vec4(gl_FragCoord.xy / uSize, 0.5, 1.0); }\n");
}

std::string computeSource(int lights, bool shade) {
    return "#version 450 core\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
           "layout(binding = 0, rgba8) uniform writeonly image2D uOut;\n" +
           shadingChunk(lights) + "void main() {\n    ivec2 p = ivec2(gl_GlobalInvocationID.xy);\n" +
           "    if (p.x >= int(uSize.x) || p.y >= int(uSize.y)) return;\n" +
           (shade ? "    imageStore(uOut, p, shadePixel(vec2(p) + 0.5));\n"
                  : "    imageStore(uOut, p, vec4((vec2(p) + 0.5) / uSize, 0.5, 1.0));\n") +
           "}\n";
}

// Mean milliseconds of `frames` runs of `pass`, after 5 unmeasured: GPU time (GL_TIME_ELAPSED around each)
// and wall time with glFinish() after each (a software rasteriser renders at the flush, outside the query).
struct Timing {
    double gpuMs = 0.0;
    double wallMs = 0.0;
};
template <typename Pass> Timing measure(int frames, Pass pass) {
    for (int i = 0; i < 5; ++i)
        pass();
    glFinish();
    std::vector<GLuint> queries(static_cast<std::size_t>(frames));
    glGenQueries(frames, queries.data());
    const auto start = std::chrono::steady_clock::now();
    for (GLuint query : queries) {
        glBeginQuery(GL_TIME_ELAPSED, query);
        pass();
        glEndQuery(GL_TIME_ELAPSED);
        glFinish();
    }
    Timing timing;
    timing.wallMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
    for (GLuint query : queries) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
        timing.gpuMs += double(ns) * 1e-6 / frames;
    }
    glDeleteQueries(frames, queries.data());
    return timing;
}

// What covering the image costs the rasteriser per output format: a full-screen triangle, then a grid of
// quads `quad` pixels wide (two triangles each) against a cleared depth buffer (test LESS, writes on), each
// writing a value that varies by pixel (a constant would let the hardware compress it). A G-buffer pass pays
// about this for its targets before any shading. With `formats` every format, else the G-buffer's alone
// (to compare depth formats).
const char* depthName(GLenum format) {
    switch (format) {
    case GL_DEPTH_COMPONENT32F:
        return "D32F";
    case GL_DEPTH32F_STENCIL8:
        return "D32F_S8";
    case GL_DEPTH_COMPONENT24:
        return "D24";
    case GL_DEPTH24_STENCIL8:
        return "D24_S8";
    default:
        return "D16";
    }
}

struct OutputFormat {
    const char* name;
    GLenum internal;
    int bytes;
    const char* type;  // the GLSL output type
    const char* value; // the GLSL value written, from the uint hash h
};

void outputCosts(int frames, int width, int height, int quad, GLenum depthFormat, bool formats) {
    const OutputFormat kFormats[] = {
        {"RGBA8", GL_RGBA8, 4, "vec4", "unpackUnorm4x8(h)"},
        {"R32F", GL_R32F, 4, "float", "float(h & 0xffffu)"},
        {"R32UI", GL_R32UI, 4, "uint", "h"},
        {"RG32UI", GL_RG32UI, 8, "uvec2", "uvec2(h, h * 747796405u)"},
        {"RGBA16F", GL_RGBA16F, 8, "vec4", "unpackUnorm4x8(h)"},
        {"RGBA32UI", GL_RGBA32UI, 16, "uvec4", "uvec4(h, h * 747796405u, h ^ 0x9e3779b9u, h >> 3)"},
        {"RGBA32F", GL_RGBA32F, 16, "vec4", "unpackUnorm4x8(h)"},
    };
    const std::string gridVertex = R"glsl(#version 450 core
uniform ivec2 uCells;
uniform vec2 uCell; // a quad's size in clip units
void main() {
    // Six vertices a quad, one quad an instance, row by row; depth grows with the quad so that the
    // depth test passes (drawn front to back, as the surface pass draws).
    ivec2 cell = ivec2(gl_InstanceID % uCells.x, gl_InstanceID / uCells.x);
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    vec2 p = (vec2(cell) + corners[gl_VertexID]) * uCell - 1.0;
    gl_Position = vec4(p, 0.5 * float(gl_InstanceID) / float(uCells.x * uCells.y), 1.0);
}
)glsl";
    GLuint depth = 0, vao = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, depthFormat, width, height);
    glCreateVertexArrays(1, &vao);
    const int cellsX = (width + quad - 1) / quad, cellsY = (height + quad - 1) / quad;
    std::printf("%-10s %6s %22s %22s %22s   (depth buffer %s)\n", "format", "bytes", "full screen",
                "+ depth test", ("quads of " + std::to_string(quad) + " px + depth").c_str(),
                depthName(depthFormat));
    for (const OutputFormat& format : kFormats) {
        if (!formats && format.internal != GL_RG32UI)
            continue; // the depth formats' table: the G-buffer's format alone
        GLuint target = 0, fbo = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &target);
        glTextureStorage2D(target, 1, format.internal, width, height);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
        const bool stencil = depthFormat == GL_DEPTH32F_STENCIL8 || depthFormat == GL_DEPTH24_STENCIL8;
        glNamedFramebufferTexture(fbo, stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, depth, 0);
        const std::string fragment = std::string("#version 450 core\nlayout(location = 0) out ") +
                                     format.type +
                                     " oValue;\nvoid main() {\n    uvec2 c = uvec2(gl_FragCoord.xy);\n"
                                     "    uint h = (c.x * 73856093u) ^ (c.y * 19349663u);\n    oValue = " +
                                     format.value + ";\n}\n";
        ShaderProgram full("probe output", kFullScreenVertex, fragment.c_str());
        ShaderProgram grid("probe grid", gridVertex.c_str(), fragment.c_str());
        glProgramUniform2i(grid.id(), grid.location("uCells"), cellsX, cellsY);
        grid.set("uCell",
                 Eigen::Vector2f(2.0f * float(quad) / float(width), 2.0f * float(quad) / float(height)));
        Timing timings[3];
        for (int mode = 0; mode < 3; ++mode)
            timings[mode] = measure(frames, [&] {
                glBindFramebuffer(GL_FRAMEBUFFER, fbo);
                glViewport(0, 0, width, height);
                glBindVertexArray(vao);
                if (mode == 0) {
                    glDisable(GL_DEPTH_TEST);
                } else {
                    glEnable(GL_DEPTH_TEST);
                    glDepthFunc(GL_LESS);
                    glDepthMask(GL_TRUE);
                    const GLfloat far = 1.0f;
                    glClearBufferfv(GL_DEPTH, 0, &far);
                }
                if (mode < 2) {
                    full.use();
                    glDrawArrays(GL_TRIANGLES, 0, 3);
                } else {
                    grid.use();
                    glDrawArraysInstanced(GL_TRIANGLES, 0, 6, cellsX * cellsY);
                }
            });
        glDisable(GL_DEPTH_TEST);
        std::printf("%-10s %6d %10.3f / %9.3f %10.3f / %9.3f %10.3f / %9.3f\n", format.name, format.bytes,
                    timings[0].gpuMs, timings[0].wallMs, timings[1].gpuMs, timings[1].wallMs,
                    timings[2].gpuMs, timings[2].wallMs);
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &target);
    }
    glDeleteVertexArrays(1, &vao);
    glDeleteTextures(1, &depth);
}

} // namespace

int main(int argc, char** argv) {
    int frames = 200, lights = 2, width = 1920, height = 1080, quad = 32;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--lights") && i + 1 < argc)
            lights = std::max(0, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--width") && i + 1 < argc)
            width = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--height") && i + 1 < argc)
            height = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--quad") && i + 1 < argc)
            quad = std::max(1, std::atoi(argv[++i]));
        else {
            std::fprintf(stderr, "usage: %s [--frames F] [--lights L] [--width W] [--height H] [--quad PX]\n",
                         argv[0]);
            return 2;
        }
    }
    GlContext context;
    std::printf("device: %s (%s), %dx%d, %d light(s), %d timed runs each\n",
                context.report().renderer.c_str(), context.report().kind.c_str(), width, height, lights,
                frames);

    GLuint color = 0, shadow = 0, fbo = 0, vao = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_RGBA8, width, height);
    glCreateTextures(GL_TEXTURE_2D, 1, &shadow);
    glTextureStorage2D(shadow, 1, GL_R16, 2048, 2048);
    std::vector<unsigned short> depths(std::size_t(2048) * 2048);
    for (std::size_t i = 0; i < depths.size(); ++i)
        depths[i] = (unsigned short)((i * 2654435761u) >> 16);
    glTextureSubImage2D(shadow, 0, 0, 0, 2048, 2048, GL_RED, GL_UNSIGNED_SHORT, depths.data());
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    glCreateVertexArrays(1, &vao);
    glBindImageTexture(1, shadow, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R16);
    glBindImageTexture(0, color, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);

    Timing results[2][2] = {}; // [shade][compute]
    for (int shade = 0; shade < 2; ++shade) {
        const std::string fragment = fragmentSource(lights, shade == 1);
        ShaderProgram raster("probe raster", kFullScreenVertex, fragment.c_str());
        raster.set("uSize", Eigen::Vector2f(float(width), float(height)));
        const std::string computeText = computeSource(lights, shade == 1);
        ShaderProgram compute("probe compute", computeText.c_str());
        compute.set("uSize", Eigen::Vector2f(float(width), float(height)));
        results[shade][0] = measure(frames, [&] {
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glViewport(0, 0, width, height);
            glBindVertexArray(vao);
            raster.use();
            glDrawArrays(GL_TRIANGLES, 0, 3);
        });
        results[shade][1] = measure(frames, [&] {
            compute.use();
            glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        });
    }
    std::printf("%-28s %22s %22s\n", "ms per pass (GPU / wall)", "fragment", "compute");
    const char* rows[] = {"constant output", "shaded"};
    for (int shade = 0; shade < 2; ++shade)
        std::printf("%-28s %10.3f / %9.3f %10.3f / %9.3f\n", rows[shade], results[shade][0].gpuMs,
                    results[shade][0].wallMs, results[shade][1].gpuMs, results[shade][1].wallMs);
    std::printf("%-28s %10.3f / %9.3f %10.3f / %9.3f\n", "shading alone (difference)",
                results[1][0].gpuMs - results[0][0].gpuMs, results[1][0].wallMs - results[0][0].wallMs,
                results[1][1].gpuMs - results[0][1].gpuMs, results[1][1].wallMs - results[0][1].wallMs);
    std::printf("\n");
    outputCosts(frames, width, height, quad, GL_DEPTH_COMPONENT32F, true); // the surface pass's depth format
    for (GLenum depth :
         {GL_DEPTH32F_STENCIL8, GL_DEPTH_COMPONENT24, GL_DEPTH24_STENCIL8, GL_DEPTH_COMPONENT16})
        outputCosts(frames, width, height, quad, depth, false);
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        std::fprintf(stderr, "GL error 0x%x\n", error);
        return 1;
    }
    glDeleteVertexArrays(1, &vao);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &shadow);
    glDeleteTextures(1, &color);
    return 0;
}
