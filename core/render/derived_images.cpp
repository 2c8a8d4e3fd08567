#include "core/render/derived_images.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/error.h"
#include "core/base/parallel.h"
#include "core/render/image_buffer.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace sp::render {

namespace {

#if defined(__x86_64__)
// Eight float16 values at `source` as float32, and back (rounded to nearest even).
__attribute__((target("avx2,f16c"))) __m256 load8(const std::uint16_t* source) {
    return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(source)));
}
__attribute__((target("avx2,f16c"))) void store8(std::uint16_t* destination, __m256 values) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(destination),
                     _mm256_cvtps_ph(values, _MM_FROUND_TO_NEAREST_INT));
}

// Eight pixels at a time: their 24 channels are three vectors of eight, and each pixel's (1 - metallic) is
// spread over its three channels with permutes.
__attribute__((target("avx2,f16c"))) std::size_t diffuseOnlyF16c(const std::uint16_t* base,
                                                                 const std::uint16_t* metallic,
                                                                 const std::uint16_t* illumination,
                                                                 std::uint16_t* out, std::size_t pixels) {
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256i spread[3] = {_mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2),
                               _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5),
                               _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7)};
    std::size_t p = 0;
    for (; p + 8 <= pixels; p += 8) {
        const __m256 dielectric = _mm256_sub_ps(one, load8(metallic + p));
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t at = 3 * p + 8 * k;
            const __m256 weighted =
                _mm256_mul_ps(load8(base + at), _mm256_permutevar8x32_ps(dielectric, spread[k]));
            store8(out + at, _mm256_mul_ps(weighted, load8(illumination + at)));
        }
    }
    return p;
}

// Eight pixels at a time: the 32 channels of HDR colour (RGBA) are packed into 24 (RGB) with permutes and
// blends, then diffuse_only is taken from them.
__attribute__((target("avx2,f16c"))) std::size_t specularResidualF16c(const std::uint16_t* hdr,
                                                                      const std::uint16_t* diffuse,
                                                                      std::uint16_t* out,
                                                                      std::size_t pixels) {
    const __m256i first = _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 0, 1);  // h0's rgb rgb, then h1's r g
    const __m256i second = _mm256_setr_epi32(2, 4, 5, 6, 0, 1, 2, 4); // h1's b rgb, then h2's rgb r
    const __m256i third = _mm256_setr_epi32(5, 6, 0, 1, 2, 4, 5, 6);  // h2's g b, then h3's rgb rgb
    std::size_t p = 0;
    for (; p + 8 <= pixels; p += 8) {
        const __m256 h0 = load8(hdr + 4 * p), h1 = load8(hdr + 4 * p + 8), h2 = load8(hdr + 4 * p + 16),
                     h3 = load8(hdr + 4 * p + 24);
        const __m256 rgb[3] = {
            _mm256_blend_ps(_mm256_permutevar8x32_ps(h0, first), _mm256_permutevar8x32_ps(h1, first), 0xc0),
            _mm256_blend_ps(_mm256_permutevar8x32_ps(h1, second), _mm256_permutevar8x32_ps(h2, second), 0xf0),
            _mm256_blend_ps(_mm256_permutevar8x32_ps(h2, third), _mm256_permutevar8x32_ps(h3, third), 0xfc)};
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t at = 3 * p + 8 * k;
            store8(out + at, _mm256_sub_ps(rgb[k], load8(diffuse + at)));
        }
    }
    return p;
}

bool hasF16c() {
    static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("f16c");
    return has;
}

// The eight floats of a shuffle of two vectors' pairs (0 1 4 5 | 2 3 6 7 of the pixels) in pixel order.
__attribute__((target("avx2"))) __m256 inPixelOrder(__m256 v) {
    return _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(v), 0xd8));
}

