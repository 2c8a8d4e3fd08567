#pragma once
// SplineCurve: the geometry behind USplineComponent. Points joined by cubic Hermite segments; a point's
// tangent is its own when set, else automatic (Catmull-Rom: half the chord between its neighbours; an
// open spline's ends take the chord to their one neighbour), as UE's curve points do. Distances along
// the curve come from a per-segment arc-length table (Gauss-Legendre over sub-intervals), inverted by
// Newton steps, so a location at a distance is accurate to well below a micrometre for curves of metres.

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace sp::procedural {

class SplineCurve {
  public:
    void clear();
    void addPoint(const Eigen::Vector3d& point);
    void setPoints(std::vector<Eigen::Vector3d> points);
    void setClosedLoop(bool closed);
    // A tangent of the point's own (std::nullopt: automatic again).
    void setTangent(int index, std::optional<Eigen::Vector3d> tangent);

    int pointCount() const { return int(points_.size()); }
    // Bumped by every change to the curve: equal revisions, equal curve.
    std::uint64_t revision() const { return revision_; }
    bool closedLoop() const { return closed_; }
    const Eigen::Vector3d& point(int index) const { return points_[std::size_t(index)]; }
    Eigen::Vector3d tangent(int index) const;
    // Segments: count - 1 for an open spline, count for a closed one (the last joins the first).
    int segmentCount() const;

    // The curve at input key `key` (segment index + t, t in [0, 1]), clamped to [0, segmentCount()].
    Eigen::Vector3d location(double key) const;
    Eigen::Vector3d derivative(double key) const;
    double length() const;
    // The distance along the curve at a point, and the input key at a distance (clamped to the curve).
    double distanceAtPoint(int index) const;
    double keyAtDistance(double distance) const;

  private:
    void invalidate() {
        lengths_.clear();
        ++revision_;
    }
    void ensureLengths() const;
    double segmentLength(int segment, double t) const; // arc length from the segment's start to t

    std::vector<Eigen::Vector3d> points_;
    std::vector<std::optional<Eigen::Vector3d>> tangents_;
    bool closed_ = false;
    std::uint64_t revision_ = 0;
    mutable std::vector<double> lengths_; // cumulative: lengths_[i] = distance at the start of segment i
};

} // namespace sp::procedural
