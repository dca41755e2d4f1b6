// A scene's textures: headers and the pixel budget before any decoding, one
// decoding per distinct file, the stop request inside decoding, and texels
// that must be finite, and the codes an 8-bit file's texels keep.
#include <gtest/gtest.h>

#include <bit>
#include <csignal>
#include <cstdint>
#include <limits>
#include <random>

#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/image_file.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "prism/texture.hpp"
#include "test_support.hpp"

namespace prism {
namespace {

namespace fs = std::filesystem;

template <typename Fn>
std::string error_of(Fn fn) {
  return test::message_of<InputError>(fn);
}

class TextureFiles : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_temp_dir(); }
  void TearDown() override { clear_cancel(); }

  fs::path write_rgb(const std::string& name, int w, int h) {
    ImageFile image{w, h, 3, {}, PixelFormat::UInt8, std::vector<float>(size_t(w) * h * 3, 0.5f)};
    write_image_file(dir_ / name, image, PixelFormat::UInt8);
    return dir_ / name;
  }

  std::string scene_with_textures(const std::string& textures) const {
    return R"({"prism": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]}, "textures": )" + textures + "}";
  }

  Scene load(const std::string& text) {
    Registry registry;
    return load_scene_from_string(text, dir_, registry, "scene.json");
  }

  fs::path dir_;
};

// The file is 69 bytes (8 signature + 25 IHDR + 24 IDAT + 12 IEND); zlib
// expands at most 1032:1, so it cannot hold 16384 rows of 49152 bytes: refused
// before a row is decoded (it used to decode for 20 s into 3.2 GB).
TEST_F(TextureFiles, AHeaderClaimingMoreThanTheFileHoldsIsRefusedBeforeDecoding) {
  const fs::path file = dir_ / "claims.png";
  test::write_file(file, test::png_claiming_size(16384, 16384));
  EXPECT_EQ(error_of([&] { load_texture(file, true); }),
            "cannot read image '" + file.string() +
                "': cannot decode: the file's 69 bytes cannot hold 16384x16384 pixels (truncated, or a false header)");
}

// A 4x4 file under two names (one through a symbolic link) counts 16 pixels
// of the budget, not 32, and both names get its texels.
TEST_F(TextureFiles, AFileUnderSeveralNamesCountsOnce) {
  const fs::path file = write_rgb("a.png", 4, 4);
  fs::create_symlink(file, dir_ / "alias.png");
  const std::vector<TextureRequest> requests = {
      {"a", file, true, "textures.a"}, {"b", file, true, "textures.b"}, {"c", dir_ / "alias.png", true, "textures.c"}};
  const std::vector<Texture> textures = load_textures(requests, 16);
  ASSERT_EQ(textures.size(), 3u);
  EXPECT_EQ(textures[1].name, "b");
  EXPECT_EQ(textures[2].texels, textures[0].texels);
  EXPECT_EQ(textures[2].texels.size(), 16u);
}

// Files are decoded in parallel; of two that fail, the error is the one
// the scene lists first, whichever decoding ends first (each try, so that a
// message chosen by the threads' timing would show).
TEST_F(TextureFiles, OfSeveralFailingFilesTheFirstInSceneOrderIsReported) {
  const fs::path good = write_rgb("good.png", 64, 64), first = dir_ / "first.png", second = dir_ / "second.png";
  test::write_file(first, test::png_claiming_size(4096, 4096));
  test::write_file(second, test::png_claiming_size(4096, 4096));
  const std::vector<TextureRequest> requests = {{"good", good, true, "textures.good"},
                                                {"first", first, true, "textures.first"},
                                                {"second", second, true, "textures.second"}};
  for (int attempt = 0; attempt < 20; ++attempt) {
    EXPECT_EQ(error_of([&] { load_textures(requests, limits::kMaxTexturePixels); }),
              "textures.first: cannot read image '" + first.string() +
                  "': cannot decode: the file's 69 bytes cannot hold 4096x4096 pixels (truncated, or a false header)");
  }
}

TEST_F(TextureFiles, DistinctFilesShareTheBudget) {
  const fs::path a = write_rgb("a.png", 4, 4), b = write_rgb("b.png", 4, 4);
  EXPECT_EQ(error_of([&] { load_textures({{"a", a, true, "textures.a"}, {"b", b, true, "textures.b"}}, 16); }),
            "textures.b: '" + b.string() +
                "' is 4x4 = 16 pixels, more than the 0 left of the 268435456 pixels all textures of a scene may hold");
}

// The first texture's pixel data is broken; the second is over the limit by
// its header. The budget is checked first, so the error is about the second:
// nothing was decoded.
TEST_F(TextureFiles, EveryHeaderIsCheckedBeforeAnyFileIsDecoded) {
  const std::string whole = test::read_file(write_rgb("whole.png", 64, 64));
  test::write_file(dir_ / "cut.png", whole.substr(0, whole.size() - 40));
  test::write_file(dir_ / "huge.png", test::png_claiming_size(16385, 16385));
  EXPECT_EQ(error_of([&] { load(scene_with_textures(R"({"a": "cut.png", "b": "huge.png"})")); }),
            "scene.json: textures.b: '" + (dir_ / "huge.png").string() +
                "' is 16385x16385 = 268468225 pixels, more than the 268431360 left of the 268435456 pixels all "
                "textures of a scene may hold");
}

