// User-named files: only regular files of bounded size are read or written, never a FIFO or a device
// that would block the engine or never end.
#include "core/base/regular_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/base/error.h"

namespace {

class RegularFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("spear_regular_file_test_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const char* name) const { return (dir_ / name).string(); }
    std::filesystem::path dir_;
};

template <typename E, typename F> std::string messageOf(F&& call) {
    try {
        call();
    } catch (const E& error) {
        return error.what();
    }
    return "(no error)";
}

TEST_F(RegularFileTest, ReadsARegularFileWhole) {
    std::ofstream(path("a.json")) << "{\"x\": 1}";
    EXPECT_EQ(sp::readRegularFile(path("a.json"), "f()", "scene file"), "{\"x\": 1}");
    EXPECT_EQ(sp::checkRegularFile(path("a.json"), "f()", "scene file"), 8u);
}

TEST_F(RegularFileTest, AMissingFileIsNotFoundNamingFunctionAndPath) {
    EXPECT_EQ(messageOf<sp::NotFound>([&] { sp::readRegularFile(path("nope.json"), "f()", "scene file"); }),
              "f(): scene file '" + path("nope.json") + "' not found");
    EXPECT_THROW(sp::readRegularFile(dir_.string(), "f()", "scene file"), sp::NotFound);
}

TEST_F(RegularFileTest, AFifoIsRefusedWithoutBlocking) {
    // No writer ever opens it: a plain open() for reading would wait for good.
    ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
    EXPECT_EQ(messageOf<sp::InvalidArgument>([&] { sp::readRegularFile(path("fifo"), "f()", "scene file"); }),
              "f(): scene file '" + path("fifo") + "' is not a regular file (a FIFO, device or socket)");
    // Writing: a FIFO with no reader would block the open too.
    EXPECT_THROW(sp::writeRegularFile(path("fifo"), "x", "f()", "scene file"), sp::InvalidArgument);
}

TEST_F(RegularFileTest, ADeviceThatNeverEndsIsRefused) {
    EXPECT_EQ(messageOf<sp::InvalidArgument>([] { sp::readRegularFile("/dev/zero", "f()", "scene file"); }),
              "f(): scene file '/dev/zero' is not a regular file (a FIFO, device or socket)");
    EXPECT_THROW(sp::writeRegularFile("/dev/null", "x", "f()", "scene file"), sp::InvalidArgument);
}

TEST_F(RegularFileTest, AFileLargerThanTheBoundIsRefused) {
    std::ofstream(path("big")) << std::string(100, 'x');
    EXPECT_EQ(
        messageOf<sp::InvalidArgument>([&] { sp::readRegularFile(path("big"), "f()", "blueprint", 99); }),
        "f(): blueprint '" + path("big") + "' holds 100 bytes, more than the 99 allowed");
}

TEST_F(RegularFileTest, WritingReplacesTheContents) {
    std::ofstream(path("out.json")) << "a much longer earlier content";
    sp::writeRegularFile(path("out.json"), "new", "f()", "scene file");
    EXPECT_EQ(sp::readRegularFile(path("out.json"), "f()", "scene file"), "new");
    EXPECT_THROW(sp::writeRegularFile(path("no/such/dir.json"), "x", "f()", "scene file"), sp::NotFound);
}

TEST_F(RegularFileTest, WritingLeavesNoTemporaryFileAndNeverHalfAFile) {
    // The contents go to a file beside the target that is renamed over it: a reader holding the old file
    // still reads it whole, and nothing else is left in the folder.
    std::ofstream(path("out.json")) << "old";
    std::ifstream reader(path("out.json"));
    sp::writeRegularFile(path("out.json"), std::string(1 << 20, 'n'), "f()", "scene file");
    std::string before;
    reader >> before;
    EXPECT_EQ(before, "old");
    EXPECT_EQ(sp::checkRegularFile(path("out.json"), "f()", "scene file"), std::size_t(1) << 20);
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_))
        ++entries;
    EXPECT_EQ(entries, 1u);
}

// Confinement is process-wide: each test sets it and this fixture lifts it again.
class ConfinedFileTest : public RegularFileTest {
  protected:
    void SetUp() override {
        RegularFileTest::SetUp();
        std::filesystem::create_directories(dir_ / "root");
        std::ofstream(path("root/in.json")) << "in";
        std::ofstream(path("out.json")) << "out";
        sp::confineUserFiles({path("root")});
        root_ = std::filesystem::canonical(dir_ / "root").string();
    }
    void TearDown() override {
        sp::confineUserFiles({});
        RegularFileTest::TearDown();
    }
    std::string outside(const std::string& given) const {
        return "f(): scene file '" + given + "' is outside the server's file roots ('" + root_ +
               "'); start spear-server with --file-root DIR to allow another folder";
    }
    std::string root_;
};

TEST_F(ConfinedFileTest, FilesInsideTheRootsAreReadAndWritten) {
    EXPECT_EQ(sp::readRegularFile(path("root/in.json"), "f()", "scene file"), "in");
    sp::writeRegularFile(path("root/new.json"), "new", "f()", "scene file");
    EXPECT_EQ(sp::readRegularFile(path("root/new.json"), "f()", "scene file"), "new");
}

TEST_F(ConfinedFileTest, PathsLeavingTheRootsAreRefusedWhetherOrNotTheFileExists) {
    std::filesystem::create_symlink(path("out.json"), path("root/link.json"));
    for (const std::string& given :
         {path("out.json"), path("missing.json"), path("root/../out.json"), path("root/link.json"),
          std::string("../out.json"), std::string("/proc/self/comm")})
        EXPECT_EQ(messageOf<sp::InvalidArgument>([&] { sp::readRegularFile(given, "f()", "scene file"); }),
                  outside(given))
            << given;
    EXPECT_EQ(messageOf<sp::InvalidArgument>(
                  [&] { sp::writeRegularFile(path("out.json"), "x", "f()", "scene file"); }),
              outside(path("out.json")));
}

TEST_F(ConfinedFileTest, EngineFilesAreNotConfined) {
    EXPECT_EQ(sp::checkRegularFile(path("out.json"), "f()", "plugin library", sp::kMaxUserFileBytes,
                                   sp::FileScope::Engine),
              3u);
}

} // namespace
