#include "core/render/shadow_layers.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "core/base/error.h"

namespace sp::render {

ShadowLayers::~ShadowLayers() {
    for (auto& [key, array] : arrays_)
        deleteObjects(array);
}

void ShadowLayers::deleteObjects(Array& array) {
    glDeleteFramebuffers(1, &array.fbo);
    glDeleteTextures(1, &array.depth);
    glDeleteTextures(1, &array.texture);
    array = {};
}

ShadowLayers::Place ShadowLayers::place(std::uint64_t owner) const {
    const auto it = held_.find(owner);
    if (it == held_.end())
        return {};
    const Held& held = it->second;
    const Array& array = arrays_.at(held.key);
    return {array.texture, held.key.second, held.key.first, held.first, held.count, int(array.owners.size())};
}

ShadowLayers::Place ShadowLayers::acquire(std::uint64_t owner, int resolution, unsigned format, int count) {
    SP_CHECK(count > 0 && resolution > 0, InvalidArgument, "ShadowLayers::acquire(): ", count, " maps of ",
             resolution, " texels");
    const Key key{resolution, format};
    if (const auto it = held_.find(owner);
        it != held_.end() && it->second.key == key && it->second.count == count)
        return place(owner);
    release(owner);
    Array& array = arrays_[key];
    // The first run of `count` free layers; else the array grows (at least doubling, so that a batch of
    // worlds arriving one by one copies the maps a few times, not once per world) past its trailing free run.
    const int size = int(array.owners.size());
    int first = -1;
    for (int i = 0, run = 0; i < size && first < 0; ++i) {
        run = array.owners[std::size_t(i)] == 0 ? run + 1 : 0;
        if (run == count)
            first = i - count + 1;
    }
    if (first < 0) {
        int trailing = 0;
        while (trailing < size && array.owners[std::size_t(size - 1 - trailing)] == 0)
            ++trailing;
        first = size - trailing;
        grow(array, key, std::max(first + count, size > 0 ? 2 * size : count));
    }
    std::fill_n(array.owners.begin() + first, count, owner);
    held_[owner] = {key, first, count};
    return place(owner);
}

void ShadowLayers::release(std::uint64_t owner) {
    const auto it = held_.find(owner);
    if (it == held_.end())
        return;
    const Key key = it->second.key;
    held_.erase(it);
    Array& array = arrays_.at(key);
    std::replace(array.owners.begin(), array.owners.end(), owner, std::uint64_t(0));
    if (std::all_of(array.owners.begin(), array.owners.end(), [](std::uint64_t o) { return o == 0; })) {
        deleteObjects(array);
        arrays_.erase(key);
    }
}

void ShadowLayers::grow(Array& array, const Key& key, int layers) {
    const auto [resolution, format] = key;
    Array bigger;
    // Read texel by texel with imageLoad and compared in the shader (see shadowFactor() in shaders.cpp).
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &bigger.texture);
    glTextureStorage3D(bigger.texture, 1, format, resolution, resolution, layers);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &bigger.depth);
    glTextureStorage3D(bigger.depth, 1, format == GL_R16 ? GL_DEPTH_COMPONENT16 : GL_DEPTH_COMPONENT32F,
                       resolution, resolution, layers);
    glCreateFramebuffers(1, &bigger.fbo);
    glNamedFramebufferDrawBuffer(bigger.fbo, GL_COLOR_ATTACHMENT0);
    if (layered_) {
        glNamedFramebufferTexture(bigger.fbo, GL_COLOR_ATTACHMENT0, bigger.texture, 0);
        glNamedFramebufferTexture(bigger.fbo, GL_DEPTH_ATTACHMENT, bigger.depth, 0);
        const GLenum status = glCheckNamedFramebufferStatus(bigger.fbo, GL_FRAMEBUFFER);
        SP_CHECK(status == GL_FRAMEBUFFER_COMPLETE, InvalidState,
                 "ShadowLayers: the layered shadow-map framebuffer is incomplete (status 0x", std::hex,
                 status, ")");
    }
    // The maps already drawn move over (the depth layers need not: a map's update clears the depth it draws
    // against).
    const int kept = int(array.owners.size());
    if (kept > 0)
        glCopyImageSubData(array.texture, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, bigger.texture,
                           GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, resolution, resolution, kept);
    bigger.owners = std::move(array.owners);
    bigger.owners.resize(std::size_t(layers), 0);
    deleteObjects(array);
    array = std::move(bigger);
}

void ShadowLayers::bind(std::uint64_t owner, int map) {
    const Held& held = held_.at(owner);
    SP_CHECK(map >= 0 && map < held.count, InvalidArgument, "ShadowLayers::bind(): map ", map, " of ",
             held.count);
    const Array& array = arrays_.at(held.key);
    glBindFramebuffer(GL_FRAMEBUFFER, array.fbo);
    if (!layered_) {
        glNamedFramebufferTextureLayer(array.fbo, GL_COLOR_ATTACHMENT0, array.texture, 0, held.first + map);
        glNamedFramebufferTextureLayer(array.fbo, GL_DEPTH_ATTACHMENT, array.depth, 0, held.first + map);
    }
}

int ShadowLayers::capacity() const {
    int layers = 0;
    for (const auto& [key, array] : arrays_)
        layers += int(array.owners.size());
    return layers;
}

} // namespace sp::render
