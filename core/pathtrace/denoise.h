#pragma once
// A denoiser for path-traced images: the edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika and
// Lensch, "Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination Filtering", HPG 2010), guided
// by what the first surface of each pixel's paths was: its albedo, normal, distance and instance.
//
// The colour is divided by the albedo first and multiplied back after, so textures and colour edges stay
// sharp and only the lighting is smoothed. Fireflies (a pixel over twice as bright as its third brightest
// neighbour of its instance) are scaled down to that neighbour first. Each pass blurs with a 5 x 5 B3-spline
// kernel whose taps are 2^pass pixels apart, each tap weighted by how alike the two pixels' guides are:
// nothing across instances (ids) or the background, little across creases (normals) and depth steps, and
// little across lighting differences larger than the noise. How large the noise is comes, where the path
// tracer measured it, from each pixel's own samples, as in SVGF (Schied et al., "Spatiotemporal
// Variance-Guided Filtering", HPG 2017; its spatial part): the variance of the pixel's mean, blurred over its
// 3 x 3 neighbours, scales the luminance test, and each pass carries the variance through its weights, so a
// converged image is left nearly as it is and a noisy one smoothed. Without a measure (too few samples), a
// tolerance relative to the luminance that halves each pass. It is biased, as every denoiser is: the
// unfiltered image stays the reference.

#include <cstdint>
#include <span>
#include <vector>

#include "core/pathtrace/path_tracer.h"

namespace sp::pathtrace {

struct DenoiseGuides {
    int width = 0;
    int height = 0;
    std::span<const float> albedo;      // linear RGB, (height, width, 3), row 0 = top
    std::span<const float> normal;      // unit, (height, width, 3); 0 where nothing was hit
    std::span<const float> depth;       // metres along the ray to the first surface, (height, width); 0: none
    std::span<const std::uint32_t> ids; // the first surface's instance + 1, (height, width); 0: background
    // The variance of each pixel's mean lighting luminance (the colour over the albedo), (height, width);
    // empty: not measured.
    std::span<const float> variance = {};
};

// The filtered image of `color` (linear RGB, (height, width, 3)); `passes` in [1, 8] (5 reaches 31 pixels
// across). Throws sp::InvalidArgument naming a guide whose size does not match.
std::vector<float> denoise(std::span<const float> color, const DenoiseGuides& guides, int passes = 5);

// The accumulated image's mean hdr_color, denoised with its own guides (Accumulation's first-surface sums):
// the analytic lights' direct light (sharp shadows, nearly noiseless) is kept as it is and the rest (sky and
// indirect light, the noise) filtered.
std::vector<float> denoise(const Accumulation& image, int passes = 5);

} // namespace sp::pathtrace
