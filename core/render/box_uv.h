#pragma once
// Texture coordinates of a material with a texture size (Material::textureSize): UE's WorldAlignedTexture,
// in the object's own frame. Each point takes the plane of the axis its normal is most along (box, or
// cubic, projection) and its position on that plane in metres, so a texture repeats every textureSize
// metres on every face of every box, whatever each box's scale: a floor of 6 m and a table top of 1.4 m show
// planks of one width. Positions and normals are the object's own, scaled (position x scale, normal /
// scale), not the world's, so textures stay on a moving object. Pure logic; the rasteriser's copy is
// kMaterialChunk's boxAxes() (shaders.cpp), which must choose the same axis and signs.

#include <utility>

#include <Eigen/Core>

namespace sp::render {

// The directions u and v run along for a surface whose normal (in the object's scaled frame) is `normal`:
// u = dot(first, p) and v = dot(second, p) for a point p of that frame. Oriented as a viewer facing the
// face with the object's +Z (or, on a Z face, +X) up sees an image: u to the right, v downwards (the
// top-left uv origin). Ties go to Z, then to X.
inline std::pair<Eigen::Vector3f, Eigen::Vector3f> boxAxes(const Eigen::Vector3f& normal) {
    const Eigen::Vector3f a = normal.cwiseAbs();
    const float down = -1.0f;
    if (a.z() >= a.x() && a.z() >= a.y()) {
        const float side = normal.z() < 0.0f ? 1.0f : -1.0f;
        return {Eigen::Vector3f(0.0f, side, 0.0f), Eigen::Vector3f(down, 0.0f, 0.0f)};
    }
    if (a.x() >= a.y()) {
        const float side = normal.x() < 0.0f ? -1.0f : 1.0f;
        return {Eigen::Vector3f(0.0f, side, 0.0f), Eigen::Vector3f(0.0f, 0.0f, down)};
    }
    const float side = normal.y() < 0.0f ? 1.0f : -1.0f;
    return {Eigen::Vector3f(side, 0.0f, 0.0f), Eigen::Vector3f(0.0f, 0.0f, down)};
}

// The texture coordinates of point `position` with normal `normal` (both in the object's scaled frame), for
// a texture repeating every 1 / inverseSize metres.
inline Eigen::Vector2f boxUv(const Eigen::Vector3f& position, const Eigen::Vector3f& normal,
                             float inverseSize) {
    const auto [u, v] = boxAxes(normal);
    return Eigen::Vector2f(u.dot(position), v.dot(position)) * inverseSize;
}

} // namespace sp::render
