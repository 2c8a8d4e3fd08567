#include "core/pathtrace/irradiance_probes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "core/base/error.h"
#include "core/base/log.h"

namespace sp::pathtrace {
namespace {

// The lattice's offset from multiples of the spacing, in cells: walls and floors are usually placed at
// round coordinates, and a probe on a surface sees half its rays end at distance 0.
constexpr double kLatticeOffset = 0.37;
// Instances whose bounding radius is under this fraction of the spacing are invisible to the probes.
constexpr double kSmallFraction = 0.5;

bool inside(const render::IrradianceProbe& probe) {
    return std::all_of(probe.freeDistance.begin(), probe.freeDistance.end(),
                       [](float d) { return d == 0.0f; });
}

} // namespace

void ProbeSettings::validate(const char* function) const {
    SP_CHECK(std::isfinite(spacing) && spacing > 0.0, InvalidArgument, function,
             ": ProbeSettings::spacing must be positive and finite, got ", spacing);
    SP_CHECK(maxProbesPerAxis >= 2 && maxProbesPerAxis <= 256, InvalidArgument, function,
             ": ProbeSettings::maxProbesPerAxis ", maxProbesPerAxis, " is out of range [2, 256]");
    SP_CHECK(rays >= 1 && rays <= 65536, InvalidArgument, function, ": ProbeSettings::rays ", rays,
             " is out of range [1, 65536]");
    SP_CHECK(maxBounces >= 0 && maxBounces <= 64, InvalidArgument, function, ": ProbeSettings::maxBounces ",
             maxBounces, " is out of range [0, 64]");
    SP_CHECK(probesPerFrame >= 1, InvalidArgument, function,
             ": ProbeSettings::probesPerFrame must be >= 1, got ", probesPerFrame);
}

int IrradianceProbes::framesToSettle() const {
    if (!volume_)
        return 0;
    const std::size_t per = std::size_t(settings_.probesPerFrame);
    return int((lit_.probes.size() + per - 1) / per);
}

void IrradianceProbes::place(const Eigen::AlignedBox3d& box, const ProbeSettings& settings) {
    // A quarter of the largest side more on each side, so that a moving thing leaving the box re-places the
    // grid rarely (of the largest side: a flat scene's box has no height to take a quarter of).
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(0.25 * box.sizes().maxCoeff());
    covered_ = Eigen::AlignedBox3d(box.min() - margin, box.max() + margin);
    const double extent = covered_.sizes().maxCoeff();
    double spacing = settings.spacing;
    while (extent / spacing + 2.0 > double(settings.maxProbesPerAxis))
        spacing *= 2.0; // a power of two times the setting: equal settings give equal lattices
    render::IrradianceVolume volume;
    volume.spacing = spacing;
    for (int axis = 0; axis < 3; ++axis) {
        const double first =
            (std::floor(covered_.min()[axis] / spacing - kLatticeOffset) + kLatticeOffset) * spacing;
        volume.origin[axis] = first;
        volume.counts[axis] =
            std::max(2, int(std::ceil((covered_.max()[axis] - first) / spacing - 1e-9)) + 1);
    }
    volume.probes.assign(std::size_t(volume.counts.prod()), render::IrradianceProbe{});
    lit_ = std::move(volume);
    litFor_.assign(lit_.probes.size(), 0);
    litAt_.assign(lit_.probes.size(), 0);
}

std::shared_ptr<const render::IrradianceVolume> IrradianceProbes::update(const render::Scene& scene,
                                                                         PathTracer& tracer,
                                                                         const ProbeSettings& settings,
                                                                         const Eigen::AlignedBox3d& around) {
    settings.validate("IrradianceProbes::update");
    ++updates_;
    litLastUpdate_ = 0;
    // The grid covers the visible instances that reach into `around` (whole: a ground the cameras move over
    // keeps one grid, rather than one that follows them and is lit again each time it moves), and only what
    // its float rays can reach: an instance further out than kMaxTraceableReach (or with a non-finite box) is
    // lit by the nearest probes but does not stretch the grid to where no ray can start.
    Eigen::AlignedBox3d box;
    scene.forEachInstance([&](render::InstanceId, const render::Instance& instance) {
        if (!instance.visible ||
            !instance.affectIndirectLighting) // what the probes do not see places no probe
            return;
        const Eigen::AlignedBox3d bounds = scene.boundingBox(instance);
        if ((around.isEmpty() || bounds.intersects(around)) && bounds.min().allFinite() &&
            bounds.max().allFinite() && bounds.min().cwiseAbs().maxCoeff() <= kMaxTraceableReach &&
            bounds.max().cwiseAbs().maxCoeff() <= kMaxTraceableReach)
            box.extend(bounds);
    });
    if (box.isEmpty()) {
        volume_.reset();
        return nullptr;
    }
    const bool placed = !volume_ || !(settings == settings_) || !covered_.contains(box);
    if (placed) {
        settings_ = settings;
        place(box, settings);
    }
    // Instances under half a spacing in radius are invisible to the probes: lit by them, but a small thing
    // moving (a ball, a robot's part) does not make every probe stale. Nor do things wholly outside the
    // grid's region (one falling away from the scene) count.
    const ProbeScope scope{kSmallFraction * lit_.spacing, covered_};
    const std::uint64_t signature = tracer.lightingSignature(scene, scope);
    // The probes to light: every one on a new grid, else those lit for another scene, longest ago first.
    std::vector<std::size_t> stale;
    for (std::size_t i = 0; i < lit_.probes.size(); ++i)
        if (placed || litFor_[i] != signature)
            stale.push_back(i);
    if (stale.empty())
        return volume_;
    if (!placed && stale.size() > std::size_t(settings.probesPerFrame)) {
        std::stable_sort(stale.begin(), stale.end(),
                         [&](std::size_t a, std::size_t b) { return litAt_[a] < litAt_[b]; });
        stale.resize(std::size_t(settings.probesPerFrame));
        std::sort(stale.begin(), stale.end());
    }
    Settings trace;
    trace.maxBounces = settings.maxBounces;
    const auto start = std::chrono::steady_clock::now();
    tracer.lightProbes(scene, lit_, stale, settings.rays, trace, scope);
    if (placed) // what the first frame (and a scene outgrowing its grid) costs, once
        SP_LOG("irradiance probes: ", lit_.counts.x(), "x", lit_.counts.y(), "x", lit_.counts.z(), " probes ",
               lit_.spacing, " m apart, lit in ",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), " s");
    for (std::size_t i : stale) {
        litFor_[i] = signature;
        litAt_[i] = updates_;
    }
    litLastUpdate_ = stale.size();

