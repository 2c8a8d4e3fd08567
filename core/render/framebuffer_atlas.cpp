#include "core/render/framebuffer_atlas.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "core/base/error.h"

namespace sp::render {

FramebufferAtlas::FramebufferAtlas(bool layered) : layered_(layered) {}

FramebufferAtlas::~FramebufferAtlas() = default;

PassSet FramebufferAtlas::passesOf(const Key& key) {
    PassSet passes;
    passes.surface = key.surface;
    passes.surfaceTargets = key.surfaceTargets;
    passes.attributeTargets = key.attributeTargets;
    passes.compactTargets = key.compactTargets;
    return passes;
}

FramebufferAtlas::Place FramebufferAtlas::place(const void* owner) const {
    const auto it = held_.find(owner);
    return it == held_.end() ? Place{} : Place{it->second.page->framebuffers.get(), it->second.layer};
}

FramebufferAtlas::Page* FramebufferAtlas::pageOf(const Framebuffers& framebuffers) const {
    for (const auto& [key, list] : pages_)
        for (const auto& candidate : list)
            if (candidate->framebuffers.get() == &framebuffers)
                return candidate.get();
    return nullptr;
}

std::size_t FramebufferAtlas::heldLayers(const Framebuffers& page) const {
    const Page* found = pageOf(page);
    return found == nullptr ? 0
                            : std::size_t(std::count_if(found->owners.begin(), found->owners.end(),
                                                        [](const void* owner) { return owner != nullptr; }));
}

FramebufferAtlas::Staged* FramebufferAtlas::staged(const Framebuffers& page, Modality modality) {
    Page* found = pageOf(page);
    return found == nullptr ? nullptr : &found->staged[modality];
}

std::uint64_t FramebufferAtlas::version(const Framebuffers& page) const {
    const Page* found = pageOf(page);
    return found == nullptr ? 0 : found->version;
}

void FramebufferAtlas::drawing(const Framebuffers& page) {
    if (Page* found = pageOf(page))
        ++found->version;
}

std::size_t FramebufferAtlas::pages() const {
    std::size_t count = 0;
    for (const auto& [key, list] : pages_)
        count += list.size();
    return count;
}

FramebufferAtlas::Place FramebufferAtlas::acquire(const void* owner, int width, int height,
                                                  const PassSet& passes) {
    SP_CHECK(suits(width, height), InvalidArgument, "FramebufferAtlas::acquire(): a ", width, "x", height,
             " view does not share framebuffers");
    const Key key{
        width, height, passes.surfaceTargets, passes.attributeTargets, passes.surface, passes.compactTargets};
    if (const auto it = held_.find(owner); it != held_.end() && it->second.key == key)
        return place(owner);
    release(owner);
    std::vector<std::unique_ptr<Page>>& list = pages_[key];
    Page* page = nullptr;
    int layer = -1;
    for (const auto& candidate : list) {
        const auto free = std::find(candidate->owners.begin(), candidate->owners.end(), nullptr);
        if (free != candidate->owners.end()) {
            page = candidate.get();
            layer = int(free - candidate->owners.begin());
            break;
        }
        if (int(candidate->owners.size()) < kMostLayers) { // full, but it may grow (doubling: few copies)
            page = candidate.get();
            layer = int(candidate->owners.size());
            grow(key, *page, std::min(kMostLayers, 2 * layer));
            break;
        }
    }
    if (page == nullptr) {
        list.push_back(std::make_unique<Page>());
        page = list.back().get();
        layer = 0;
        grow(key, *page, 1);
    }
    page->owners[std::size_t(layer)] = owner;
    held_[owner] = {key, page, layer};
    return place(owner);
}

void FramebufferAtlas::release(const void* owner) {
    const auto it = held_.find(owner);
    if (it == held_.end())
        return;
    const Held held = it->second;
    held_.erase(it);
    held.page->owners[std::size_t(held.layer)] = nullptr;
    if (std::all_of(held.page->owners.begin(), held.page->owners.end(), [](const void* o) { return !o; })) {
        std::vector<std::unique_ptr<Page>>& list = pages_[held.key];
        std::erase_if(list, [&](const std::unique_ptr<Page>& page) { return page.get() == held.page; });
        if (list.empty())
            pages_.erase(held.key);
    }
}

void FramebufferAtlas::grow(const Key& key, Page& page, int layers) {
    auto bigger = std::make_unique<Framebuffers>();
    bigger->ensure(key.width, key.height, passesOf(key), layers);
    // The layers keep their pixels (a frame not read yet); depth is cleared by each render.
    const int kept = int(page.owners.size());
    for (std::size_t t = 0; t < kTargetCount && kept > 0; ++t) {
        const unsigned source = page.framebuffers->texture(static_cast<Target>(t));
        const unsigned destination = bigger->texture(static_cast<Target>(t));
        if (source != 0 && destination != 0)
            glCopyImageSubData(source, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, destination, GL_TEXTURE_2D_ARRAY, 0,
                               0, 0, 0, key.width, key.height, kept);
    }
    page.framebuffers = std::move(bigger);
    page.owners.resize(std::size_t(layers), nullptr);
    ++page.version;
}

} // namespace sp::render