TEST_F(TextureFiles, AStopRequestEndsDecoding) {
  const fs::path file = write_rgb("a.png", 4, 4);
  request_cancel(SIGINT);
  EXPECT_THROW(load_texture(file, true), Cancelled);
}

// NaN at (1, 0) in G; +Inf at (0, 1) in R comes later and is not the one named.
TEST_F(TextureFiles, NonFiniteTexelsAreRefusedNamingTheTextureAndThePixel) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const ImageFile image{2, 2, 3, {}, PixelFormat::Float, {0, 0, 0, 1, nan, 1, inf, 0, 0, 1, 1, 1}};
  write_image_file(dir_ / "bad.exr", image, PixelFormat::Float);
  EXPECT_EQ(error_of([&] { load(scene_with_textures(R"({"sky": {"path": "bad.exr"}})")); }),
            "scene.json: textures.sky: '" + (dir_ / "bad.exr").string() +
                "': texel (1, 0) channel G is NaN; texture values must be finite");
  const ImageFile infinite{1, 1, 3, {}, PixelFormat::Half, {0, 0, -inf}};
  write_image_file(dir_ / "inf.exr", infinite, PixelFormat::Half);
  EXPECT_EQ(error_of([&] { load(scene_with_textures(R"({"t": "inf.exr"})")); }),
            "scene.json: textures.t: '" + (dir_ / "inf.exr").string() +
                "': texel (0, 0) channel B is -Inf; texture values must be finite");
}

// An 8-bit file's texels keep their codes (Texture::codes): the byte the
// file holds per channel, a grey file's in R, G and B, 255 in A where the
// file has no alpha, and each code's value the texel's float bit for bit.
// The sampler reads them in place of the floats and gives the same bits at
// every lookup (a texture without its codes samples the floats). A 16-bit
// file keeps no codes.
TEST_F(TextureFiles, EightBitFilesKeepTheirCodesBitForBit) {
  const int w = 7, h = 5;
  auto code_at = [](int x, int y, int c) { return (x * 37 + y * 11 + c * 53) % 256; };
  auto bits = [](double v) { return std::bit_cast<uint64_t>(v); };
  for (const int channels : {1, 2, 3, 4}) {
    std::vector<float> values;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c) values.push_back(float(code_at(x, y, c)) / 255.0f);
    const fs::path file = dir_ / ("codes" + std::to_string(channels) + ".png");
    write_image_file(file, ImageFile{w, h, channels, {}, PixelFormat::UInt8, values}, PixelFormat::UInt8);
    for (const bool srgb : {true, false}) {
      SCOPED_TRACE(std::to_string(channels) + " channels, srgb " + std::to_string(srgb));
      const Texture texture = load_texture(file, srgb);
      ASSERT_EQ(texture.codes.size(), size_t(w * h));
      ASSERT_EQ(texture.code_values.size(), 512u);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const size_t i = size_t(y * w + x);
          const bool grey = channels <= 2, alpha = channels == 2 || channels == 4;
          const int expected[4] = {code_at(x, y, 0), code_at(x, y, grey ? 0 : 1), code_at(x, y, grey ? 0 : 2),
                                   alpha ? code_at(x, y, channels - 1) : 255};
          for (int c = 0; c < 4; ++c) {
            const int code = int((texture.codes[i] >> (8 * c)) & 0xffu);
            EXPECT_EQ(code, expected[c]) << "texel (" << x << ", " << y << ") channel " << c;
            EXPECT_EQ(bits(texture.code_values[size_t((c == 3 ? 256 : 0) + code)]), bits(double(texture.texels[i][c])));
          }
        }
      }
      Texture floats = texture;
      floats.codes.clear();
      floats.code_values.clear();
      std::mt19937_64 random(5);
      std::uniform_real_distribution<double> coordinate(-2.5, 2.5);
      for (int k = 0; k < 500; ++k) {
        const glm::dvec2 uv(coordinate(random), coordinate(random));
        const glm::dvec4 coded = sample_texture(texture, uv), plain = sample_texture(floats, uv);
        for (int c = 0; c < 4; ++c) ASSERT_EQ(bits(coded[c]), bits(plain[c])) << "uv (" << uv.x << ", " << uv.y << ")";
      }
    }
  }
  const fs::path wide = dir_ / "wide.png";
  write_image_file(wide, ImageFile{2, 2, 3, {}, PixelFormat::UInt16, std::vector<float>(12, 0.25f)}, PixelFormat::UInt16);
  EXPECT_TRUE(load_texture(wide, true).codes.empty());
}

}  // namespace
}  // namespace prism