// Eight pixels at a time, with the scalar loop's operations in the same order (no fused multiply-adds):
// the same floats.
__attribute__((target("avx2"))) std::size_t decodeOctahedralAvx2(const float* encoded, float* out,
                                                                 std::size_t pixels) {
    const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
    const __m256 signBit = _mm256_set1_ps(-0.0f);
    std::size_t p = 0;
    alignas(32) float xs[8], ys[8], zs[8];
    for (; p + 8 <= pixels; p += 8) {
        const __m256 a = _mm256_loadu_ps(encoded + 2 * p), b = _mm256_loadu_ps(encoded + 2 * p + 8);
        __m256 x = inPixelOrder(_mm256_shuffle_ps(a, b, 0x88)),
               y = inPixelOrder(_mm256_shuffle_ps(a, b, 0xdd));
        const __m256 ax = _mm256_andnot_ps(signBit, x), ay = _mm256_andnot_ps(signBit, y);
        const __m256 z = _mm256_sub_ps(_mm256_sub_ps(one, ax), ay);
        // Folded where z < 0: ((1 - |y|) sign x, (1 - |x|) sign y), a zero's sign taken as +.
        const __m256 folded = _mm256_cmp_ps(z, zero, _CMP_LT_OQ);
        const __m256 sx = _mm256_blendv_ps(one, _mm256_set1_ps(-1.0f), _mm256_cmp_ps(x, zero, _CMP_LT_OQ));
        const __m256 sy = _mm256_blendv_ps(one, _mm256_set1_ps(-1.0f), _mm256_cmp_ps(y, zero, _CMP_LT_OQ));
        const __m256 fx = _mm256_mul_ps(_mm256_sub_ps(one, ay), sx);
        const __m256 fy = _mm256_mul_ps(_mm256_sub_ps(one, ax), sy);
        x = _mm256_blendv_ps(x, fx, folded);
        y = _mm256_blendv_ps(y, fy, folded);
        const __m256 length = _mm256_sqrt_ps(
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(x, x), _mm256_mul_ps(y, y)), _mm256_mul_ps(z, z)));
        // Not a surface where |x| > 1 (kNoOctahedralNormal) or the value is not a number: zero.
        const __m256 surface = _mm256_cmp_ps(ax, one, _CMP_LE_OQ);
        _mm256_store_ps(xs, _mm256_and_ps(surface, _mm256_div_ps(x, length)));
        _mm256_store_ps(ys, _mm256_and_ps(surface, _mm256_div_ps(y, length)));
        _mm256_store_ps(zs, _mm256_and_ps(surface, _mm256_div_ps(z, length)));
        float* row = out + 3 * p;
        for (int i = 0; i < 8; ++i) {
            row[3 * i] = xs[i];
            row[3 * i + 1] = ys[i];
            row[3 * i + 2] = zs[i];
        }
    }
    return p;
}
bool hasAvx2() {
    static const bool has = __builtin_cpu_supports("avx2");
    return has;
}
#else // elsewhere the scalar loops do it all
std::size_t diffuseOnlyF16c(const std::uint16_t*, const std::uint16_t*, const std::uint16_t*, std::uint16_t*,
                            std::size_t) {
    return 0;
}
std::size_t specularResidualF16c(const std::uint16_t*, const std::uint16_t*, std::uint16_t*, std::size_t) {
    return 0;
}
bool hasF16c() {
    return false;
}
std::size_t decodeOctahedralAvx2(const float*, float*, std::size_t) {
    return 0;
}
bool hasAvx2() {
    return false;
}
#endif

} // namespace

void computeDiffuseOnly(const std::uint16_t* base, const std::uint16_t* metallic,
                        const std::uint16_t* illumination, std::uint16_t* out, std::size_t pixels) {
    const std::size_t done = hasF16c() ? diffuseOnlyF16c(base, metallic, illumination, out, pixels) : 0;
    for (std::size_t p = done; p < pixels; ++p) {
        const float dielectric = 1.0f - halfToFloat(metallic[p]);
        for (std::size_t c = 0; c < 3; ++c)
            out[3 * p + c] =
                floatToHalf(halfToFloat(base[3 * p + c]) * dielectric * halfToFloat(illumination[3 * p + c]));
    }
}

void computeSpecularResidual(const std::uint16_t* hdr, const std::uint16_t* diffuse, std::uint16_t* out,
                             std::size_t pixels) {
    const std::size_t done = hasF16c() ? specularResidualF16c(hdr, diffuse, out, pixels) : 0;
    for (std::size_t p = done; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c)
            out[3 * p + c] = floatToHalf(halfToFloat(hdr[4 * p + c]) - halfToFloat(diffuse[3 * p + c]));
}

