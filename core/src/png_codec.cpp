// PNG through libpng. libpng reports errors by longjmp from its error
// callback: every function below that calls into libpng sets its jump point
// first and keeps no C++ object alive across the libpng calls it makes.
#include <png.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "image_codecs.hpp"
#include "prism/cancel.hpp"

namespace prism::codec {

namespace {

// The message of libpng's last error, for the exception thrown once it has unwound.
struct PngContext {
  char message[256] = "";
  int fd = -1;  // writing: the file descriptor the bytes go to
  int write_errno = 0;
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* context = static_cast<PngContext*>(png_get_error_ptr(png));
  std::snprintf(context->message, sizeof context->message, "%s", message);
  png_longjmp(png, 1);
}

// libpng's warnings (an unusual iCCP profile, an unknown chunk) do not stop
// a read; without this handler libpng prints them on stderr.
void on_png_warning(png_structp, png_const_charp) {}

int color_channels(int color_type) {
  switch (color_type) {
    case PNG_COLOR_TYPE_GRAY: case PNG_COLOR_TYPE_PALETTE: return 1;
    case PNG_COLOR_TYPE_GRAY_ALPHA: return 2;
    case PNG_COLOR_TYPE_RGB: return 3;
    default: return 4;
  }
}

std::vector<std::string> png_channel_names(int channels) {
  // OpenImageIO's names for the PNG layouts.
  switch (channels) {
    case 1: return {"Y"};
    case 2: return {"Y", "A"};
    case 3: return {"R", "G", "B"};
    default: return {"R", "G", "B", "A"};
  }
}

class PngReader {
 public:
  PngReader() = default;
  void open(const std::filesystem::path& file) {
    file_ = std::fopen(file.c_str(), "rbe");
    if (!file_) throw CodecError(std::strerror(errno));
    unsigned char signature[8] = {};
    if (std::fread(signature, 1, 8, file_) != 8 || png_sig_cmp(signature, 0, 8) != 0)
      throw CodecError("not a PNG file");
    png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, &context_, on_png_error, on_png_warning);
    if (png_) info_ = png_create_info_struct(png_);
    if (!png_ || !info_) throw CodecError("out of memory");
    if (!read_info()) throw CodecError(context_.message);
  }
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;
  ~PngReader() {
    if (png_) png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr);
    if (file_) std::fclose(file_);
  }

  const ImageFile& header() const { return header_; }

  void read(int max_channels, const RowSink& sink) {
    check_plausible_size();
    const int channels = std::min(header_.channels, max_channels);
    ImageFile shape = header_;
    shape.channels = channels;
    shape.channel_names.resize(size_t(channels));
    sink.header(shape);
    std::vector<float> values(size_t(header_.width) * size_t(channels));
    if (passes_ > 1) return read_interlaced(channels, values, sink);
    const bool as_codes = sink.codes8 && depth_ == 8 && channels == header_.channels;
    std::vector<png_byte> row(row_bytes_);
    for (int y = 0; y < header_.height; ++y) {
      throw_if_cancelled();
      if (!read_row(row.data())) throw CodecError(std::string("cannot decode: ") + context_.message);
      if (as_codes) {
        sink.codes8(y, row.data());
        continue;
      }
      convert(row.data(), channels, values.data());
      sink.row(y, values.data());
    }
    finish();
  }

 private:
  bool read_info() {
    if (setjmp(png_jmpbuf(png_))) return false;
    png_init_io(png_, file_);
    png_set_sig_bytes(png_, 8);
    png_read_info(png_, info_);
    png_uint_32 width = 0, height = 0;
    int color_type = 0, interlace = 0;
    png_get_IHDR(png_, info_, &width, &height, &file_depth_, &color_type, &interlace, nullptr, nullptr);
    file_bits_per_pixel_ = file_depth_ * color_channels(color_type);
    // OpenImageIO's expansions: palette to RGB, low-bit grey to 8 bits, tRNS to an alpha channel.
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png_);
    if (color_type == PNG_COLOR_TYPE_GRAY && file_depth_ < 8) png_set_expand_gray_1_2_4_to_8(png_);
    if (png_get_valid(png_, info_, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png_);
    if (file_depth_ == 16) png_set_swap(png_);  // little-endian uint16 in memory
    passes_ = png_set_interlace_handling(png_);
    png_read_update_info(png_, info_);
    header_.width = int(width);
    header_.height = int(height);
    header_.channels = png_get_channels(png_, info_);
    header_.channel_names = png_channel_names(header_.channels);
    depth_ = png_get_bit_depth(png_, info_);
    header_.format = depth_ == 16 ? PixelFormat::UInt16 : PixelFormat::UInt8;
    row_bytes_ = png_get_rowbytes(png_, info_);
    return true;
  }

