// Content keys: the same bytes give the same key, any change gives another (core/render/content_key.h).

#include <gtest/gtest.h>

#include "core/render/content_key.h"
#include "core/render/primitives.h"

namespace sp::render::test {
namespace {

TEST(ContentKey, EqualMeshesShareAKeyAndAnyChangeMakesAnother) {
    const MeshData box = primitives::box({1.0f, 2.0f, 3.0f});
    EXPECT_EQ(contentKey(box), contentKey(primitives::box({1.0f, 2.0f, 3.0f})));
    EXPECT_EQ(contentKey(box).rfind("mesh:", 0), 0u);
    EXPECT_EQ(contentKey(box).size(), 5u + 32u);

    MeshData moved = box;
    moved.positions[3].x() += 1e-6f;
    EXPECT_NE(contentKey(moved), contentKey(box));
    MeshData uv = box;
    uv.uvs[0].y() = 0.5f;
    EXPECT_NE(contentKey(uv), contentKey(box));
    MeshData split = box; // the same triangles in two submeshes
    split.submeshes = {{0, 6}, {6, std::uint32_t(box.indices.size()) - 6}};
    EXPECT_NE(contentKey(split), contentKey(box));
    MeshData renamed = box; // the name is not content
    renamed.name = "another";
    EXPECT_EQ(contentKey(renamed), contentKey(box));
}

TEST(ContentKey, TexturesDifferByAnyPixelByShapeAndByEncoding) {
    TextureImage image;
    image.width = 4;
    image.height = 2;
    image.rgba.assign(4 * 2 * 4, 128);
    TextureImage same = image;
    same.source = "elsewhere.png"; // where it came from is not content
    EXPECT_EQ(contentKey(image, TextureEncoding::Srgb), contentKey(same, TextureEncoding::Srgb));
    TextureImage pixel = image;
    pixel.rgba[17] = 129;
    EXPECT_NE(contentKey(pixel, TextureEncoding::Srgb), contentKey(image, TextureEncoding::Srgb));
    TextureImage transposed = image; // the same bytes, another shape
    transposed.width = 2;
    transposed.height = 4;
    EXPECT_NE(contentKey(transposed, TextureEncoding::Srgb), contentKey(image, TextureEncoding::Srgb));
    EXPECT_NE(contentKey(image, TextureEncoding::Linear), contentKey(image, TextureEncoding::Srgb))
        << "read as data, not colour: another upload";
}

} // namespace
} // namespace sp::render::test
