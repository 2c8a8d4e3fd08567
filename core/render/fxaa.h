#pragma once
// Fast approximate anti-aliasing of final_color (Lottes, "FXAA", NVIDIA 2009; the 3.11 quality variant's
// steps): an edge is found where a pixel's luma differs from its neighbours' by more than a threshold; its
// direction and its ends are searched along the luma of the pixel pairs across it, and the pixel is blended
// with its neighbour across the edge by how far it lies from the edge's nearer end (a staircase step becomes
// a ramp), or by how much it stands out from its neighbourhood (one-pixel features). Other pixels are copied.
//
// Why on the CPU, at readback: a software rasteriser runs a fragment shader's branches under masks, so a
// full-screen pass pays for the edge search at every pixel (and a multisampled frame costs llvmpipe about
// three times a single-sampled one), while here the 90-odd per cent of pixels that are not on an edge cost a
// five-pixel contrast test, and the rest is done in place, in the image just read back.
// The blend is in linear light, as a camera's sensor (and a supersampled reference) averages.
//
// Exact modalities (depth, ids, normals, ...) are never filtered: only final_color is.

#include <cstddef>
#include <cstdint>

namespace sp::render {

// Anti-aliases `image` (width x height RGBA8 sRGB, row 0 the top row, tightly packed) in place, on up to
// `threads` threads; alpha is kept. The result does not depend on the thread count.
void fxaa(std::uint8_t* image, int width, int height, int threads = 1);

// The threads a readback filters on: this machine's hardware threads, at most 4 (the filter is compute-bound,
// unlike a copy, so it gains from every core; a 1080p frame takes a few milliseconds on one).
int defaultFxaaThreads();

} // namespace sp::render
