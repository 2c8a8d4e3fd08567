#include "core/render/content_key.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace sp::render {
namespace {

// splitmix64's finaliser: every input bit reaches every output bit.
std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Two hashes with different seeds, fed eight bytes at a time (the tail zero-padded, the length mixed in).
struct Hasher {
    std::uint64_t a = 0x243f6a8885a308d3ull, b = 0x13198a2e03707344ull;

    void add(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        std::size_t i = 0;
        for (; i + 8 <= size; i += 8) {
            std::uint64_t word;
            std::memcpy(&word, bytes + i, 8);
            step(word);
        }
        if (i < size) {
            std::uint64_t word = 0;
            std::memcpy(&word, bytes + i, size - i);
            step(word);
        }
        step(size);
    }
    template <typename T> void add(const std::vector<T>& items) {
        add(items.data(), items.size() * sizeof(T));
    }

    void step(std::uint64_t word) {
        a = mix(a ^ word) + 0x9e3779b97f4a7c15ull;
        b = mix(b + word * 0xff51afd7ed558ccdull) ^ (b >> 17);
    }
    std::string hex() const {
        char text[33];
        std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(a),
                      static_cast<unsigned long long>(b));
        return text;
    }
};

} // namespace

std::string contentKey(const MeshData& mesh) {
    Hasher hasher;
    hasher.add(mesh.positions); // Eigen's fixed-size vectors are packed floats
    hasher.add(mesh.normals);
    hasher.add(mesh.uvs);
    hasher.add(mesh.indices);
    for (const Submesh& submesh : mesh.submeshes) {
        hasher.step(submesh.firstIndex);
        hasher.step(submesh.indexCount);
    }
    return "mesh:" + hasher.hex();
}

std::string contentKey(const TextureImage& image, TextureEncoding encoding) {
    Hasher hasher;
    hasher.add(image.rgba);
    return "texture:" + std::to_string(image.width) + "x" + std::to_string(image.height) +
           (encoding == TextureEncoding::Srgb ? ":srgb:" : ":linear:") + hasher.hex();
}

} // namespace sp::render
