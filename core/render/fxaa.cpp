#include "core/render/fxaa.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <mutex>
#include <vector>

#include "core/base/parallel.h"
#include "core/render/tone.h"

namespace sp::render {
namespace {

// An edge is a luma difference across a pixel's neighbours of at least an eighth of their brightest, and
// never less than 16/255 (FXAA's high-quality settings): fainter steps are hardly visible, and filtering
// them would soften texture and cost time (a lower floor changed no aliasing figure of
// bench/bench_image_quality.py's scenes).
constexpr int kEdgeThresholdMin = 16;
constexpr int kEdgeThresholdShift = 3;
// How much a pixel that stands out of its 3x3 neighbourhood (a feature thinner than a pixel) is blended.
constexpr float kSubpixel = 0.75f;
// The steps of the search for an edge's ends, in pixels (cumulative: 1, 2, 3, 5, 7, 11, 19); an edge longer
// than that is treated as ending there, which only lessens the blend of its middle pixels.
constexpr std::array<int, 7> kSearchSteps = {1, 1, 1, 2, 2, 4, 8};
// Rows of at least this many pixels a thread takes (a thread's wake-up costs tens of microseconds).
constexpr std::size_t kLeastPixelsPerPart = 64 * 1024;

const std::array<float, 256>& decodeTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i)
            t[std::size_t(i)] = float(srgbDecode(i / 255.0));
        return t;
    }();
    return table;
}

// sRGB encoding of linear [0, 1] by a table of 4096 steps (finer than an 8-bit step everywhere but in the
// darkest 0.1 %, where it is within half a step): a power per channel would cost more than the rest of a
// filtered pixel.
constexpr int kEncodeSteps = 4096;
const std::array<std::uint8_t, kEncodeSteps + 1>& encodeTable() {
    static const std::array<std::uint8_t, kEncodeSteps + 1> table = [] {
        std::array<std::uint8_t, kEncodeSteps + 1> t{};
        for (int i = 0; i <= kEncodeSteps; ++i)
            t[std::size_t(i)] = std::uint8_t(std::lround(srgbEncode(double(i) / kEncodeSteps) * 255.0));
        return t;
    }();
    return table;
}

std::uint8_t encode(float linear) {
    return encodeTable()[std::size_t(std::clamp(linear, 0.0f, 1.0f) * float(kEncodeSteps) + 0.5f)];
}

// Luma is the encoded green channel (FXAA's green-as-luma): green carries most of a pixel's perceived
// brightness, and reading it in place spares a pass that would compute luma for every pixel first.
struct Image {
    const std::uint8_t* rgba;
    int width, height;
    // The luma at (x, y), which must lie inside the image.
    int l(int x, int y) const { return rgba[4 * (std::size_t(y) * std::size_t(width) + std::size_t(x)) + 1]; }
    const std::uint8_t* pixel(int x, int y) const {
        return rgba + 4 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
    }
};

