// Prism's PNG, JPEG and EXR readers and writers (and its Radiance HDR writer) give what OpenImageIO gives:
// files Prism writes read back through OpenImageIO with the expected pixels,
// names and types, and files of every PNG layout (and JPEG, EXR) read by
// Prism equal OpenImageIO's reading of them, value for value.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <png.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>

#include "prism/image_file.hpp"
#include "prism/image_io.hpp"
#include "prism/texture.hpp"
#include "test_support.hpp"

namespace prism {
namespace {

namespace fs = std::filesystem;

struct OiioImage {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> names;
  OIIO::TypeDesc format;
  std::vector<OIIO::TypeDesc> channel_formats;
  std::vector<float> pixels;
};

OiioImage read_with_oiio(const fs::path& file) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(file.string(), &config);
  if (!input) throw std::runtime_error("OpenImageIO cannot open " + file.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  OiioImage image{spec.width, spec.height, spec.nchannels, spec.channelnames, spec.format, spec.channelformats, {}};
  image.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw std::runtime_error("OpenImageIO cannot decode " + file.string());
  return image;
}

void write_with_oiio(const fs::path& file, int width, int height, const std::vector<std::string>& names,
                     OIIO::TypeDesc type, const std::vector<float>& pixels) {
  auto output = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(output);
  OIIO::ImageSpec spec(width, height, int(names.size()), type);
  spec.channelnames = names;
  ASSERT_TRUE(output->open(file.string(), spec));
  ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  ASSERT_TRUE(output->close());
}

// A PNG of any layout straight through libpng: `rows` holds the raw bytes
// of each row as PNG stores them (big-endian 16-bit samples, packed palette indices).
void write_png_raw(const fs::path& file, int width, int height, int bit_depth, int color_type,
                   const std::vector<std::vector<png_byte>>& rows, const std::vector<png_color>& palette = {},
                   const std::vector<png_byte>& transparency = {}, bool interlaced = false) {
  FILE* out = std::fopen(file.c_str(), "wb");
  ASSERT_NE(out, nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, out);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), bit_depth, color_type,
               interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
  if (!transparency.empty()) png_set_tRNS(png, info, transparency.data(), int(transparency.size()), nullptr);
  png_write_info(png, info);
  std::vector<png_bytep> pointers;
  for (const auto& row : rows) pointers.push_back(const_cast<png_bytep>(row.data()));
  png_write_image(png, pointers.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  std::fclose(out);
}

// Prism's reading (whole file, and as a texture) against OpenImageIO's.
void expect_read_like_oiio(const fs::path& file) {
  SCOPED_TRACE(file.filename().string());
  const OiioImage want = read_with_oiio(file);
  const ImageFile got = read_image_file(file);
  EXPECT_EQ(got.width, want.width);
  EXPECT_EQ(got.height, want.height);
  EXPECT_EQ(got.channels, want.channels);
  EXPECT_EQ(got.channel_names, want.names);
  EXPECT_EQ(got.pixels, want.pixels);
  const ImageFile header = read_image_header(file);
  EXPECT_EQ(header.channels, want.channels);
  EXPECT_TRUE(header.pixels.empty());
  // As a texture: the sRGB curve on 8/16-bit colour channels of OpenImageIO's values.
  const bool integer = want.format == OIIO::TypeDesc::UINT8 || want.format == OIIO::TypeDesc::UINT16;
  EXPECT_EQ(got.format, want.format == OIIO::TypeDesc::UINT8    ? PixelFormat::UInt8
                        : want.format == OIIO::TypeDesc::UINT16 ? PixelFormat::UInt16
                        : want.format == OIIO::TypeDesc::HALF   ? PixelFormat::Half
                                                                : PixelFormat::Float);
  const Texture texture = load_texture(file, true);
  const int c = want.channels, colour = (c == 2 || c == 4) ? c - 1 : c;
  for (size_t i = 0; i < texture.texels.size(); ++i) {
    float p[4];
    for (int k = 0; k < c; ++k) {
      const float v = want.pixels[i * size_t(c) + size_t(k)];
      p[k] = integer && k < colour ? float(srgb_to_linear(v)) : v;
    }
    const glm::vec4 expected = c == 1 ? glm::vec4(p[0], p[0], p[0], 1)
                               : c == 2 ? glm::vec4(p[0], p[0], p[0], p[1])
                               : c == 3 ? glm::vec4(p[0], p[1], p[2], 1)
                                        : glm::vec4(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(texture.texels[i], expected) << "texel " << i;
  }
}

class ImageCodecs : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::fresh_temp_dir(); }
  fs::path dir_;
};

// round(255 * oetf(clamp(v))): 0.5 -> 0.735357 -> 187.52 -> 188; 0.2 -> 0.484529 -> 123.56 -> 124.
TEST_F(ImageCodecs, RenderedPngReadsBackThroughOpenImageIO) {
  Image image;
  image.width = 3;
  image.height = 2;
  image.rgb = {0, 0.5f, 1, 2, -1, 0.2f, 0.2f, 0.5f, 0, 1, 1, 1, 0, 0, 0, 0.5f, 0.5f, 0.5f};
  const fs::path file = dir_ / "out.png";
  write_image(image, file);
  const OiioImage read = read_with_oiio(file);
  EXPECT_EQ(read.width, 3);
  EXPECT_EQ(read.height, 2);
  EXPECT_EQ(read.names, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(read.format, OIIO::TypeDesc::UINT8);
  const std::vector<int> codes = {0, 188, 255, 255, 0, 124, 124, 188, 0, 255, 255, 255, 0, 0, 0, 188, 188, 188};
  ASSERT_EQ(read.pixels.size(), codes.size());
  for (size_t i = 0; i < codes.size(); ++i) EXPECT_EQ(std::lround(read.pixels[i] * 255.0f), codes[i]) << i;
}

TEST_F(ImageCodecs, RenderedExrReadsBackThroughOpenImageIO) {
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgb = {0.25f, -1.5f, 1e6f, 3.0f, 0.125f, 0.0f};
  image.id = {7, -1};
  image.path = {123456, 0};
  const fs::path file = dir_ / "out.exr";
  write_image(image, file);
  const OiioImage read = read_with_oiio(file);
  EXPECT_EQ(read.names, (std::vector<std::string>{"R", "G", "B", "id", "path"}));
  EXPECT_EQ(read.format, OIIO::TypeDesc::FLOAT);
  for (const OIIO::TypeDesc& t : read.channel_formats) EXPECT_EQ(t, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(read.pixels, (std::vector<float>{0.25f, -1.5f, 1e6f, 7, 123456, 3.0f, 0.125f, 0.0f, -1, 0}));
}

// The first-hit AOVs after id and path, named as OpenEXR tools expect
// (Z; layers N and albedo), read back in OpenImageIO's order (by layer,
// R G B ... Z first).
TEST_F(ImageCodecs, RenderedExrHoldsTheFirstHitAovs) {
  Image image;
  image.width = 1;
  image.height = 1;
  image.rgb = {0.5f, 0.25f, 0.125f};
  image.depth = {4.5f};
  image.normal = {0.6f, 0.0f, -0.8f};
  image.albedo = {0.9f, 0.6f, 0.3f};
  const fs::path file = dir_ / "out.exr";
  write_image(image, file);
  const OiioImage read = read_with_oiio(file);
  EXPECT_EQ(read.names, (std::vector<std::string>{"R", "G", "B", "Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G",
                                                  "albedo.B"}));
  EXPECT_EQ(read.pixels, (std::vector<float>{0.5f, 0.25f, 0.125f, 4.5f, 0.6f, 0.0f, -0.8f, 0.9f, 0.6f, 0.3f}));
}

// RGBE by hand: (1, 0.5, 0.25) has the largest 1 = 0.5 * 2^1, mantissas
// 256 * 0.5 * (1, 0.5, 0.25) = 128, 64, 32 and exponent 1 + 128; (3, -1,
// 0.75): 3 = 0.75 * 2^2, scale 256 * 0.75 / 3 = 64, so 192, 0 (negative), 48
// and 130. Read back, mantissa * 2^(e - 136) gives the values exactly.
TEST_F(ImageCodecs, RenderedHdrIsRgbeAndReadsBackThroughOpenImageIO) {
  Image image;
  image.width = 3;
  image.height = 1;
  image.rgb = {1.0f, 0.5f, 0.25f, 0, 0, 0, 3.0f, -1.0f, 0.75f};
  const fs::path file = dir_ / "out.hdr";
  write_image(image, file);
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 3\n";
  const std::string pixels = {char(128), 64, 32, char(129), 0, 0, 0, 0, char(192), 0, 48, char(130)};
  EXPECT_EQ(test::read_file(file), header + pixels);
  const OiioImage read = read_with_oiio(file);
  EXPECT_EQ(read.width, 3);
  EXPECT_EQ(read.height, 1);
  EXPECT_EQ(read.pixels, (std::vector<float>{1.0f, 0.5f, 0.25f, 0, 0, 0, 3.0f, 0, 0.75f}));
}

// A flat grey block survives JPEG exactly: 0.5 is sRGB code 188, luma 188
// (libjpeg's RGB weights sum to exactly 1 in its fixed point), chroma 128,
// and the DC coefficient 8 * (188 - 128) = 480 is a multiple of the
// quality-95 step (16 * 10 / 100, rounded: 2), so decoding gives 188 back.
TEST_F(ImageCodecs, RenderedJpegReadsBackThroughOpenImageIO) {
  Image image;
  image.width = 8;
  image.height = 8;
  image.rgb.assign(8 * 8 * 3, 0.5f);
  const fs::path file = dir_ / "out.jpg";
  write_image(image, file);
  const OiioImage read = read_with_oiio(file);
  EXPECT_EQ(read.width, 8);
  EXPECT_EQ(read.height, 8);
  EXPECT_EQ(read.channels, 3);
  EXPECT_EQ(read.format, OIIO::TypeDesc::UINT8);
  for (size_t i = 0; i < read.pixels.size(); ++i) EXPECT_EQ(std::lround(read.pixels[i] * 255.0f), 188) << i;
}

// 16-bit output (tests write their fixtures this way): code round(65535 * v).
TEST_F(ImageCodecs, SixteenBitPngReadsBackThroughOpenImageIO) {
  const ImageFile image{2, 1, 2, {}, PixelFormat::UInt16, {0.5f, 1.0f, 0.25f, 0.0f}};
  const fs::path file = dir_ / "grey16.png";
  write_image_file(file, image, PixelFormat::UInt16);
  const OiioImage read = read_with_oiio(file);
  EXPECT_EQ(read.format, OIIO::TypeDesc::UINT16);
  EXPECT_EQ(read.channels, 2);
  const std::vector<long> codes = {32768, 65535, 16384, 0};
  for (size_t i = 0; i < codes.size(); ++i) EXPECT_EQ(std::lround(read.pixels[i] * 65535.0f), codes[i]) << i;
}

// The writer deflates its filtered rows in bands of 256 KiB, in parallel,
// and joins them into one zlib stream: a 16-bit RGBA image of 400 x 300
// (960,300 filtered bytes: four bands, their seams inside rows) of
// pseudo-random codes must read back code for code.
// Noise barely compresses: 700x500 RGBA at 16 bits is ~2.8 MB of deflate
// data, several bands of whole rows that the 1 MiB IDAT chunks cut across.
// The file is the same, byte for byte, written on one thread.
TEST_F(ImageCodecs, PngOfSeveralCompressedBandsReadsBackThroughOpenImageIO) {
  const int width = 700, height = 500, channels = 4;
  std::vector<long> codes(size_t(width) * height * channels);
  uint32_t state = 12345;
  for (long& code : codes) {
    state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG: any fixed sequence will do
    code = long(state >> 16);
  }
  ImageFile image{width, height, channels, {}, PixelFormat::UInt16, {}};
  for (const long code : codes) image.pixels.push_back(float(double(code) / 65535.0));
  const fs::path file = dir_ / "bands.png";
  write_image_file(file, image, PixelFormat::UInt16);
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    write_image_file(dir_ / "one_thread.png", image, PixelFormat::UInt16);
  }
  const std::string bytes = test::read_file(file);
  EXPECT_GT(bytes.size(), size_t(2) << 20);
  EXPECT_EQ(bytes, test::read_file(dir_ / "one_thread.png"));
  const OiioImage read = read_with_oiio(file);
  ASSERT_EQ(read.width, width);
  ASSERT_EQ(read.height, height);
  ASSERT_EQ(read.format, OIIO::TypeDesc::UINT16);
  ASSERT_EQ(read.pixels.size(), codes.size());
  for (size_t i = 0; i < codes.size(); ++i) ASSERT_EQ(std::lround(read.pixels[i] * 65535.0f), codes[i]) << i;
}

TEST_F(ImageCodecs, EveryPngLayoutReadsAsOpenImageIOReadsIt) {
  write_png_raw(dir_ / "grey8.png", 3, 1, 8, PNG_COLOR_TYPE_GRAY, {{0, 128, 255}});
  write_png_raw(dir_ / "grey16.png", 2, 1, 16, PNG_COLOR_TYPE_GRAY, {{0x12, 0x34, 0xff, 0xfe}});
  write_png_raw(dir_ / "grey4.png", 4, 1, 4, PNG_COLOR_TYPE_GRAY, {{0x0f, 0x73}});
  write_png_raw(dir_ / "grey_alpha8.png", 2, 1, 8, PNG_COLOR_TYPE_GRAY_ALPHA, {{10, 20, 200, 0}});
  write_png_raw(dir_ / "grey_alpha16.png", 1, 1, 16, PNG_COLOR_TYPE_GRAY_ALPHA, {{1, 2, 3, 4}});
  write_png_raw(dir_ / "rgb8.png", 2, 2, 8, PNG_COLOR_TYPE_RGB, {{1, 2, 3, 250, 251, 252}, {0, 0, 0, 99, 100, 101}});
  write_png_raw(dir_ / "rgb16.png", 1, 1, 16, PNG_COLOR_TYPE_RGB, {{0xab, 0xcd, 0, 1, 0xff, 0xff}});
  write_png_raw(dir_ / "rgba8.png", 2, 1, 8, PNG_COLOR_TYPE_RGB_ALPHA, {{255, 0, 0, 128, 0, 255, 0, 0}});
  write_png_raw(dir_ / "rgba16.png", 1, 1, 16, PNG_COLOR_TYPE_RGB_ALPHA, {{0, 1, 2, 3, 4, 5, 6, 7}});
  const std::vector<png_color> palette = {{255, 0, 0}, {0, 128, 0}, {1, 2, 3}};
  write_png_raw(dir_ / "palette.png", 3, 1, 8, PNG_COLOR_TYPE_PALETTE, {{2, 0, 1}}, palette);
  write_png_raw(dir_ / "palette_alpha.png", 3, 1, 8, PNG_COLOR_TYPE_PALETTE, {{2, 0, 1}}, palette, {0, 77});
  write_png_raw(dir_ / "palette2.png", 4, 1, 2, PNG_COLOR_TYPE_PALETTE, {{0x1b}}, palette);
  std::vector<std::vector<png_byte>> rows(9);
  for (size_t y = 0; y < rows.size(); ++y)
    for (int x = 0; x < 9 * 3; ++x) rows[y].push_back(png_byte(y * 29 + size_t(x) * 7));
  write_png_raw(dir_ / "interlaced.png", 9, 9, 8, PNG_COLOR_TYPE_RGB, rows, {}, {}, true);
  for (const char* name : {"grey8.png", "grey16.png", "grey4.png", "grey_alpha8.png", "grey_alpha16.png", "rgb8.png",
                           "rgb16.png", "rgba8.png", "rgba16.png", "palette.png", "palette_alpha.png", "palette2.png",
                           "interlaced.png"})
    expect_read_like_oiio(dir_ / name);
}

TEST_F(ImageCodecs, JpegReadsAsOpenImageIOReadsIt) {
  std::vector<float> rgb, grey;
  for (int i = 0; i < 16 * 8; ++i) {
    rgb.insert(rgb.end(), {float(i % 16) / 15.0f, float(i / 16) / 7.0f, 0.5f});
    grey.push_back(float((i * 37) % 256) / 255.0f);
  }
  write_with_oiio(dir_ / "rgb.jpg", 16, 8, {"R", "G", "B"}, OIIO::TypeDesc::UINT8, rgb);
  write_with_oiio(dir_ / "grey.jpg", 16, 8, {"Y"}, OIIO::TypeDesc::UINT8, grey);
  expect_read_like_oiio(dir_ / "rgb.jpg");
  expect_read_like_oiio(dir_ / "grey.jpg");
}

TEST_F(ImageCodecs, ExrReadsAsOpenImageIOReadsIt) {
  const std::vector<float> rgba = {0.5f, 1.5f, -2.0f, 0.25f, 1e-3f, 65504.0f, 0.0f, 1.0f};
  write_with_oiio(dir_ / "half.exr", 2, 1, {"R", "G", "B", "A"}, OIIO::TypeDesc::HALF, rgba);
  write_with_oiio(dir_ / "float.exr", 1, 2, {"B", "A", "R", "G"}, OIIO::TypeDesc::FLOAT, rgba);
  write_with_oiio(dir_ / "extra.exr", 2, 1, {"R", "G", "B", "Z"}, OIIO::TypeDesc::FLOAT, rgba);
  write_with_oiio(dir_ / "y.exr", 2, 2, {"Y"}, OIIO::TypeDesc::HALF, {0.5f, 0.25f, 2.0f, 0.0f});
  for (const char* name : {"half.exr", "float.exr", "extra.exr", "y.exr"}) expect_read_like_oiio(dir_ / name);
}

}  // namespace
}  // namespace prism

