#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/base/asset_path.h"

namespace fs = std::filesystem;

namespace {
// A scratch folder with a built-in folder (builtin/assets/scenes/room.json), a user library
// (library/rooms/mine.json) and an empty working directory; the process works in the latter.
class AssetPathTest : public ::testing::Test {
  protected:
    void SetUp() override {
        root_ = fs::temp_directory_path() / ("spear-asset-path-" + std::to_string(::getpid()));
        fs::create_directories(root_ / "builtin/assets/scenes");
        fs::create_directories(root_ / "library/rooms");
        fs::create_directories(root_ / "work");
        std::ofstream(root_ / "builtin/assets/scenes/room.json") << "{}";
        std::ofstream(root_ / "library/rooms/mine.json") << "{}";
        previous_ = fs::current_path();
        fs::current_path(root_ / "work");
        sp::setBuiltinAssetFolder((root_ / "builtin").string());
        ::unsetenv("SPEAR_ASSET_PATH");
    }
    void TearDown() override {
        fs::current_path(previous_);
        sp::setBuiltinAssetFolder("");
        ::unsetenv("SPEAR_ASSET_PATH");
        fs::remove_all(root_);
    }
    fs::path root_, previous_;
};
} // namespace

TEST_F(AssetPathTest, RelativeNamesFallBackToTheBuiltInFolder) {
    EXPECT_EQ(sp::findAsset("assets/scenes/room.json"), (root_ / "builtin/assets/scenes/room.json").string());
    EXPECT_EQ(sp::findAsset("/Game/scenes/room"), (root_ / "builtin/assets/scenes/room.json").string());
    EXPECT_EQ(sp::findAsset("/Game/scenes/room.json"), (root_ / "builtin/assets/scenes/room.json").string());
    // Not found anywhere: the name as written, for the reader's "no such file".
    EXPECT_EQ(sp::findAsset("assets/scenes/none.json"), "assets/scenes/none.json");
    EXPECT_EQ(sp::findAsset("/abs/none.json"), "/abs/none.json");
}

TEST_F(AssetPathTest, TheWorkingDirectoryComesFirstThenSpearAssetPath) {
    ::setenv("SPEAR_ASSET_PATH", ("/nonexistent::" + (root_ / "library").string()).c_str(), 1);
    EXPECT_EQ(sp::findAsset("rooms/mine.json"), (root_ / "library/rooms/mine.json").string());
    const std::vector<std::string> expected{"/nonexistent", (root_ / "library").string(),
                                            (root_ / "builtin").string()};
    EXPECT_EQ(sp::assetSearchPath(), expected);
    fs::create_directories("assets/scenes");
    std::ofstream("assets/scenes/room.json") << "{}";
    EXPECT_EQ(sp::findAsset("assets/scenes/room.json"), "assets/scenes/room.json");
}
