#pragma once
// Shared framebuffers for small views: the render targets of one size and set of targets hold layers of the
// same layered framebuffers (pages), so that a batch of many small worlds' cameras (Renderer::render) draws
// into one framebuffer. A software rasteriser runs the work queued between two changes of the bound
// framebuffer as one job for its threads, and waking them costs more than a 128 x 128 view's shading; larger
// views keep framebuffers of their own (suits()). Layers rather than tiles side by side: a view drawn at an
// offset rasterises at other window coordinates, which changes its depths and interpolated values in the
// last bits, while every layer is drawn as framebuffers of its own would be, bit for bit. The vertex shader
// picks the layer (ARB_shader_viewport_layer_array); without it, no view is shared. A layer is its owner's
// until released or asked for at another size, so a frame waiting to be read stays in it whatever other
// targets draw. A page grows by copying its layers into larger arrays; past kMostLayers, another page starts.
// Needs a current context.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "core/render/framebuffers.h"
#include "core/render/modality.h"

namespace sp::render {

class FramebufferAtlas {
  public:
    // `layered`: the driver offers ARB_shader_viewport_layer_array (see the header comment).
    explicit FramebufferAtlas(bool layered);
    ~FramebufferAtlas();
    FramebufferAtlas(const FramebufferAtlas&) = delete;
    FramebufferAtlas& operator=(const FramebufferAtlas&) = delete;

    // Whether views of this size share pages: those of up to kMostPixels pixels, where the driver can.
    static constexpr long kMostPixels = 512 * 512;
    static constexpr int kMostLayers = 256;
    bool suits(int width, int height) const { return layered_ && long(width) * long(height) <= kMostPixels; }

    // Where a view is drawn: its framebuffers and, when they are a page, its layer.
    struct Place {
        Framebuffers* framebuffers = nullptr; // null: none
        int layer = -1;                       // -1: framebuffers of its own, not layered
    };
    // A width x height layer of a page holding what `passes` writes, for `owner`: the one it holds when it
    // asks for the same again, else a new one (the old one freed). May grow a page, which replaces its
    // framebuffers (the layers keep their pixels): call place() again after any acquire().
    Place acquire(const void* owner, int width, int height, const PassSet& passes);
    Place place(const void* owner) const;
    void release(const void* owner);
    // The layers held in the page whose framebuffers are `page` (0 for other framebuffers).
    std::size_t heldLayers(const Framebuffers& page) const;

    // A copy of every layer of one modality of a page, read with one transfer at the first read since the
    // page was last drawn: a software rasteriser's read of a texture costs a round trip to its threads
    // (0.1 ms on two cores), which one read per view of a batch of small worlds would pay per world.
    struct Staged {
        std::vector<std::byte> bytes; // every layer, one after the other
        std::uint64_t version = 0;    // of the page when read (0: never)
    };
    // The copy of `modality` of `page` (to be refreshed when its version is not version(page)); null for
    // framebuffers that are not a page.
    Staged* staged(const Framebuffers& page, Modality modality);
    std::uint64_t version(const Framebuffers& page) const;
    // The page is drawn again (by a batch that is about to render into it): its copies are stale.
    void drawing(const Framebuffers& page);
    // Layers held and pages (tests).
    std::size_t held() const { return held_.size(); }
    std::size_t pages() const;

  private:
    struct Key {
        int width = 0, height = 0;
        TargetMask surfaceTargets = 0, attributeTargets = 0;
        bool surface = false;
        bool compactTargets = false;
        auto operator<=>(const Key&) const = default;
    };
    struct Page {
        std::unique_ptr<Framebuffers> framebuffers;
        std::vector<const void*> owners; // per layer, null where free
        std::uint64_t version = 1;       // bumped whenever it is drawn or grows
        std::map<Modality, Staged> staged;
    };
    Page* pageOf(const Framebuffers& framebuffers) const;
    struct Held {
        Key key;
        Page* page = nullptr;
        int layer = 0;
    };
    static PassSet passesOf(const Key& key);
    // Grows `page` to `layers` layers, copying the layers it has.
    void grow(const Key& key, Page& page, int layers);

    bool layered_;
    std::map<Key, std::vector<std::unique_ptr<Page>>> pages_;
    std::map<const void*, Held> held_;
};

} // namespace sp::render