  // zlib expands at most 1032:1, so a file whose size cannot hold its
  // header's rows is refused before anything is decoded or allocated (a
  // 66-byte file claiming 16384x16384 would otherwise decode for seconds).
  void check_plausible_size() {
    const long position = std::ftell(file_);
    std::fseek(file_, 0, SEEK_END);
    const double file_bytes = double(std::ftell(file_));
    std::fseek(file_, position, SEEK_SET);
    const double data_bytes = double(header_.height) * std::ceil(double(header_.width) * file_bits_per_pixel_ / 8.0);
    if (data_bytes > 1032.0 * file_bytes + 65536.0)
      throw CodecError("cannot decode: the file's " + std::to_string(long(file_bytes)) + " bytes cannot hold " +
                       std::to_string(header_.width) + "x" + std::to_string(header_.height) +
                       " pixels (truncated, or a false header)");
  }

  bool read_row(png_bytep row) {
    if (setjmp(png_jmpbuf(png_))) return false;
    png_read_row(png_, row, nullptr);
    return true;
  }

  bool read_all(png_bytepp rows) {
    if (setjmp(png_jmpbuf(png_))) return false;
    png_read_image(png_, rows);
    return true;
  }

  // The end chunks are read for their CRCs, as a complete read of the file.
  void finish() {
    if (setjmp(png_jmpbuf(png_))) throw CodecError(std::string("cannot decode: ") + context_.message);
    png_read_end(png_, nullptr);
  }

  void read_interlaced(int channels, std::vector<float>& values, const RowSink& sink) {
    std::vector<png_byte> image(row_bytes_ * size_t(header_.height));
    std::vector<png_bytep> rows(size_t(header_.height));
    for (size_t y = 0; y < rows.size(); ++y) rows[y] = image.data() + y * row_bytes_;
    throw_if_cancelled();
    if (!read_all(rows.data())) throw CodecError(std::string("cannot decode: ") + context_.message);
    for (int y = 0; y < header_.height; ++y) {
      if (y % 256 == 0) throw_if_cancelled();
      convert(rows[size_t(y)], channels, values.data());
      sink.row(y, values.data());
    }
    finish();
  }

  // OpenImageIO's integer-to-float conversion: code * (1 / max) in float.
  void convert(const png_byte* row, int channels, float* out) const {
    const size_t width = size_t(header_.width), stride = size_t(header_.channels);
    if (depth_ == 16) {
      const auto* codes = reinterpret_cast<const uint16_t*>(row);
      for (size_t x = 0; x < width; ++x)
        for (int c = 0; c < channels; ++c) out[x * size_t(channels) + size_t(c)] = float(codes[x * stride + size_t(c)]) * (1.0f / 65535.0f);
    } else {
      for (size_t x = 0; x < width; ++x)
        for (int c = 0; c < channels; ++c) out[x * size_t(channels) + size_t(c)] = code8_value(row[x * stride + size_t(c)]);
    }
  }

  FILE* file_ = nullptr;
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
  PngContext context_;
  ImageFile header_;
  int file_depth_ = 8, file_bits_per_pixel_ = 8, depth_ = 8, passes_ = 1;
  size_t row_bytes_ = 0;
};

void write_to_fd(png_structp png, png_bytep data, size_t length) {
  auto* context = static_cast<PngContext*>(png_get_io_ptr(png));
  if (const int error = write_fully(context->fd, data, length)) png_error(png, std::strerror(error));
}

void flush_nothing(png_structp) {}

// `image`'s rows quantised to the stored depth: round(v * max) of v clamped to [0, 1].
PngRows quantised_rows(const ImageFile& image, bool sixteen) {
  PngRows rows{image.width, image.height, image.channels, sixteen, {}};
  const size_t values = size_t(image.width) * size_t(image.channels);
  rows.row = [&image, values, sixteen](int y, unsigned char* samples) {
    const double max = sixteen ? 65535.0 : 255.0;
    const float* in = image.pixels.data() + size_t(y) * values;
    for (size_t i = 0; i < values; ++i) {
      const long code = std::lround(std::clamp(double(in[i]), 0.0, 1.0) * max);
      if (sixteen) {
        samples[2 * i] = png_byte(code >> 8);
        samples[2 * i + 1] = png_byte(code & 0xff);
      } else {
        samples[i] = png_byte(code);
      }
    }
  };
  return rows;
}

