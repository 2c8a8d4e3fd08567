#include "core/render/mesh_lods.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "core/base/parallel.h"
#include "core/base/recent_cache.h"

namespace sp::render {
namespace {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "positions are read as packed float triples");

// The vertices `indices` use, renumbered in first use (meshoptimizer's fetch order), into `level`.
void compact(const MeshData& mesh, std::vector<std::uint32_t> indices, MeshData& level) {
    std::vector<unsigned> remap(mesh.positions.size());
    const std::size_t vertices =
        meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), mesh.positions.size());
    level.positions.resize(vertices);
    level.normals.resize(vertices);
    level.uvs.resize(vertices);
    meshopt_remapVertexBuffer(level.positions.data(), mesh.positions.data(), mesh.positions.size(),
                              sizeof(Eigen::Vector3f), remap.data());
    meshopt_remapVertexBuffer(level.normals.data(), mesh.normals.data(), mesh.normals.size(),
                              sizeof(Eigen::Vector3f), remap.data());
    meshopt_remapVertexBuffer(level.uvs.data(), mesh.uvs.data(), mesh.uvs.size(), sizeof(Eigen::Vector2f),
                              remap.data());
    meshopt_remapIndexBuffer(indices.data(), indices.data(), indices.size(), remap.data());
    level.indices = std::move(indices);
}

// The closest point to `p` on triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3f closestOnTriangle(const Eigen::Vector3f& p, const Eigen::Vector3f& a,
                                  const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
    const Eigen::Vector3f ab = b - a, ac = c - a, ap = p - a;
    const float d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0f && d2 <= 0.0f)
        return a;
    const Eigen::Vector3f bp = p - b;
    const float d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0f && d4 <= d3)
        return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f)
        return a + ab * (d1 / (d1 - d3));
    const Eigen::Vector3f cp = p - c;
    const float d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0f && d5 <= d6)
        return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f)
        return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denominator = 1.0f / (va + vb + vc);
    return a + ab * (vb * denominator) + ac * (vc * denominator);
}

// How far the mesh's surface moved in a level (`level`: its triangles, indices into `mesh`): the largest
// distance from a vertex of `mesh` to the level's nearest triangle, found through a grid of those triangles.
// (The simplifier's own error is a quadric estimate: on a fine sphere the surface moved up to 2.6 times it.)
float deviation(const MeshData& mesh, const std::vector<std::uint32_t>& level, const Eigen::Vector3f& min,
                const Eigen::Vector3f& max) {
    const std::size_t triangles = level.size() / 3;
    const Eigen::Vector3f extent = (max - min).cwiseMax(Eigen::Vector3f::Constant(1e-6f));
    // About one triangle a cell over the bounds' volume, at most 64 cells a side.
    const float side = std::cbrt(extent.prod() / float(triangles));
    const Eigen::Vector3i cells =
        (extent / std::max(side, 1e-6f)).array().ceil().cast<int>().matrix().cwiseMax(1).cwiseMin(64);
    const Eigen::Vector3f toCell = cells.cast<float>().cwiseQuotient(extent);
    const float cellWidth = extent.cwiseQuotient(cells.cast<float>()).minCoeff();
    const auto cellOf = [&](const Eigen::Vector3f& p) -> Eigen::Vector3i {
        const Eigen::Vector3f c = (p - min).cwiseProduct(toCell);
        return c.array().floor().cast<int>().matrix().cwiseMax(0).cwiseMin(cells - Eigen::Vector3i::Ones());
    };
    const auto flat = [&](int x, int y, int z) { return std::size_t((z * cells.y() + y) * cells.x() + x); };
    std::vector<std::vector<std::uint32_t>> grid(std::size_t(cells.prod()));
    const auto corner = [&](std::size_t t, int k) -> const Eigen::Vector3f& {
        return mesh.positions[level[3 * t + std::size_t(k)]];
    };
    for (std::size_t t = 0; t < triangles; ++t) {
        const Eigen::Vector3i lo = cellOf(corner(t, 0).cwiseMin(corner(t, 1)).cwiseMin(corner(t, 2)));
        const Eigen::Vector3i hi = cellOf(corner(t, 0).cwiseMax(corner(t, 1)).cwiseMax(corner(t, 2)));
        for (int z = lo.z(); z <= hi.z(); ++z)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int x = lo.x(); x <= hi.x(); ++x)
                    grid[flat(x, y, z)].push_back(std::uint32_t(t));
    }
    // The squared distance from p to the nearest triangle, or any no greater than `enough` (the largest found
    // so far, which p then cannot raise): rings of cells around p's, until the nearest found is nearer than
    // any cell of the next ring can be ((ring - 1) cell widths at least).
    const auto nearest = [&](const Eigen::Vector3f& p, float enough) {
        const Eigen::Vector3i centre = cellOf(p);
        float best = std::numeric_limits<float>::max();
        for (int ring = 0; ring <= cells.maxCoeff(); ++ring) {
            const float reach = float(ring - 1) * cellWidth;
            if (best <= enough || (reach > 0.0f && best <= reach * reach))
                break;
            const Eigen::Vector3i lo = (centre.array() - ring).max(0),
                                  hi = (centre.array() + ring).min(cells.array() - 1);
            for (int z = lo.z(); z <= hi.z(); ++z)
                for (int y = lo.y(); y <= hi.y(); ++y)
                    for (int x = lo.x(); x <= hi.x(); ++x) {
                        if ((Eigen::Vector3i(x, y, z) - centre).cwiseAbs().maxCoeff() != ring)
                            continue; // an inner ring's, seen
                        for (std::uint32_t t : grid[flat(x, y, z)])
                            best = std::min(
                                best, (closestOnTriangle(p, corner(t, 0), corner(t, 1), corner(t, 2)) - p)
                                          .squaredNorm());
                    }
        }
        return best;
    };
    // The vertices of the mesh's triangles that the level dropped (those it kept are its triangles' corners),
    // in parts on the machine's threads.
    std::vector<char> dropped(mesh.positions.size(), 0);
    for (std::uint32_t index : mesh.indices)
        dropped[index] = 1;
    for (std::uint32_t index : level)
        dropped[index] = 0;
    std::mutex merging;
    float largest = 0.0f;
    parallelRanges(mesh.positions.size(), 1, 1024, 4 * hardwareThreads(), hardwareThreads(),
                   [&](std::size_t begin, std::size_t end) {
                       float found = 0.0f;
                       for (std::size_t v = begin; v < end; ++v)
                           if (dropped[v] != 0)
                               found = std::max(found, nearest(mesh.positions[v], found));
                       const std::lock_guard<std::mutex> lock(merging);
                       largest = std::max(largest, found);
                   });
    return std::sqrt(largest);
}

} // namespace