void computePositionFromDepth(const float* depth, const Camera& camera, float* out) {
    const int width = camera.params.width, height = camera.params.height;
    const double focal = camera.focalLengthPixels();
    const Eigen::Matrix3d axes = camera.pose.linear(); // columns: forward, left, up (Camera::project())
    const Eigen::Vector3d origin = camera.pose.translation();
    // A pixel's centre ray, (1, (W/2 - u - 0.5) / f, (H/2 - v - 0.5) / f) in the camera's body frame, is a
    // row's first ray plus a step per column.
    const Eigen::Vector3d step = -axes.col(1) / focal;
    // Bands of rows, two a thread.
    const auto rows = [&](std::size_t firstRow, std::size_t endRow) {
        for (int v = int(firstRow); v < int(endRow); ++v) {
            const Eigen::Vector3d first = axes.col(0) + axes.col(1) * ((0.5 * width - 0.5) / focal) +
                                          axes.col(2) * ((0.5 * height - v - 0.5) / focal);
            const float* in = depth + std::size_t(v) * std::size_t(width);
            float* row = out + 3 * std::size_t(v) * std::size_t(width);
            for (int u = 0; u < width; ++u) {
                const double d = in[u];
                const Eigen::Vector3d point =
                    d == 0.0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(origin + d * (first + u * step));
                row[3 * u] = float(point.x());
                row[3 * u + 1] = float(point.y());
                row[3 * u + 2] = float(point.z());
            }
        }
    };
    parallelRanges(std::size_t(height), 1, 1, 2 * hardwareThreads(), hardwareThreads(), rows);
}

void decodeOctahedralNormals(const float* encoded, float* out, std::size_t pixels) {
    // Bands of whole groups of eight pixels (the vector width), two a thread.
    const auto band = [&](std::size_t first, std::size_t end) {
        const std::size_t count = end - first;
        const float* in = encoded + 2 * first;
        float* at = out + 3 * first;
        const std::size_t done = hasAvx2() ? decodeOctahedralAvx2(in, at, count) : 0;
        for (std::size_t p = done; p < count; ++p) {
            float x = in[2 * p], y = in[2 * p + 1];
            const float ax = std::abs(x), ay = std::abs(y);
            const float z = 1.0f - ax - ay;
            if (z < 0.0f) {
                const float fx = (1.0f - ay) * (x < 0.0f ? -1.0f : 1.0f);
                const float fy = (1.0f - ax) * (y < 0.0f ? -1.0f : 1.0f);
                x = fx;
                y = fy;
            }
            const float length = std::sqrt(x * x + y * y + z * z);
            const bool surface = ax <= 1.0f; // else kNoOctahedralNormal, or not a number
            at[3 * p] = surface ? x / length : 0.0f;
            at[3 * p + 1] = surface ? y / length : 0.0f;
            at[3 * p + 2] = surface ? z / length : 0.0f;
        }
    };
    parallelRanges(pixels, 8, 4096, 2 * hardwareThreads(), hardwareThreads(), band);
}

void lookUpMaterials(const std::uint32_t* record, std::span<const DrawMaterial> draws, std::size_t pixels,
                     const MaterialImages& out) {
    // Record 0 is the background: an entry of zeros in front of the draws.
    std::vector<DrawMaterial> table(draws.size() + 1);
    std::copy(draws.begin(), draws.end(), table.begin() + 1);
    std::size_t bad = pixels; // the first pixel whose record is past the draws
    for (std::size_t p = 0; p < pixels; ++p) {
        std::uint32_t r = record[p];
        if (r >= table.size()) {
            bad = std::min(bad, p);
            r = 0;
        }
        const DrawMaterial& m = table[r];
        if (out.objectIds != nullptr)
            out.objectIds[p] = m.objectId;
        if (out.materialIds != nullptr)
            out.materialIds[p] = m.materialId;
        if (out.baseColor != nullptr) {
            out.baseColor[3 * p] = m.baseColor[0];
            out.baseColor[3 * p + 1] = m.baseColor[1];
            out.baseColor[3 * p + 2] = m.baseColor[2];
        }
        if (out.roughness != nullptr)
            out.roughness[p] = m.roughness;
        if (out.metallic != nullptr)
            out.metallic[p] = m.metallic;
        if (out.ambientOcclusion != nullptr)
            out.ambientOcclusion[p] = m.ambientOcclusion;
    }
    SP_CHECK(bad == pixels, InvalidState, "lookUpMaterials(): pixel ", bad, " holds record ", record[bad],
             ", past the ", draws.size(), " draws");
}

} // namespace sp::render
