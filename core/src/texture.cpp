#include "prism/texture.hpp"

#include <sys/stat.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <compare>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <stdexcept>

#include "json_reader.hpp"
#include "prism/errors.hpp"
#include "prism/image_file.hpp"

namespace prism {

namespace {

// Euclidean modulo: repeat wrap for negative coordinates too.
int wrap(int i, int n) {
  if (static_cast<unsigned>(i) < static_cast<unsigned>(n)) return i;  // inside: no division
  if ((n & (n - 1)) == 0) return i & (n - 1);  // a power of two: two's complement masks any i right
  int m = i % n;
  return m < 0 ? m + n : m;
}

// wrap(i + 1, n) from at = wrap(i, n), without a second division (a scaled
// texture, such as a tiled floor, wraps nearly every lookup).
int wrap_next(int /*i*/, int at, int n) { return at + 1 == n ? 0 : at + 1; }
int clamp_index(int i, int n) { return std::clamp(i, 0, n - 1); }
int clamp_next(int i, int /*at*/, int n) { return clamp_index(i + 1, n); }

// A texture's texels as the sampler reads them: the float texels, or their
// codes and the codes' values (Texture::codes), which give the same bits.
class FloatTexels {
 public:
  explicit FloatTexels(const Texture& t) : texels_(t.texels.data()), width_(size_t(t.width)) {}
  [[gnu::always_inline]] glm::dvec4 operator()(int x, int y) const { return glm::dvec4(texels_[size_t(y) * width_ + size_t(x)]); }

 private:
  const glm::vec4* texels_;
  size_t width_;
};

class CodedTexels {
 public:
  explicit CodedTexels(const Texture& t)
      : codes_(t.codes.data()), colour_(t.code_values.data()), alpha_(colour_ + 256), width_(size_t(t.width)) {}
  [[gnu::always_inline]] glm::dvec4 operator()(int x, int y) const {  // four per lookup: a call each cost ~10 %
    const uint32_t c = codes_[size_t(y) * width_ + size_t(x)];
    return {colour_[c & 0xffu], colour_[(c >> 8) & 0xffu], colour_[(c >> 16) & 0xffu], alpha_[c >> 24]};
  }

