#include "core/procedural/pcg_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace sp::procedural::pcg {

namespace {

double uniform(std::mt19937_64& rng, double low, double high) {
    return low == high ? low : std::uniform_real_distribution<double>(low, high)(rng);
}

int variantOf(std::mt19937_64& rng, int variants) {
    return variants <= 1 ? 0 : std::uniform_int_distribution<int>(0, variants - 1)(rng);
}

double pointToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

bool segmentsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c),
                 d4 = cross(d - c, b - c);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

} // namespace

double distanceToPolyline(const Eigen::AlignedBox2d& rect, const Polyline& line) {
    const Eigen::Vector2d corners[4] = {
        rect.corner(Eigen::AlignedBox2d::BottomLeft), rect.corner(Eigen::AlignedBox2d::BottomRight),
        rect.corner(Eigen::AlignedBox2d::TopRight), rect.corner(Eigen::AlignedBox2d::TopLeft)};
    double best = INFINITY;
    for (size_t i = 0; i < line.size(); ++i) {
        const Eigen::Vector2d a = line[i].head<2>();
        if (rect.contains(a))
            return 0.0;
        best = std::min(best, rect.exteriorDistance(a));
        if (i + 1 == line.size())
            break;
        const Eigen::Vector2d b = line[i + 1].head<2>();
        for (int k = 0; k < 4; ++k) {
            if (segmentsCross(a, b, corners[k], corners[(k + 1) % 4]))
                return 0.0;
            best = std::min(best, pointToSegment(corners[k], a, b));
        }
    }
    return best;
}

std::vector<Placement> scatter(const Eigen::AlignedBox2d& area, const ScatterRules& rules,
                               const std::vector<Eigen::AlignedBox2d>& exclusions, std::mt19937_64& rng) {
    std::vector<Placement> placed;
    if (area.isEmpty() || rules.maxCount <= 0)
        return placed;
    // A grid of cells no wider than spacing / sqrt(2) holds at most one placement each, so a candidate only
    // looks at the 5 x 5 cells around it. Only the cells that hold one are stored: the memory is bounded by
    // MaxCount, however many cells the area has (the caller bounds the cells along an axis to 2^31).
    const double cell = rules.spacing > 0.0 ? rules.spacing / std::sqrt(2.0) : 1.0;
    const Eigen::Vector2d size = area.sizes();
    const std::int64_t columns = std::max<std::int64_t>(1, std::int64_t(std::ceil(size.x() / cell))),
                       rows = std::max<std::int64_t>(1, std::int64_t(std::ceil(size.y() / cell)));
    std::unordered_map<std::int64_t, int> grid; // y * columns + x -> its placement
    const auto at = [&](std::int64_t x, std::int64_t y) {
        const auto found = grid.find(y * columns + x);
        return found == grid.end() ? -1 : found->second;
    };
    const long attempts = 30L * rules.maxCount;
    for (long attempt = 0; attempt < attempts && int(placed.size()) < rules.maxCount; ++attempt) {
        const Eigen::Vector2d p(uniform(rng, area.min().x(), area.max().x()),
                                uniform(rng, area.min().y(), area.max().y()));
        if (std::any_of(exclusions.begin(), exclusions.end(),
                        [&](const Eigen::AlignedBox2d& box) { return box.contains(p); }))
            continue;
        const std::int64_t cx = std::min(columns - 1, std::int64_t((p.x() - area.min().x()) / cell));
        const std::int64_t cy = std::min(rows - 1, std::int64_t((p.y() - area.min().y()) / cell));
        bool fits = true;
        if (rules.spacing > 0.0) {
            for (std::int64_t y = std::max<std::int64_t>(0, cy - 2); fits && y <= std::min(rows - 1, cy + 2);
                 ++y)
                for (std::int64_t x = std::max<std::int64_t>(0, cx - 2);
                     fits && x <= std::min(columns - 1, cx + 2); ++x) {
                    const int other = at(x, y);
                    fits =
                        other < 0 || (placed[size_t(other)].location.head<2>() - p).norm() >= rules.spacing;
                }
        }
        if (!fits)
            continue;
        Placement placement;
        placement.location = Eigen::Vector3d(p.x(), p.y(), 0.0);
        placement.yawDegrees = rules.randomYaw ? uniform(rng, 0.0, 360.0) : 0.0;
        placement.scale = Eigen::Vector3d::Constant(uniform(rng, rules.minScale, rules.maxScale));
        placement.variant = variantOf(rng, rules.variants);
        grid[cy * columns + cx] = int(placed.size());
        placed.push_back(placement);
    }
    return placed;
}

