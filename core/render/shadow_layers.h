#pragma once
// The storage of the shadow maps of every scene one Renderer draws: texture arrays shared by the scenes, one
// per resolution and format, in which each scene holds a run of layers (one per map). A software rasteriser
// hands the work queued between two changes of the bound framebuffer to its threads as one job, so maps in
// framebuffers of their own cost a job each; in one layered framebuffer, the depth program choosing the layer
// (gl_Layer from the vertex shader, ARB_shader_viewport_layer_array), the maps of a whole batch of worlds
// are one job. Without that extension each map's layer is attached in turn, as separate framebuffers would
// be. Needs a current context.
//
// Each layer has a depth layer of its own, so that drawing one map never disturbs another's depth test. An
// array grows by copying its maps into a larger one, so the maps of other scenes survive a scene's arrival.

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace sp::render {

class ShadowLayers {
  public:
    // `layered`: the driver offers ARB_shader_viewport_layer_array (see the header comment).
    explicit ShadowLayers(bool layered) : layered_(layered) {}
    ~ShadowLayers();
    ShadowLayers(const ShadowLayers&) = delete;
    ShadowLayers& operator=(const ShadowLayers&) = delete;

    // Where an owner's maps are: its first layer in an array's texture (of `format`, GL_R16 or GL_R32F).
    struct Place {
        unsigned texture = 0;
        unsigned format = 0;
        int resolution = 0;
        int first = -1; // -1: none
        int count = 0;
        int arrayLayers = 0; // of the whole array
    };
    // `count` consecutive layers of the array of `resolution` x `format` maps for `owner` (a Scene::uid()),
    // which gives up what it held before (those maps are not kept). Returns where they are; keeps them when
    // the owner already holds exactly that. Arrays grow as needed, keeping the other owners' maps.
    Place acquire(std::uint64_t owner, int resolution, unsigned format, int count);
    // The owner's current place (first -1: none); valid until the next acquire() or release() of any owner.
    Place place(std::uint64_t owner) const;
    void release(std::uint64_t owner);
    // Binds the framebuffer of the owner's array for drawing into its map number `map` (0-based): the array's
    // layered framebuffer, the depth program writing the layer it is told (layered()), or the layer attached.
    void bind(std::uint64_t owner, int map);
    bool layered() const { return layered_; }
    // Layers allocated in all arrays (tests).
    int capacity() const;

  private:
    struct Array {
        unsigned texture = 0, depth = 0, fbo = 0;
        std::vector<std::uint64_t> owners; // per layer: its owner, 0 where free
    };
    using Key = std::pair<int, unsigned>; // resolution, format
    struct Held {
        Key key;
        int first = 0, count = 0;
    };
    // Grows `array` to at least `layers` layers, copying its maps over.
    void grow(Array& array, const Key& key, int layers);
    void deleteObjects(Array& array);

    bool layered_;
    std::map<Key, Array> arrays_;
    std::map<std::uint64_t, Held> held_; // by owner
};

} // namespace sp::render