// zlib level 2 with the "sub" filter: several times faster than libpng's
// default (level 6, every filter tried per row) for ~40 % larger files;
// level 1 was no faster and 2 % larger.
constexpr int kZlibLevel = 2;
// The rows are filtered and deflated in bands of whole rows, each about this
// many bytes of filtered data, in parallel: each band independently, so the
// file does not depend on the thread count. A band loses the matches that
// reach back into the one before it: nothing measurable (the showcase at
// 1280x720: 515,235 bytes, against 515,881 from libpng's own deflate at the
// same level). A band's filtered rows live only in its worker's buffer,
// never in one buffer of the whole image: at 1280x720 that buffer and
// zero-filled room for each band's output were ~1,300 fresh pages to fault
// in, ~1.5 ms of a whole `prism render` to PNG.
constexpr size_t kBandBytes = size_t(1) << 18;

// The image as PNG's compressed data holds it, band by band: each row as
// `rows.row` fills it, after a filter-type byte, filtered with "sub" (each
// byte less the byte one pixel to its left).
class CompressedRows {
 public:
  explicit CompressedRows(const PngRows& rows) : rows_(rows) {
    const size_t sample_bytes = rows.sixteen ? 2 : 1;
    pixel_bytes_ = size_t(rows.channels) * sample_bytes;
    raw_bytes_ = size_t(rows.width) * pixel_bytes_;
    row_bytes_ = 1 + raw_bytes_;
    rows_per_band_ = std::max<size_t>(1, kBandBytes / row_bytes_);
    // At least one band, so that an image without rows is still a finished stream.
    bands_.resize(std::max<size_t>(1, (size_t(rows.height) + rows_per_band_ - 1) / rows_per_band_));
    tbb::enumerable_thread_specific<Scratch> scratch;
    tbb::parallel_for(size_t(0), bands_.size(), [&](size_t b) { compress_band(b, scratch.local()); });
    sum_ = bands_[0].adler;
    for (size_t b = 1; b < bands_.size(); ++b) sum_ = adler32_combine(sum_, bands_[b].adler, z_off_t(bands_[b].filtered));
    for (const Band& band : bands_) size_ += band.size;
  }

  // The zlib stream (RFC 1950): header, the bands' deflate data in order,
  // and the Adler-32 of the whole, combined from the bands' own.
  size_t size() const { return sizeof header_ + size_ + 4; }
  template <typename Fn>  // fn(const png_byte* data, size_t size), piece by piece in order
  void for_each_piece(Fn&& fn) const {
    fn(header_, sizeof header_);
    for (const Band& band : bands_) fn(band.data.get(), band.size);
    const png_byte trailer[4] = {png_byte(sum_ >> 24), png_byte(sum_ >> 16), png_byte(sum_ >> 8), png_byte(sum_)};
    fn(trailer, sizeof trailer);
  }

 private:
  struct Band {
    std::unique_ptr<png_byte[]> data;  // raw deflate data
    size_t size = 0;
    size_t filtered = 0;  // bytes of filtered rows it holds
    uLong adler = 0;      // their Adler-32
  };
  struct Scratch {
    std::vector<png_byte> raw, filtered;
  };

  void compress_band(size_t b, Scratch& scratch) {
    const int y0 = int(b * rows_per_band_), y1 = int(std::min(size_t(rows_.height), (b + 1) * rows_per_band_));
    scratch.raw.resize(raw_bytes_);
    scratch.filtered.resize(size_t(y1 - y0) * row_bytes_);
    for (int y = y0; y < y1; ++y) {
      png_byte* row = scratch.filtered.data() + size_t(y - y0) * row_bytes_;
      rows_.row(y, scratch.raw.data());
      filter_sub(scratch.raw.data(), row);
    }
    Band& band = bands_[b];
    band.filtered = scratch.filtered.size();
    band.adler = adler32(adler32(0, nullptr, 0), scratch.filtered.data(), uInt(band.filtered));
    deflate_band(scratch.filtered.data(), band.filtered, b + 1 == bands_.size(), band);
  }

  void filter_sub(const png_byte* raw, png_byte* row) const {
    row[0] = PNG_FILTER_VALUE_SUB;
    std::copy_n(raw, std::min(pixel_bytes_, raw_bytes_), row + 1);
    for (size_t i = pixel_bytes_; i < raw_bytes_; ++i) row[1 + i] = png_byte(raw[i] - raw[i - pixel_bytes_]);
  }

