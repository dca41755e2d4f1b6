// How outputs replace older files: permissions and symbolic links kept, a
// full disk failing the write with the older file intact, and messages that
// name the file the caller asked for.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "test_support.hpp"

namespace prism {
namespace {

namespace fs = std::filesystem;

Image grey_image(int width, int height, float value) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.assign(size_t(width) * height * 3, value);
  return image;
}

template <typename Fn>
std::string runtime_error_of(Fn fn) {
  return test::message_of<RuntimeError>(fn);
}

class OutputFiles : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_temp_dir(); }
  fs::path dir_;
};

TEST_F(OutputFiles, AReplacedFileKeepsItsPermissions) {
  const fs::path file = dir_ / "out.png";
  write_image(grey_image(2, 2, 0.5f), file);
  ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
  write_image(grey_image(2, 2, 0.25f), file);
  struct stat info {};
  ASSERT_EQ(::stat(file.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0640u);
  write_text_file_atomically(dir_ / "t.csv", "a\n");
  ASSERT_EQ(::chmod((dir_ / "t.csv").c_str(), 0600), 0);
  write_text_file_atomically(dir_ / "t.csv", "b\n");
  ASSERT_EQ(::stat((dir_ / "t.csv").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0600u);
}

// As cp does: the link stays, its target (in another folder) gets the new bytes.
TEST_F(OutputFiles, ASymbolicLinkIsWrittenThrough) {
  fs::create_directory(dir_ / "store");
  test::write_file(dir_ / "store" / "stats.json", "old\n");
  fs::create_symlink("store/stats.json", dir_ / "stats.json");
  write_text_file_atomically(dir_ / "stats.json", "new\n");
  EXPECT_TRUE(fs::is_symlink(dir_ / "stats.json"));
  EXPECT_EQ(test::read_file(dir_ / "store" / "stats.json"), "new\n");
  EXPECT_EQ(fs::directory_iterator(dir_ / "store")->path().filename(), "stats.json");  // no temporary left
}

// A link to something that is not a regular file (a FIFO here; /dev/zero in
// a program cache) is replaced itself: the write never renames a file over
// a device or a FIFO.
TEST_F(OutputFiles, ALinkToANonRegularFileIsReplacedNotFollowed) {
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  fs::create_symlink(fifo, dir_ / "entry");
  write_text_file_atomically(dir_ / "entry", "new\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_FALSE(fs::is_symlink(dir_ / "entry"));
  EXPECT_EQ(test::read_file(dir_ / "entry"), "new\n");
}

TEST_F(OutputFiles, AParentThatIsAFileIsSaidToBeNoFolder) {
  test::write_file(dir_ / "plain", "x");
  const fs::path file = dir_ / "plain" / "out.png";
  EXPECT_EQ(runtime_error_of([&] { check_output_path(file, {".png"}); }),
            file.string() + ": " + (dir_ / "plain").string() + " is not a folder");
  const fs::path deeper = dir_ / "plain" / "sub" / "out.png";
  EXPECT_EQ(runtime_error_of([&] { check_output_path(deeper, {".png"}); }),
            deeper.string() + ": " + (dir_ / "plain").string() + " is not a folder");
  const fs::path missing = dir_ / "missing" / "out.png";
  EXPECT_EQ(runtime_error_of([&] { check_output_path(missing, {".png"}); }),
            missing.string() + ": folder " + (dir_ / "missing").string() + " does not exist");
}

// A 64 KiB tmpfs, filled up between the first write and the second.
class FullDisk : public OutputFiles {
 protected:
  void SetUp() override {
    OutputFiles::SetUp();
    if (const std::string why = disk.mount(dir_ / "disk"); !why.empty()) GTEST_SKIP() << why;
    disk_ = disk.folder();
  }
  void fill() { ASSERT_TRUE(disk.fill()); }
  std::vector<std::string> outputs() const { return disk.files(); }
  prism::test::SmallDisk disk;
  fs::path disk_;
};

TEST_F(FullDisk, AnImageIsNotReplacedAndTheErrorNamesIt) {
  for (const char* name : {"out.png", "out.exr"}) {
    SCOPED_TRACE(name);
    const fs::path file = disk_ / name;
    write_image(grey_image(8, 8, 0.5f), file);
    const std::string before = test::read_file(file);
    fill();
    // Noise: neither format compresses it below the space left (none).
    Image noise = grey_image(32, 32, 0);
    for (size_t i = 0; i < noise.rgb.size(); ++i) noise.rgb[i] = float((i * 7919) % 251) / 251.0f;
    EXPECT_EQ(runtime_error_of([&] { write_image(noise, file); }), "cannot write " + file.string() + ": No space left on device");
    EXPECT_EQ(test::read_file(file), before);
    EXPECT_EQ(outputs(), std::vector<std::string>{name});
    fs::remove(disk_ / "filler");
    fs::remove(file);
  }
}

TEST_F(FullDisk, ATextFileIsNotReplaced) {
  const fs::path file = disk_ / "hits.csv";
  write_text_file_atomically(file, "old\n");
  fill();
  EXPECT_EQ(runtime_error_of([&] { write_text_file_atomically(file, std::string(8192, 'y')); }),
            "cannot write " + file.string() + ": No space left on device");
  EXPECT_EQ(test::read_file(file), "old\n");
  EXPECT_EQ(outputs(), std::vector<std::string>{"hits.csv"});
}

}  // namespace
}  // namespace prism
