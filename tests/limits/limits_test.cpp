// Each input limit of prism/limits.hpp is refused with the JSON path (or the
// file) and the limit named, before the work it guards is done: a scene is
// refused from its size before it is read, nesting while it is parsed, a
// texture from its header before its pixels are allocated.
#include "prism/limits.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "prism/errors.hpp"
#include "prism/image_file.hpp"
#include "prism/scene_loader.hpp"
#include "prism/texture.hpp"
#include "test_support.hpp"

namespace prism {
namespace {

namespace fs = std::filesystem;

const std::string kHead = R"({"prism": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]}, )";

// The InputError message `load` throws, or "(no error)".
std::string error_of(const std::function<void()>& load) { return test::message_of<InputError>(load); }

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

// ------------------------------------------------------------- scene size

TEST(SceneSizeLimit, TextOverTheLimitIsRefusedBeforeParsing) {
  Registry registry;
  const std::string text(limits::kMaxSceneFileBytes + 1, ' ');
  EXPECT_EQ(error_of([&] { load_scene_from_string(text, ".", registry, "big.json"); }),
            "big.json: the scene is 67108865 bytes, more than the limit of 67108864 bytes (64 MiB)");
}

// A valid scene padded with spaces to exactly the limit loads.
TEST(SceneSizeLimit, TextAtTheLimitLoads) {
  Registry registry;
  std::string text = kHead + R"("objects": []})";
  text.resize(limits::kMaxSceneFileBytes, ' ');
  EXPECT_EQ(error_of([&] { load_scene_from_string(text, ".", registry, "big.json"); }), "(no error)");
}

// A sparse file: refused from its size, so its 64 MiB of zeros are never read.
TEST(SceneSizeLimit, FileOverTheLimitIsRefusedFromItsSize) {
  Registry registry;
  const fs::path file = test::fresh_temp_dir() / "big.json";
  test::write_file(file, "");
  fs::resize_file(file, limits::kMaxSceneFileBytes + 1);
  EXPECT_EQ(error_of([&] { load_scene(file, registry); }),
            file.string() + ": the scene is 67108865 bytes, more than the limit of 67108864 bytes (64 MiB)");
}

// A device has no size to check up front: reading stops one byte past the limit.
TEST(SceneSizeLimit, EndlessStreamIsCutOffAtTheLimit) {
  Registry registry;
  EXPECT_EQ(error_of([&] { load_scene("/dev/zero", registry); }),
            "/dev/zero: the scene is at least 67108865 bytes, more than the limit of 67108864 bytes (64 MiB)");
}

// ---------------------------------------------------------- JSON nesting

std::string repeated(const std::string& part, int times) {
  std::string out;
  for (int i = 0; i < times; ++i) out += part;
  return out;
}

// 100,000 levels would overflow the stack of any recursive walk; the parser
// stops at level 65 and names where.
TEST(JsonDepthLimit, HundredThousandNestedArraysAreRefusedAtTheLimit) {
  Registry registry;
  const std::string text = kHead + R"("objects": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
  EXPECT_EQ(error_of([&] { load_scene_from_string(text, ".", registry, "deep.json"); }),
            "deep.json: objects" + repeated("[0]", 63) +
                ": arrays and objects nested more than 64 levels deep (the limit)");
}

TEST(JsonDepthLimit, HundredThousandNestedObjectsAreRefusedAtTheLimit) {
  Registry registry;
  const std::string text = kHead + R"("x": )" + repeated(R"({"x": )", 100000) + "0" + std::string(100000, '}') + "}";
  EXPECT_EQ(error_of([&] { load_scene_from_string(text, ".", registry, "deep.json"); }),
            "deep.json: x" + repeated(".x", 63) + ": arrays and objects nested more than 64 levels deep (the limit)");
}

// The root object and 63 arrays are 64 levels: parsed, then refused for what they hold.
TEST(JsonDepthLimit, SixtyFourLevelsParse) {
  Registry registry;
  const std::string text = kHead + R"("objects": )" + std::string(63, '[') + std::string(63, ']') + "}";
  EXPECT_EQ(error_of([&] { load_scene_from_string(text, ".", registry, "deep.json"); }),
            "deep.json: objects[0]: must be an object, got an array of 1");
}

// -------------------------------------------------------------- textures

class TextureLimits : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_temp_dir(); }
  fs::path dir_;