std::vector<Placement> alongPolyline(const Polyline& curve, const SplineRules& rules, std::mt19937_64& rng) {
    std::vector<Placement> placed;
    if (curve.size() < 2 || rules.spacing <= 0.0)
        return placed;
    double next = 0.0, walked = 0.0;
    for (size_t i = 0; i + 1 < curve.size(); ++i) {
        const Eigen::Vector3d a = curve[i], b = curve[i + 1];
        const double length = (b - a).norm();
        if (length <= 0.0)
            continue;
        const Eigen::Vector3d direction = (b - a) / length;
        const Eigen::Vector3d left(-direction.y(), direction.x(), 0.0);
        const double heading = std::atan2(direction.y(), direction.x()) * 180.0 / M_PI;
        while (next <= walked + length + 1e-9) { // a curve sampled in pieces: its end must count
            const Eigen::Vector3d on = a + direction * (next - walked);
            for (int side = 0; side < (rules.bothSides ? 2 : 1); ++side) {
                Placement placement;
                const double offset = side == 0 ? rules.offset : -rules.offset;
                placement.location = on + left.normalized() * offset;
                placement.yawDegrees = rules.align ? heading + (side == 1 ? 180.0 : 0.0)
                                                   : (rules.randomYaw ? uniform(rng, 0.0, 360.0) : 0.0);
                placement.scale = Eigen::Vector3d::Constant(uniform(rng, rules.minScale, rules.maxScale));
                placement.variant = variantOf(rng, rules.variants);
                placed.push_back(placement);
            }
            next += rules.spacing;
        }
        walked += length;
    }
    return placed;
}

std::vector<Placement> cityBlocks(const Eigen::AlignedBox2d& area, const CityRules& rules,
                                  const std::vector<Polyline>& roads, std::mt19937_64& rng) {
    std::vector<Placement> placed;
    if (area.isEmpty() || rules.blockSize <= 0.0 || rules.lotsPerSide <= 0)
        return placed;
    const double pitch = rules.blockSize + rules.streetWidth;
    const double lot = rules.blockSize / rules.lotsPerSide, footprint = 0.8 * lot;
    for (double by = area.min().y(); by + rules.blockSize <= area.max().y() + 1e-9; by += pitch)
        for (double bx = area.min().x(); bx + rules.blockSize <= area.max().x() + 1e-9; bx += pitch)
            for (int j = 0; j < rules.lotsPerSide; ++j)
                for (int i = 0; i < rules.lotsPerSide; ++i) {
                    const Eigen::Vector2d centre(bx + (i + 0.5) * lot, by + (j + 0.5) * lot);
                    const Eigen::AlignedBox2d rect(centre.array() - footprint / 2,
                                                   centre.array() + footprint / 2);
                    // The height is drawn for every lot, built or not, so a road moving does not reshuffle
                    // the rest of the city.
                    const double height = uniform(rng, rules.minHeight, rules.maxHeight);
                    const int variant = variantOf(rng, rules.variants);
                    if (std::any_of(roads.begin(), roads.end(), [&](const Polyline& road) {
                            return distanceToPolyline(rect, road) < rules.roadWidth / 2;
                        }))
                        continue;
                    Placement placement;
                    placement.location = Eigen::Vector3d(centre.x(), centre.y(), 0.0);
                    placement.scale = Eigen::Vector3d(footprint, footprint, height);
                    placement.variant = variant;
                    placed.push_back(placement);
                }
    return placed;
}

} // namespace sp::procedural::pcg
