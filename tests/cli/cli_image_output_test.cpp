// `prism render` to PNG or EXR without OpenImageIO, and outputs on a full
// disk: the run fails with exit status 1, names the output, and leaves the
// older files (image, --stats, trace CSV) byte for byte as they were.
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "test_support.hpp"
#include "prism/image_file.hpp"

namespace prism::cli_test {
namespace {

using nlohmann::json;

class ImageOutput : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  RunResult render(const fs::path& out, std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"render", scene_, "-b", "reference", "-o", out.string()};
    args.insert(args.end(), more.begin(), more.end());
    return run(args);
  }
  std::string scene_;
};

TEST_F(ImageOutput, RenderingToPngOrExrDoesNotLoadOpenImageIO) {
  ASSERT_TRUE(ExitedWith(render(path("out.png"), {"--stats", path("png.json").string()}), 0));
  EXPECT_EQ(json::parse(read_file(path("png.json")))["loaded_libraries"]["openimageio"], false);
  ASSERT_TRUE(ExitedWith(render(path("out.exr"), {"--aov", "id,path", "--stats", path("exr.json").string()}), 0));
  EXPECT_EQ(json::parse(read_file(path("exr.json")))["loaded_libraries"]["openimageio"], false);
}

// The same record says yes once a texture needs OpenImageIO (a BMP file).
TEST_F(ImageOutput, ATextureOnlyOpenImageIOReadsLoadsIt) {
  write_image_file(path("tex.bmp"), ImageFile{2, 2, 3, {}, PixelFormat::UInt8, std::vector<float>(12, 0.5f)},
                   PixelFormat::UInt8);
  SceneText text;
  text.extra = R"("textures": {"t": "tex.bmp"}, "materials": {"m": {"texture": "t"}})";
  text.objects = R"([{"type": "sphere", "radius": 1, "material": "m"}])";
  scene_ = write("textured.json", text.text()).string();
  ASSERT_TRUE(ExitedWith(render(path("out.png"), {"--stats", path("s.json").string()}), 0));
  EXPECT_EQ(json::parse(read_file(path("s.json")))["loaded_libraries"]["openimageio"], true);
}

// libpng prints its warnings and errors on stderr unless a handler takes
// them: a texture with a damaged ancillary chunk (a warning, the chunk is
// dropped) renders with nothing on stderr (-q: not even Prism's summary
// line), and a cut one fails with Prism's one-line message only.
TEST_F(ImageOutput, LibpngPrintsNothingOfItsOwn) {
  write_image_file(path("tex.png"), ImageFile{2, 2, 3, {}, PixelFormat::UInt8, std::vector<float>(12, 0.5f)},
                   PixelFormat::UInt8);
  const std::string png = read_file(path("tex.png"));
  // After the signature (8 bytes) and IHDR (25): a tEXt chunk whose CRC is wrong.
  const std::string text_chunk = std::string("\0\0\0\x05tEXtab\0cd", 13) + "\xde\xad\xbe\xef";
  write_file(path("damaged.png"), png.substr(0, 33) + text_chunk + png.substr(33));
  write_file(path("cut.png"), png.substr(0, png.size() - 20));
  for (const char* texture : {"damaged.png", "cut.png"}) {
    SCOPED_TRACE(texture);
    SceneText text;
    text.extra = std::string(R"("textures": {"t": ")") + texture + R"("}, "materials": {"m": {"texture": "t"}})";
    text.objects = R"([{"type": "sphere", "radius": 1, "material": "m"}])";
    scene_ = write("textured.json", text.text()).string();
    const RunResult r = render(path("out.png"), {"-q"});
    if (std::string(texture) == "damaged.png") {
      EXPECT_TRUE(ExitedWith(r, 0));
      EXPECT_EQ(r.err, "");
    } else {
      EXPECT_TRUE(ExitedWith(r, 2));
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(StderrHas(r, {"textures.t: cannot read image '" + path("cut.png").string() + "': cannot decode: "}));
      EXPECT_EQ(r.err.find("libpng"), std::string::npos) << r.err;
    }
  }
}

// A 64 KiB tmpfs in the test's folder, filled up on request.
class FullDiskOutput : public ImageOutput {
 protected:
  void SetUp() override {
    ImageOutput::SetUp();
    if (const std::string why = disk.mount(path("disk")); !why.empty()) GTEST_SKIP() << why;
    disk_ = disk.folder();
  }
  void TearDown() override {
    disk.unmount();
    ImageOutput::TearDown();
  }
  void fill() { ASSERT_TRUE(disk.fill()); }
  void expect_kept(const std::string& name, const std::string& message);
  std::vector<std::string> leftovers() const { return disk.files(); }
  prism::test::SmallDisk disk;
  fs::path disk_;
};

// `name` is written on a disk with room, then again on the full disk: exit
// status 1 with `message` on stderr, and the older file stays, alone.
void FullDiskOutput::expect_kept(const std::string& name, const std::string& message) {
  SCOPED_TRACE(name);
  const fs::path out = disk_ / name;
  ASSERT_TRUE(ExitedWith(render(out, {"--width", "16", "--height", "12"}), 0));
  const std::string before = read_file(out);
  fill();
  const RunResult r = render(out, {"--width", "32", "--height", "24"});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {message}));
  EXPECT_EQ(read_file(out), before);
  EXPECT_EQ(leftovers(), std::vector<std::string>{name});
  fs::remove(disk_ / "filler");
  fs::remove(out);
}

TEST_F(FullDiskOutput, AnImageIsNotReplaced) {
  for (const char* name : {"out.png", "out.exr"})
    expect_kept(name, "cannot write " + (disk_ / name).string() + ": No space left on device");
}

// The other formats (OpenImageIO's TIFF, our JPEG and HDR writers) are
// staged the same way: exit status 1 naming the file, and the older one stays.
TEST_F(FullDiskOutput, AnImageOpenImageIOWritesIsNotReplaced) {
  for (const char* name : {"out.tif", "out.jpg", "out.hdr"})
    expect_kept(name, "prism: error: cannot write " + (disk_ / name).string() + ": ");
}

// The image and the statistics are both written before either replaces its
// older file: the statistics failing leaves the older image too.
TEST_F(FullDiskOutput, FailedStatisticsLeaveTheImageAsItWas) {
  const fs::path image = path("out.png"), stats = disk_ / "stats.json";
  ASSERT_TRUE(ExitedWith(render(image, {"--width", "16", "--height", "12", "--stats", stats.string()}), 0));
  const std::string image_before = read_file(image), stats_before = read_file(stats);
  fill();
  const RunResult r = render(image, {"--width", "32", "--height", "24", "--stats", stats.string()});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"cannot write " + stats.string() + ": No space left on device"}));
  EXPECT_EQ(read_file(image), image_before);
  EXPECT_EQ(read_file(stats), stats_before);
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"disk", "out.png", "scene.json"}));
}

TEST_F(FullDiskOutput, TraceOutputIsNotReplaced) {
  std::string rays;
  for (int i = 0; i < 400; ++i) rays += "0,0,-5,0,0,1\n";
  write("rays.csv", rays);
  const fs::path out = disk_ / "hits.csv";
  write_file(out, "old\n");
  fill();
  const RunResult r = run({"trace", scene_, "-b", "reference", "--rays", path("rays.csv").string(), "-o", out.string()});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"cannot write " + out.string() + ": No space left on device"}));
  EXPECT_EQ(read_file(out), "old\n");
  EXPECT_EQ(leftovers(), std::vector<std::string>{"hits.csv"});
}

}  // namespace
}  // namespace prism::cli_test