  // A w x h RGB PNG of noise (which compresses poorly, so half the file is half the rows).
  fs::path write_png(const std::string& name, int w, int h) {
    ImageFile image{w, h, 3, {}, PixelFormat::UInt8, std::vector<float>(size_t(w) * h * 3)};
    uint32_t state = 12345;
    for (float& v : image.pixels) {
      state = state * 1664525u + 1013904223u;
      v = float(state >> 24) / 255.0f;
    }
    const fs::path file = dir_ / name;
    write_image_file(file, image, PixelFormat::UInt8);
    return file;
  }
};

TEST_F(TextureLimits, HugeHeaderIsRefusedBeforeAnyPixelIsAllocated) {
  const fs::path file = dir_ / "huge.png";
  test::write_file(file, test::png_claiming_size(100000, 100000));
  EXPECT_EQ(error_of([&] { load_texture(file, true); }),
            "'" + file.string() +
                "' is 100000x100000 = 10000000000 pixels, more than the limit of 268435456 pixels all textures of a "
                "scene may hold");
}

// 16384 x 16384 is exactly the limit.
TEST_F(TextureLimits, OneSideOverTheLargestSquareIsRefused) {
  const fs::path file = dir_ / "square.png";
  test::write_file(file, test::png_claiming_size(16385, 16385));
  EXPECT_EQ(error_of([&] { load_texture(file, true); }),
            "'" + file.string() +
                "' is 16385x16385 = 268468225 pixels, more than the limit of 268435456 pixels all textures of a "
                "scene may hold");
}

// What the textures before it left of the scene's budget.
TEST_F(TextureLimits, TheScenesBudgetIsShared) {
  const fs::path file = write_png("small.png", 4, 4);
  EXPECT_EQ(load_texture(file, true, 16).width, 4);
  EXPECT_EQ(error_of([&] { load_texture(file, true, 15); }),
            "'" + file.string() +
                "' is 4x4 = 16 pixels, more than the 15 left of the 268435456 pixels all textures of a scene may hold");
}

TEST_F(TextureLimits, TruncatedFileIsRefused) {
  const fs::path whole = write_png("whole.png", 64, 64);
  const std::string bytes = test::read_file(whole);
  const fs::path cut = dir_ / "cut.png";
  test::write_file(cut, bytes.substr(0, bytes.size() / 2));
  EXPECT_TRUE(starts_with(error_of([&] { load_texture(cut, true); }), "cannot read image '" + cut.string() + "': cannot decode: "));
}

TEST_F(TextureLimits, TextFileNamedPngIsRefused) {
  const fs::path file = dir_ / "text.png";
  test::write_file(file, "this is text, not a PNG\n");
  EXPECT_TRUE(starts_with(error_of([&] { load_texture(file, true); }), "cannot read image '" + file.string() + "': "));
}

TEST_F(TextureLimits, MissingFileIsRefused) {
  const fs::path file = dir_ / "missing.png";
  EXPECT_TRUE(starts_with(error_of([&] { load_texture(file, true); }), "cannot read image '" + file.string() + "': "));
}

// Memory is bounded by pixels times 4 channels however many a file holds.
TEST_F(TextureLimits, ChannelsPastRgbaAreNotRead) {
  ImageFile image{2, 1, 6, {"R", "G", "B", "A", "Z", "W"}, PixelFormat::Float, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}};
  const fs::path file = dir_ / "six.exr";
  write_image_file(file, image, PixelFormat::Float);
  const ImageFile read = read_image_file(file, limits::kMaxTexturePixels, 4);
  EXPECT_EQ(read.channels, 4);
  EXPECT_EQ(read.channel_names, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(read.pixels, (std::vector<float>{1, 2, 3, 4, 7, 8, 9, 10}));
  const Texture texture = load_texture(file, true);
  EXPECT_EQ(texture.texels[1], glm::vec4(7, 8, 9, 10));
}

// Through the loader the message leads with the texture's JSON path.
TEST_F(TextureLimits, TheLoaderNamesTheTexturesPath) {
  test::write_file(dir_ / "huge.png", test::png_claiming_size(100000, 100000));
  Registry registry;
  const std::string text = kHead + R"("textures": {"sky": {"path": "huge.png"}}})";
  EXPECT_EQ(error_of([&] { load_scene_from_string(text, dir_, registry, "scene.json"); }),
            "scene.json: textures.sky: '" + (dir_ / "huge.png").string() +
                "' is 100000x100000 = 10000000000 pixels, more than the limit of 268435456 pixels all textures of a "
                "scene may hold");
}

}  // namespace
}  // namespace prism