  // One band as raw deflate data: ended by a full flush (byte-aligned, no
  // final block) so that the next band's data may follow it, or finished.
  // Its room is left unfilled: deflate touches only the pages it writes.
  static void deflate_band(const png_byte* data, size_t size, bool last, Band& band) {
    z_stream z{};
    if (deflateInit2(&z, kZlibLevel, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
      throw CodecError("zlib: cannot start compressing");
    const size_t room = deflateBound(&z, uLong(size)) + 16;
    band.data = std::make_unique_for_overwrite<png_byte[]>(room);
    z.next_in = const_cast<png_byte*>(data);
    z.avail_in = uInt(size);
    z.next_out = band.data.get();
    z.avail_out = uInt(room);
    const int result = deflate(&z, last ? Z_FINISH : Z_FULL_FLUSH);
    // A flush is whole when input is used up and output room is left over.
    const bool done = last ? result == Z_STREAM_END : result == Z_OK && z.avail_in == 0 && z.avail_out > 0;
    band.size = z.total_out;
    deflateEnd(&z);
    if (!done) throw CodecError("zlib: compressing failed");
  }

  // CMF: deflate, 32 KiB window; FLG: level 2-5's "fast" and the check bits (RFC 1950).
  static constexpr unsigned kCmf = 0x78, kFlags = 1u << 6;
  static constexpr png_byte header_[2] = {png_byte(kCmf), png_byte(kFlags + 31 - (kCmf * 256 + kFlags) % 31)};

  const PngRows& rows_;
  size_t pixel_bytes_ = 0, raw_bytes_ = 0, row_bytes_ = 0, rows_per_band_ = 1;
  std::vector<Band> bands_;
  uLong sum_ = 0;
  size_t size_ = 0;
};

bool write_png_chunks(png_structp png, png_infop info, const PngRows& rows, const CompressedRows& compressed) {
  if (setjmp(png_jmpbuf(png))) return false;
  static const int kColorTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                    PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_write_fn(png, png_get_error_ptr(png), write_to_fd, flush_nothing);
  png_set_IHDR(png, info, png_uint_32(rows.width), png_uint_32(rows.height), rows.sixteen ? 16 : 8,
               kColorTypes[rows.channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  // The compressed rows as IDAT chunks (libpng compresses on one thread
  // only; it writes the chunks, with their CRCs, as they are).
  // Chunks of up to kChunkBytes, each written from the pieces it spans.
  constexpr size_t kChunkBytes = size_t(1) << 20;
  const size_t total = compressed.size();
  size_t written = 0, chunk_left = 0;
  compressed.for_each_piece([&](const png_byte* data, size_t size) {
    while (size > 0) {
      if (chunk_left == 0) {
        chunk_left = std::min(kChunkBytes, total - written);
        png_write_chunk_start(png, reinterpret_cast<png_const_bytep>("IDAT"), png_uint_32(chunk_left));
      }
      const size_t part = std::min(size, chunk_left);
      png_write_chunk_data(png, data, part);
      data += part, size -= part, written += part, chunk_left -= part;
      if (chunk_left == 0) png_write_chunk_end(png);
    }
  });
  png_write_chunk(png, reinterpret_cast<png_const_bytep>("IEND"), nullptr, 0);
  return true;
}

}  // namespace

ImageFile read_png_header(const std::filesystem::path& file) {
  PngReader reader;
  reader.open(file);
  return reader.header();
}

void read_png(const std::filesystem::path& file, int max_channels, const RowSink& sink) {
  PngReader reader;
  reader.open(file);
  reader.read(max_channels, sink);
}

void write_png(int fd, const ImageFile& image, PixelFormat storage) {
  if (storage != PixelFormat::UInt8 && storage != PixelFormat::UInt16) throw CodecError("PNG stores 8- or 16-bit integers only");
  write_png(fd, quantised_rows(image, storage == PixelFormat::UInt16));
}

void write_png(int fd, const PngRows& rows) {
  if (rows.channels < 1 || rows.channels > 4) throw CodecError("PNG holds 1 to 4 channels, not " + std::to_string(rows.channels));
  // Made before libpng's structures, and outside its jump points.
  const CompressedRows compressed(rows);
  PngContext context;
  context.fd = fd;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &context, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, nullptr);
    throw CodecError("out of memory");
  }
  const bool written = write_png_chunks(png, info, rows, compressed);
  png_destroy_write_struct(&png, &info);
  if (!written) throw CodecError(context.message);
}

}  // namespace prism::codec