    // Probes inside geometry take the mean of their lit neighbours (the 26 around them).
    auto volume = std::make_shared<render::IrradianceVolume>(lit_);
    const Eigen::Vector3i& counts = lit_.counts;
    for (int z = 0; z < counts.z(); ++z)
        for (int y = 0; y < counts.y(); ++y)
            for (int x = 0; x < counts.x(); ++x) {
                const std::size_t at = lit_.index(x, y, z);
                if (!inside(lit_.probes[at]))
                    continue;
                render::IrradianceProbe sum;
                int n = 0;
                for (int dz = -1; dz <= 1; ++dz)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const Eigen::Vector3i c(x + dx, y + dy, z + dz);
                            if ((c.array() < 0).any() || (c.array() >= counts.array()).any())
                                continue;
                            const render::IrradianceProbe& neighbour =
                                lit_.probes[lit_.index(c.x(), c.y(), c.z())];
                            if (inside(neighbour))
                                continue;
                            sum.constant += neighbour.constant;
                            sum.linear += neighbour.linear;
                            ++n;
                        }
                if (n > 0) {
                    volume->probes[at].constant = sum.constant / float(n);
                    volume->probes[at].linear = sum.linear / float(n);
                }
            }
    volume->revision = updates_;
    volume_ = std::move(volume);
    return volume_;
}

} // namespace sp::pathtrace