MeshLevels simplifiedLods(const MeshData& mesh, const std::function<void()>& levelDone) {
    MeshLevels lods;
    const std::size_t triangles = mesh.indices.size() / 3;
    if (triangles < kLeastLodTriangles)
        return lods;
    Eigen::Vector3f min, max;
    mesh.bounds(min, max);
    const float radius = 0.5f * (max - min).norm();
    const float* positions = mesh.positions.front().data();
    const float scale = meshopt_simplifyScale(positions, mesh.positions.size(), sizeof(Eigen::Vector3f));
    if (!(radius > 0.0f) || !(scale > 0.0f))
        return lods;
    // The simplifier's errors are fractions of `scale` (the mesh's largest extent); MeshLod's of `radius`.
    const float toRadius = scale / radius;
    // A submesh alone sees the edges it shares with the others as its border: locked, they stay where the
    // neighbouring material's triangles meet them.
    const unsigned options = mesh.submeshes.size() > 1 ? unsigned(meshopt_SimplifyLockBorder) : 0u;
    // Each level is simplified from the one before (indices into the mesh's vertices), which spares the
    // simplifier most of its work on a large mesh (1,000,000 triangles: 4.4 s for the levels when each began
    // from the full mesh); its error is measured against the full mesh all the same.
    std::vector<std::uint32_t> current = mesh.indices;
    std::vector<Submesh> currentSubmeshes = mesh.submeshes;
    float previousError = 0.0f;
    std::vector<std::uint32_t> simplified(mesh.indices.size());
    while (current.size() / 3 >= kLeastLodTriangles / 4) {
        MeshData level;
        level.name = mesh.name;
        std::vector<std::uint32_t> indices;
        float error = 0.0f;
        bool emptied = false;
        for (const Submesh& submesh : currentSubmeshes) {
            const std::uint32_t* source = current.data() + submesh.firstIndex;
            const std::size_t target = submesh.indexCount / 3 / 2 * 3;
            float submeshError = 0.0f;
            const std::size_t kept =
                submesh.indexCount == 0
                    ? 0
                    : meshopt_simplify(simplified.data(), source, submesh.indexCount, positions,
                                       mesh.positions.size(), sizeof(Eigen::Vector3f), target,
                                       kMostLodError / toRadius, options, &submeshError);
            emptied = emptied || (submesh.indexCount > 0 && kept == 0);
            error = std::max(error, submeshError * toRadius);
            level.submeshes.push_back({std::uint32_t(indices.size()), std::uint32_t(kept)});
            indices.insert(indices.end(), simplified.begin(), simplified.begin() + std::ptrdiff_t(kept));
        }
        // Stalled (the simplifier stops at its error bound or where topology forbids collapses) or a material
        // gone: the levels so far are all. Else the level's error is how far its surface moved, measured.
        if (emptied || indices.size() * 5 > current.size() * 4)
            break;
        error = std::max(error, deviation(mesh, indices, min, max) / radius);
        if (!(error <= kMostLodError))
            break;
        previousError = std::max(error, previousError); // MeshLod errors never decrease
        current = indices;
        currentSubmeshes = level.submeshes;
        compact(mesh, std::move(indices), level);
        lods.emplace_back(std::move(level), previousError);
        if (levelDone)
            levelDone();
    }
    return lods;
}

namespace {

// The bytes a mesh's levels hold.
std::size_t bytesOf(const MeshLevels& levels) {
    std::size_t bytes = 0;
    for (const auto& [level, error] : levels)
        bytes += level.positions.size() * (sizeof(Eigen::Vector3f) * 2 + sizeof(Eigen::Vector2f)) +
                 level.indices.size() * sizeof(std::uint32_t);
    return bytes;
}

} // namespace

std::shared_ptr<const MeshLevels> sharedLods(const std::string& key, const MeshData& mesh,
                                             const std::function<void()>& levelDone) {
    static base::RecentCache<MeshLevels> cache(kLodCacheBytes);
    if (auto levels = cache.find(key))
        return levels;
    // Made outside the cache's lock: another world's import of another mesh need not wait for this one (two
    // worlds making the same levels at once both make them; one set is kept).
    auto levels = std::make_shared<const MeshLevels>(simplifiedLods(mesh, levelDone));
    return cache.insert(key, levels, bytesOf(*levels));
}

} // namespace sp::render