// The filtered colour of an edge pixel (x, y) whose 3x3 luma range is `range`, into `out`.
void filterPixel(const Image& image, int x, int y, int range, std::uint8_t* out) {
    // The neighbours, clamped to the image once.
    const int xw = std::max(x - 1, 0), xe = std::min(x + 1, image.width - 1);
    const int yn = std::max(y - 1, 0), ys = std::min(y + 1, image.height - 1);
    const float m = float(image.l(x, y));
    const float n = float(image.l(x, yn)), s = float(image.l(x, ys));
    const float w = float(image.l(xw, y)), e = float(image.l(xe, y));
    const float nw = float(image.l(xw, yn)), ne = float(image.l(xe, yn));
    const float sw = float(image.l(xw, ys)), se = float(image.l(xe, ys));

    // A pixel standing out of its neighbourhood's low-pass average: blended by how much (smoothstep,
    // squared).
    const float average = (2.0f * (n + s + w + e) + (nw + ne + sw + se)) / 12.0f;
    const float outlier = std::clamp(std::abs(average - m) / float(range), 0.0f, 1.0f);
    const float smooth = (3.0f - 2.0f * outlier) * outlier * outlier;
    const float subpixel = smooth * smooth * kSubpixel;

    // A horizontal edge (luma changing from row to row) or a vertical one, by second differences.
    const float horizontal =
        std::abs(nw + sw - 2.0f * w) + 2.0f * std::abs(n + s - 2.0f * m) + std::abs(ne + se - 2.0f * e);
    const float vertical =
        std::abs(nw + ne - 2.0f * n) + 2.0f * std::abs(w + e - 2.0f * m) + std::abs(sw + se - 2.0f * s);
    const bool alongX = horizontal >= vertical;
    // The side of the edge: towards the neighbour (across it) that differs more.
    const float before = alongX ? n : w, after = alongX ? s : e;
    const bool towardsBefore = std::abs(before - m) >= std::abs(after - m);
    const float across = towardsBefore ? before : after;

    // Walk along the edge both ways, on the average luma of the pixel pairs across it, until it leaves the
    // edge's average by a quarter of the gradient (an end) or the image ends.
    const int length = alongX ? image.width : image.height;
    const int at = alongX ? x : y;
    // The pair's two lumas: from the pixel's row (column) and the neighbour's, `stride` bytes a step along.
    const int nx = alongX ? x : (towardsBefore ? xw : xe);
    const int ny = alongX ? (towardsBefore ? yn : ys) : y;
    const std::uint8_t* first =
        image.rgba + 4 * (alongX ? std::size_t(y) * std::size_t(image.width) : std::size_t(x)) + 1;
    const std::uint8_t* second =
        image.rgba + 4 * (alongX ? std::size_t(ny) * std::size_t(image.width) : std::size_t(nx)) + 1;
    const std::size_t stride = alongX ? 4 : 4 * std::size_t(image.width);
    // In integers: a pair's luma sum less the edge's (m + across), against twice a quarter of the gradient.
    const int edgeSum = int(m + across);
    const int gradientSum = int(std::max(std::abs(before - m), std::abs(after - m)));
    const auto pairEnd = [&](int along) {
        const std::size_t k = stride * std::size_t(along);
        return int(first[k]) + int(second[k]) - edgeSum;
    };
    const auto isEnd = [&](int end) { return 2 * std::abs(end) >= gradientSum; };
    int negative = at, positive = at;
    int endNegative = 0, endPositive = 0;
    bool doneNegative = false, donePositive = false;
    for (int step : kSearchSteps) {
        if (!doneNegative) {
            negative = std::max(negative - step, 0);
            endNegative = pairEnd(negative);
            doneNegative = isEnd(endNegative) || negative == 0;
        }
        if (!donePositive) {
            positive = std::min(positive + step, length - 1);
            endPositive = pairEnd(positive);
            donePositive = isEnd(endPositive) || positive == length - 1;
        }
        if (doneNegative && donePositive)
            break;
    }
    // Blend by the distance to the nearer end, where the edge's luma there says the step lies this side.
    const int toNegative = at - negative, toPositive = positive - at;
    const bool nearerNegative = toNegative < toPositive;
    const int end = nearerNegative ? endNegative : endPositive;
    const bool mBelow = 2 * int(m) < edgeSum;
    const bool stepHere = (end < 0) != mBelow;
    const float span = float(toNegative + toPositive);
    // (An image one pixel long along the edge has no span: nothing to blend along it.)
    const float edgeOffset =
        stepHere && span > 0.0f ? 0.5f - float(std::min(toNegative, toPositive)) / span : 0.0f;
    const float offset = std::max(edgeOffset, subpixel);

    const std::uint8_t* centre = image.pixel(x, y);
    const std::uint8_t* neighbour = image.pixel(nx, ny);
    const std::array<float, 256>& linear = decodeTable();
    for (int c = 0; c < 3; ++c)
        out[c] = encode(linear[centre[c]] + offset * (linear[neighbour[c]] - linear[centre[c]]));
    out[3] = centre[3];
}

