#pragma once
// Emissive meshes as lights: the scene's emissive triangles, in world space, for next-event estimation.
// sample() draws a triangle in proportion to its power (area times the luminance of its radiance), then a
// point uniformly over it; a point of any emitter is therefore drawn with density, per unit area,
// luminance(radiance) / total power (pdfArea()), which the path tracer needs again when a bounce ray finds
// an emitter by chance (multiple importance sampling). Emission is two-sided, as the surfaces are.
// Pure logic.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sp::pathtrace {

struct EmitterSample {
    Eigen::Vector3f point;    // world
    Eigen::Vector3f normal;   // unit, of the triangle (either side emits)
    Eigen::Vector3f radiance; // linear RGB
    float pdfArea = 0.0f;     // density of `point` per unit area
    std::uint32_t shape = 0;  // the instance (geometry id) the triangle belongs to
};

class Emitters {
  public:
    // Starts a new set.
    void clear();
    // Adds the triangle (a, b, c) of `shape`, world space, emitting `radiance`; one of zero area or
    // radiance is left out (it cannot be drawn, nor met).
    void add(std::uint32_t shape, const Eigen::Vector3f& a, const Eigen::Vector3f& b,
             const Eigen::Vector3f& c, const Eigen::Vector3f& radiance);
    bool empty() const { return cumulative_.empty(); }
    std::size_t size() const { return triangles_.size(); }
    // A point of an emitter from the uniform numbers u0, u1, u2 in [0, 1). Not when empty().
    EmitterSample sample(float u0, float u1, float u2) const;
    // The density per unit area with which sample() draws a point of a triangle emitting `radiance`.
    float pdfArea(const Eigen::Vector3f& radiance) const;

  private:
    struct Triangle {
        Eigen::Vector3f a, ab, ac; // a corner and the edges from it
        Eigen::Vector3f normal;
        Eigen::Vector3f radiance;
        std::uint32_t shape;
    };
    std::vector<Triangle> triangles_;
    std::vector<double> cumulative_; // of the triangles' powers, in order
};

} // namespace sp::pathtrace