// linear_to_srgb8's table lookup against the formula it stands for, at
// every float within 2000 ulps of each code's threshold (where a table could
// be off by one), at 200,000 spread over [0, 1] and at both ends of every
// run of 2^16 floats; plus values worked out
// by hand: 255 * (1.055 * 0.18^(1/2.4) - 0.055) = 117.65, 255 * 12.92 * 0.001 = 3.29.
TEST(Srgb8Codes, EqualTheFormulaEverywhereTheCodeChanges) {
  auto formula = [](float v) { return int(std::lround(255.0 * prism::linear_to_srgb(std::clamp(double(v), 0.0, 1.0)))); };
  EXPECT_EQ(prism::linear_to_srgb8(0.18f), 118);
  EXPECT_EQ(prism::linear_to_srgb8(0.001f), 3);
  EXPECT_EQ(prism::linear_to_srgb8(0.0f), 0);
  EXPECT_EQ(prism::linear_to_srgb8(1.0f), 255);
  EXPECT_EQ(prism::linear_to_srgb8(-3.0f), 0);
  EXPECT_EQ(prism::linear_to_srgb8(7.0f), 255);
  EXPECT_EQ(prism::linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  int mismatches = 0;
  for (int k = 1; k < 256; ++k) {
    // The smallest float with code k, by bisection on the formula itself.
    uint32_t lo = 0, hi = std::bit_cast<uint32_t>(1.0f);
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      (formula(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
    }
    for (uint32_t bits = hi - 2000; bits <= hi + 2000; ++bits) {
      const float v = std::bit_cast<float>(bits);
      if (v <= 1.0f) mismatches += prism::linear_to_srgb8(v) != formula(v);
    }
  }
  for (int i = 0; i <= 200000; ++i) {
    const float v = float(i) / 200000.0f;
    mismatches += prism::linear_to_srgb8(v) != formula(v);
  }
  // The first and last float of every run of 2^16 bit patterns below 1 (a
  // table kept by the top bits of a float is wrong at a run's ends first).
  for (uint32_t run = 0; run < (std::bit_cast<uint32_t>(1.0f) >> 16); ++run) {
    for (const uint32_t bits : {run << 16, (run << 16) | 0xffffu})
      mismatches += prism::linear_to_srgb8(std::bit_cast<float>(bits)) != formula(std::bit_cast<float>(bits));
  }
  EXPECT_EQ(mismatches, 0);
}