 private:
  const uint32_t* codes_;
  const double* colour_;
  const double* alpha_;
  size_t width_;
};

// Bilinear blend of the four texels around (x, y) in texel space; `index`
// maps an integer coordinate and the size to a texel row/column, and
// next(i, index(i, n), n) gives index(i + 1, n).
template <int (*index)(int, int), int (*next)(int, int, int), typename Texels>
glm::dvec4 bilinear_of(const Texture& t, double x, double y) {
  const Texels texel(t);
  double fx0 = std::floor(x), fy0 = std::floor(y);
  double fx = x - fx0, fy = y - fy0;
  int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  int xa = index(x0, t.width), xb = next(x0, xa, t.width);
  int ya = index(y0, t.height), yb = next(y0, ya, t.height);
  glm::dvec4 top = texel(xa, ya) * (1 - fx) + texel(xb, ya) * fx;
  glm::dvec4 bottom = texel(xa, yb) * (1 - fx) + texel(xb, yb) * fx;
  return top * (1 - fy) + bottom * fy;
}

template <int (*index)(int, int), int (*next)(int, int, int)>
glm::dvec4 bilinear(const Texture& t, double x, double y) {
  return t.codes.empty() ? bilinear_of<index, next, FloatTexels>(t, x, y) : bilinear_of<index, next, CodedTexels>(t, x, y);
}

glm::vec4 expand_channels(const float* p, int channels) {
  switch (channels) {
    case 1: return {p[0], p[0], p[0], 1.0f};
    case 2: return {p[0], p[0], p[0], p[1]};
    case 3: return {p[0], p[1], p[2], 1.0f};
    default: return {p[0], p[1], p[2], p[3]};
  }
}

}  // namespace

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

double linear_to_srgb(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

namespace {

// The code linear_to_srgb8 stands for, computed the slow way.
int srgb8_by_formula(float linear) { return int(std::lround(255.0 * linear_to_srgb(std::clamp(double(linear), 0.0, 1.0)))); }

// For each code k, the smallest float in [0, 1] whose code is at least k
// (the code only grows with the value), found by bisection over the bit
// patterns of the floats in [0, 1], which order as the floats do. A lookup
// takes the float's top 16 bits (sign, exponent and 7 mantissa bits: slices
// 2^-7 of their own size wide, fine where the curve is steep near 0) to the
// code at its slice's start and the next code's threshold. Every slice holds
// at most one threshold (the densest, near 0.003, about 0.45; checked when
// the table is built), so one comparison finishes the lookup, without a
// branch to mispredict (2.8 M values, one thread: 11.3-12.0 ms with a loop
// over the thresholds, 7.6-8.4 ms so).
class Srgb8Table {
 public:
  Srgb8Table() {
    float threshold[257];
    threshold[0] = 0.0f;
    for (int k = 1; k < 256; ++k) threshold[k] = smallest_with_code(k);
    threshold[256] = std::numeric_limits<float>::infinity();
    int code = 0;
    for (uint32_t slice = 0; slice < kSlices; ++slice) {
      const float start = std::bit_cast<float>(slice << kDroppedBits);
      const float end = std::bit_cast<float>(((slice + 1) << kDroppedBits) - 1);  // the slice's last float
      while (start >= threshold[code + 1]) ++code;
      start_code_[slice] = uint8_t(code);
      next_threshold_[slice] = threshold[code + 1];
      if (end >= threshold[std::min(code + 2, 256)]) throw std::logic_error("sRGB table: two codes start in one slice");
    }
  }

  uint8_t code(float linear) const {
    if (!(linear > 0.0f)) return 0;  // NaN too
    if (linear >= 1.0f) return 255;
    const uint32_t slice = std::bit_cast<uint32_t>(linear) >> kDroppedBits;
    return uint8_t(start_code_[slice] + (linear >= next_threshold_[slice] ? 1 : 0));
  }

 private:
  static constexpr int kDroppedBits = 16;
  static constexpr uint32_t kSlices = std::bit_cast<uint32_t>(1.0f) >> kDroppedBits;  // the slices below 1

  static float smallest_with_code(int k) {
    uint32_t lo = 0, hi = std::bit_cast<uint32_t>(1.0f);  // code(lo) < k <= code(hi)
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      (srgb8_by_formula(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
    }
    return std::bit_cast<float>(hi);
  }

  uint8_t start_code_[kSlices];
  float next_threshold_[kSlices];
};

}  // namespace

uint8_t linear_to_srgb8(float linear) {
  static const Srgb8Table table;
  return table.code(linear);
}

namespace {

// Refuses a texture whose header says it is larger than what is left of the scene's pixel budget.
void check_texture_size(const std::filesystem::path& path, const ImageFile& header, size_t pixels_left) {
  const size_t pixels = size_t(header.width) * size_t(header.height);
  if (pixels <= pixels_left) return;
  const std::string limit = std::to_string(limits::kMaxTexturePixels) + " pixels all textures of a scene may hold";
  const std::string left = pixels_left == limits::kMaxTexturePixels
                               ? "the limit of " + limit
                               : "the " + std::to_string(pixels_left) + " left of the " + limit;
  throw InputError("'" + path.string() + "' is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                   " = " + std::to_string(pixels) + " pixels, more than " + left);
}

// Decoded texel by texel as rows arrive, so memory grows with the pixels
// actually in the file, and a stop request ends the decoding within a row.
class TexelDecoder {
 public:
  TexelDecoder(const std::filesystem::path& path, bool srgb) : path_(path), srgb_(srgb) { texture_.path = path; }

  void header(const ImageFile& header) {
    texture_.width = header.width;
    texture_.height = header.height;
    channels_ = std::min(header.channels, 4);
    names_ = header.channel_names;
    // 8- and 16-bit colour is sRGB-encoded unless the scene says otherwise; float formats are linear.
    const bool integer_format = header.format == PixelFormat::UInt8 || header.format == PixelFormat::UInt16;
    finite_check_ = !integer_format;
    if (srgb_ && integer_format) build_srgb_table(header.format == PixelFormat::UInt8 ? 255 : 65535);
    if (header.format == PixelFormat::UInt8) {
      build_code_values();
      coded_ = true;
      codes_.reserve(size_t(header.width) * size_t(header.height));
    }
    texture_.texels.reserve(size_t(header.width) * size_t(header.height));
  }

  // An 8-bit row as codes: each channel's value from a table, the same
  // float the row of values would have given (code8_value, then the sRGB
  // table for colour), without a float per sample in between.
  void codes8(const unsigned char* codes) {
    switch (channels_) {
      case 1: return decode_codes<1>(codes);
      case 2: return decode_codes<2>(codes);
      case 3: return decode_codes<3>(codes);
      default: return decode_codes<4>(codes);
    }
  }

  void row(int y, const float* values) {
    const int colour_channels = (channels_ == 2 || channels_ == 4) ? channels_ - 1 : channels_;
    for (int x = 0; x < texture_.width; ++x) {
      float p[4];
      std::copy_n(values + size_t(x) * size_t(channels_), channels_, p);
      if (!srgb_table_.empty())
        for (int c = 0; c < colour_channels; ++c) p[c] = srgb_table_[size_t(std::lround(p[c] * max_code_))];
      if (finite_check_) refuse_non_finite(x, y, p);
      texture_.texels.push_back(expand_channels(p, channels_));
    }
    if (coded_) {
      for (int x = 0; x < texture_.width; ++x) {
        unsigned char codes[4];
        for (int c = 0; c < channels_; ++c) {
          const float code = std::round(values[size_t(x) * size_t(channels_) + size_t(c)] * 255.0f);
          codes[c] = code >= 0.0f && code <= 255.0f ? static_cast<unsigned char>(code) : 0;  // a mismatch is caught in take()
        }
        codes_.push_back(code_word(codes, channels_));
      }
    }
  }

  // The texture, with its codes where they give every texel bit for bit.
  Texture take() {
    if (coded_ && codes_give_the_texels()) {
      texture_.codes = std::move(codes_);
      texture_.code_values.assign(&code_values_[0][0], &code_values_[0][0] + 512);
    }
    return std::move(texture_);
  }

 private:
  template <int kChannels>
  void decode_codes(const unsigned char* codes) {
    constexpr int kColourChannels = (kChannels == 2 || kChannels == 4) ? kChannels - 1 : kChannels;
    for (int x = 0; x < texture_.width; ++x) {
      float p[4];
      for (int c = 0; c < kChannels; ++c) p[c] = code_values_[c < kColourChannels ? 0 : 1][codes[size_t(x) * kChannels + size_t(c)]];
      texture_.texels.push_back(expand_channels(p, kChannels));
      codes_.push_back(code_word(codes + size_t(x) * kChannels, kChannels));
    }
  }

  // One texel's codes as expand_channels spreads its channels over R, G, B, A
  // (an opaque texel's alpha: code 255, whose value is 1).
  static uint32_t code_word(const unsigned char* codes, int channels) {
    uint32_t r = codes[0], g = codes[0], b = codes[0], a = 255;
    if (channels == 2) a = codes[1];
    if (channels >= 3) g = codes[1], b = codes[2];
    if (channels == 4) a = codes[3];
    return r | (g << 8) | (b << 16) | (a << 24);
  }

  bool codes_give_the_texels() const {
    if (codes_.size() != texture_.texels.size()) return false;
    for (size_t i = 0; i < codes_.size(); ++i) {
      const glm::vec4& texel = texture_.texels[i];
      for (int c = 0; c < 4; ++c) {
        const float value = code_values_[c == 3 ? 1 : 0][(codes_[i] >> (8 * c)) & 0xffu];
        if (std::bit_cast<uint32_t>(value) != std::bit_cast<uint32_t>(texel[c])) return false;
      }
    }
    return true;
  }

  void build_code_values() {
    for (unsigned code = 0; code < 256; ++code) {
      code_values_[0][code] = srgb_table_.empty() ? code8_value(code) : srgb_table_[code];
      code_values_[1][code] = code8_value(code);
    }
  }

  // Each code's value as the decoder gives it (code * (1 / max) in float), then the curve in double.
  void build_srgb_table(int max_code) {
    max_code_ = float(max_code);
    srgb_table_.resize(size_t(max_code) + 1);
    for (int code = 0; code <= max_code; ++code)
      srgb_table_[size_t(code)] = static_cast<float>(srgb_to_linear(double(float(code) * (1.0f / float(max_code)))));
  }

  // A NaN or infinity would spread through every shading sum it touches.
  void refuse_non_finite(int x, int y, const float* p) const {
    for (int c = 0; c < channels_; ++c) {
      if (std::isfinite(p[c])) continue;
      const std::string value = std::isnan(p[c]) ? "NaN" : (p[c] > 0 ? "+Inf" : "-Inf");
      const std::string channel = size_t(c) < names_.size() ? names_[size_t(c)] : std::to_string(c);
      throw InputError("'" + path_.string() + "': texel (" + std::to_string(x) + ", " + std::to_string(y) +
                       ") channel " + channel + " is " + value + "; texture values must be finite");
    }
  }

  std::filesystem::path path_;
  bool srgb_;
  Texture texture_;
  int channels_ = 0;
  std::vector<std::string> names_;
  bool finite_check_ = false;
  float max_code_ = 0;
  std::vector<float> srgb_table_;
  float code_values_[2][256] = {};  // 8-bit files: [0] colour channels, [1] alpha
  bool coded_ = false;              // an 8-bit file: its codes are kept
  std::vector<uint32_t> codes_;
};

Texture decode_texture(const std::filesystem::path& path, bool srgb, size_t max_pixels) {
  TexelDecoder decoder(path, srgb);
  read_image_rows(path, max_pixels, 4,  // channels past RGBA are never used
                  {[&](const ImageFile& header) { decoder.header(header); },
                   [&](int y, const float* values) { decoder.row(y, values); },
                   [&](int, const unsigned char* codes) { decoder.codes8(codes); }});
  return decoder.take();
}

// The same file read for the same colour space: decoded once however many names it has.
struct TextureKey {
  dev_t device;
  ino_t inode;
  bool srgb;
  auto operator<=>(const TextureKey&) const = default;
};

TextureKey key_of(const std::filesystem::path& file, bool srgb) {
  struct stat info {};
  if (::stat(file.c_str(), &info) != 0) throw InputError("cannot read image '" + file.string() + "': " + std::strerror(errno));
  return {info.st_dev, info.st_ino, srgb};
}

template <typename Fn>
auto leading_with(const std::string& path, Fn fn) {
  try {
    return fn();
  } catch (const InputError& e) {
    json::fail(path, e.what());
  }
}

}  // namespace

Texture load_texture(const std::filesystem::path& path, bool srgb, size_t pixels_left) {
  check_texture_size(path, read_image_header(path), pixels_left);
  return decode_texture(path, srgb, pixels_left);
}

std::vector<Texture> load_textures(const std::vector<TextureRequest>& requests, size_t pixels_left) {
  // Every header and the budget first: nothing is decoded for a scene whose textures cannot all fit.
  std::vector<TextureKey> keys;
  std::map<TextureKey, size_t> first_of;  // key -> index of the request that decodes it
  for (size_t i = 0; i < requests.size(); ++i) {
    const TextureRequest& r = requests[i];
    keys.push_back(leading_with(r.path, [&] {
      const ImageFile header = read_image_header(r.file);
      const TextureKey key = key_of(r.file, r.srgb);
      if (!first_of.count(key)) {
        check_texture_size(r.file, header, pixels_left);
        pixels_left -= size_t(header.width) * size_t(header.height);
        first_of[key] = i;
      }
      return key;
    }));
  }
  // The files decoded in parallel (a scene's textures are independent); a
  // failure is kept and the first request's in scene order is the one thrown,
  // so the message does not depend on which thread finished first.
  std::vector<Texture> decoded(requests.size());
  std::vector<std::exception_ptr> failed(requests.size());
  tbb::parallel_for(size_t(0), requests.size(), [&](size_t i) {
    const TextureRequest& r = requests[i];
    if (first_of.at(keys[i]) != i) return;
    try {
      decoded[i] = leading_with(r.path, [&] { return decode_texture(r.file, r.srgb, limits::kMaxTexturePixels); });
    } catch (...) {
      failed[i] = std::current_exception();
    }
  });
  std::vector<Texture> textures;
  for (size_t i = 0; i < requests.size(); ++i) {
    if (failed[i]) std::rethrow_exception(failed[i]);
    const TextureRequest& r = requests[i];
    const size_t first = first_of.at(keys[i]);
    Texture texture = first == i ? std::move(decoded[i]) : textures[first];
    texture.name = r.name;
    texture.path = r.file;
    textures.push_back(std::move(texture));
  }
  return textures;
}

glm::dvec4 sample_texture(const Texture& texture, glm::dvec2 uv) {
  return bilinear<wrap, wrap_next>(texture, uv.x * texture.width - 0.5, uv.y * texture.height - 0.5);
}

namespace {

// A cube-map face sampled at (s, t) with the texture filter, clamped to the face's edge texels.
glm::dvec3 sample_face(const Texture& face, double s, double t) {
  return glm::dvec3(bilinear<clamp_index, clamp_next>(face, s * face.width - 0.5, t * face.height - 0.5));
}

}  // namespace

glm::dvec3 background_radiance(const Scene& scene, const glm::dvec3& d) {
  const Background& bg = scene.background;
  if (!bg.has_cubemap()) return bg.color;
  const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  int face;
  double sc, tc, ma;  // the OpenGL cube-map selection table
  if (ax >= ay && ax >= az) {
    face = d.x >= 0 ? 0 : 1;
    sc = d.x >= 0 ? -d.z : d.z;
    tc = -d.y;
    ma = d.x;
  } else if (ay >= az) {
    face = d.y >= 0 ? 2 : 3;
    sc = d.x;
    tc = d.y >= 0 ? d.z : -d.z;
    ma = d.y;
  } else {
    face = d.z >= 0 ? 4 : 5;
    sc = d.z >= 0 ? d.x : -d.x;
    tc = -d.y;
    ma = d.z;
  }
  const double m = std::abs(ma);
  const double s = (sc / m + 1) / 2, t = (tc / m + 1) / 2;
  return sample_face(scene.textures[size_t(bg.cubemap[size_t(face)])], s, t);
}

}  // namespace prism