// Marks the pixels of a row whose 5-pixel neighbourhood (the rows above and below, clamped at the image's
// border; RGBA pixels, luma in green) holds an edge: edge[x] = the luma range there, or 0. Written so that
// the compiler vectorises it.
// (Compiled twice, for AVX2 and for the x86-64 baseline, and picked when the program loads: AVX2 compares
// 32 pixels at once.)
__attribute__((target_clones("avx2", "default"))) void markEdges(const std::uint8_t* up,
                                                                 const std::uint8_t* row,
                                                                 const std::uint8_t* down, std::size_t w,
                                                                 std::uint8_t* edge) {
    const auto g = [](const std::uint8_t* pixels, std::size_t x) { return pixels[4 * x + 1]; };
    const auto mark = [&](std::size_t x, std::uint8_t left, std::uint8_t right) {
        const std::uint8_t u = g(up, x), d = g(down, x), m = g(row, x);
        const std::uint8_t lo = std::min(std::min(std::min(u, d), std::min(left, right)), m);
        const std::uint8_t hi = std::max(std::max(std::max(u, d), std::max(left, right)), m);
        const std::uint8_t range = std::uint8_t(hi - lo);
        const std::uint8_t threshold =
            std::max(std::uint8_t(kEdgeThresholdMin), std::uint8_t(hi >> kEdgeThresholdShift));
        edge[x] = range >= threshold ? range : 0;
    };
    mark(0, g(row, 0), g(row, w > 1 ? 1 : 0));
    for (std::size_t x = 1; x + 1 < w; ++x)
        mark(x, g(row, x - 1), g(row, x + 1));
    if (w > 1)
        mark(w - 1, g(row, w - 2), g(row, w - 1));
    std::memset(edge + w, 0, 8); // the tail of the last eight-pixel word
}

} // namespace

void fxaa(std::uint8_t* image, int width, int height, int threads) {
    if (width <= 0 || height <= 0)
        return;
    const std::size_t w = std::size_t(width), h = std::size_t(height);
    const Image view{image, width, height};
    // The filtered pixels are computed from the unfiltered image first, then written: in place, with no copy
    // of the frame (a few per cent of its pixels change).
    struct Filtered {
        std::size_t offset;
        std::array<std::uint8_t, 4> rgba;
    };
    std::vector<Filtered> filtered;
    std::mutex merging;
    parallelRanges(h, 1, kLeastPixelsPerPart / w + 1, threads, threads,
                   [&](std::size_t begin, std::size_t end) {
                       std::vector<std::uint8_t> edge(w + 8);
                       std::vector<Filtered> mine;
                       for (std::size_t y = begin; y < end; ++y) {
                           const std::uint8_t* up = image + 4 * (y > 0 ? y - 1 : 0) * w;
                           const std::uint8_t* row = image + 4 * y * w;
                           const std::uint8_t* down = image + 4 * (y + 1 < h ? y + 1 : y) * w;
                           markEdges(up, row, down, w, edge.data());
                           // Most pixels are not on an edge: skip them eight at a time.
                           for (std::size_t x = 0; x < w; x += 8) {
                               std::uint64_t any = 0;
                               std::memcpy(&any, edge.data() + x, sizeof any);
                               if (any == 0)
                                   continue;
                               for (std::size_t i = x; i < std::min(x + 8, w); ++i)
                                   if (edge[i] != 0) {
                                       Filtered& f = mine.emplace_back();
                                       f.offset = 4 * (y * w + i);
                                       filterPixel(view, int(i), int(y), edge[i], f.rgba.data());
                                   }
                           }
                       }
                       const std::lock_guard lock(merging);
                       filtered.insert(filtered.end(), mine.begin(), mine.end());
                   });
    for (const Filtered& f : filtered)
        std::memcpy(image + f.offset, f.rgba.data(), 4);
}

int defaultFxaaThreads() {
    return std::clamp(hardwareThreads(), 1, 4);
}

} // namespace sp::render
