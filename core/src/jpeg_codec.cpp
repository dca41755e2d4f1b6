// JPEG textures and `prism render -o x.jpg` through libjpeg-turbo. Its
// errors and warnings come back by
// longjmp to the function that called into it; as OpenImageIO does, a
// warning (corrupt data, a premature end of file) fails the read, and
// nothing is printed on stderr.
// jpeglib.h needs size_t and FILE declared before it.
#include <cstddef>
#include <cstdio>

#include <jpeglib.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "image_codecs.hpp"
#include "prism/cancel.hpp"

namespace prism::codec {

namespace {

struct JpegErrors {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void on_jpeg_error(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  info->err->format_message(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void on_jpeg_message(j_common_ptr info, int level) {
  if (level < 0) on_jpeg_error(info);  // a warning: the data is corrupt
}

// A progressive file is read whole inside jpeg_start_decompress: the stop
// request is checked between its passes and scans.
void on_jpeg_progress(j_common_ptr info) {
  if (!cancel_requested()) return;
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  std::snprintf(errors->message, sizeof errors->message, "cancelled");
  std::longjmp(errors->jump, 1);
}

class JpegReader {
 public:
  JpegReader() = default;
  JpegReader(const JpegReader&) = delete;
  JpegReader& operator=(const JpegReader&) = delete;
  ~JpegReader() {
    if (created_) jpeg_destroy_decompress(&info_);
    if (file_) std::fclose(file_);
  }

  void open(const std::filesystem::path& file) {
    file_ = std::fopen(file.c_str(), "rbe");
    if (!file_) throw CodecError(std::strerror(errno));
    info_.err = jpeg_std_error(&errors_.manager);
    errors_.manager.error_exit = on_jpeg_error;
    errors_.manager.emit_message = on_jpeg_message;
    progress_.progress_monitor = on_jpeg_progress;
    if (!read_header()) throw CodecError(errors_.message);
    if (info_.jpeg_color_space == JCS_CMYK || info_.jpeg_color_space == JCS_YCCK)
      throw Unsupported("CMYK JPEG");
    header_.width = int(info_.output_width);
    header_.height = int(info_.output_height);
    header_.channels = info_.output_components;
    header_.channel_names = header_.channels == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
    header_.format = PixelFormat::UInt8;
  }

  const ImageFile& header() const { return header_; }

  void read(int max_channels, const RowSink& sink) {
    const int channels = std::min(header_.channels, max_channels);
    ImageFile shape = header_;
    shape.channels = channels;
    shape.channel_names.resize(size_t(channels));
    sink.header(shape);
    throw_if_cancelled();
    if (!start()) {
      throw_if_cancelled();
      throw CodecError(std::string("cannot decode: ") + errors_.message);
    }
    std::vector<JSAMPLE> row(size_t(header_.width) * size_t(header_.channels));
    std::vector<float> values(size_t(header_.width) * size_t(channels));
    for (int y = 0; y < header_.height; ++y) {
      throw_if_cancelled();
      if (!read_row(row.data())) throw CodecError(std::string("cannot decode: ") + errors_.message);
      for (size_t x = 0; x < size_t(header_.width); ++x)
        for (int c = 0; c < channels; ++c)
          values[x * size_t(channels) + size_t(c)] = float(row[x * size_t(header_.channels) + size_t(c)]) * (1.0f / 255.0f);
      sink.row(y, values.data());
    }
  }

 private:
  bool read_header() {
    if (setjmp(errors_.jump)) return false;
    jpeg_create_decompress(&info_);
    created_ = true;
    info_.progress = &progress_;
    jpeg_stdio_src(&info_, file_);
    jpeg_read_header(&info_, TRUE);
    if (info_.jpeg_color_space != JCS_GRAYSCALE) info_.out_color_space = JCS_RGB;
    jpeg_calc_output_dimensions(&info_);
    return true;
  }

  bool start() {
    if (setjmp(errors_.jump)) return false;
    jpeg_start_decompress(&info_);
    return true;
  }

  bool read_row(JSAMPLE* row) {
    if (setjmp(errors_.jump)) return false;
    JSAMPROW rows[1] = {row};
    if (jpeg_read_scanlines(&info_, rows, 1) == 1) return true;
    std::snprintf(errors_.message, sizeof errors_.message, "no image data");
    return false;
  }

  FILE* file_ = nullptr;
  jpeg_decompress_struct info_{};
  JpegErrors errors_{};
  jpeg_progress_mgr progress_{};
  bool created_ = false;
  ImageFile header_;
};

// Compresses 8-bit `codes` (width * height * channels, 1 or 3 channels) into
// `*out` (malloc'ed by libjpeg; the caller frees it, also on failure).
// false with `errors.message` set when libjpeg fails. Only trivial locals
// live across setjmp.
bool compress_jpeg(const ImageFile& image, const unsigned char* codes, int quality, unsigned char** out,
                   unsigned long* size, JpegErrors& errors) {
  jpeg_compress_struct info{};
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = on_jpeg_error;
  errors.manager.emit_message = on_jpeg_message;
  if (setjmp(errors.jump)) {
    jpeg_destroy_compress(&info);
    return false;
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, out, size);
  info.image_width = JDIMENSION(image.width);
  info.image_height = JDIMENSION(image.height);
  info.input_components = image.channels;
  info.in_color_space = image.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  const size_t row = size_t(image.width) * size_t(image.channels);
  while (info.next_scanline < info.image_height) {
    JSAMPROW rows[1] = {const_cast<JSAMPLE*>(codes + size_t(info.next_scanline) * row)};
    jpeg_write_scanlines(&info, rows, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  return true;
}

}  // namespace

void write_jpeg(int fd, const ImageFile& image, int quality) {
  if (image.channels != 1 && image.channels != 3) throw CodecError("JPEG takes 1 or 3 channels, not " + std::to_string(image.channels));
  std::vector<unsigned char> codes(image.pixels.size());
  for (size_t i = 0; i < codes.size(); ++i)
    codes[i] = static_cast<unsigned char>(std::lround(std::clamp(image.pixels[i], 0.0f, 1.0f) * 255.0f));
  unsigned char* compressed = nullptr;
  unsigned long size = 0;
  JpegErrors errors{};
  const bool done = compress_jpeg(image, codes.data(), quality, &compressed, &size, errors);
  // Written in one piece once compressed, so every write is checked here.
  const int error = done ? write_fully(fd, compressed, size) : 0;
  std::free(compressed);
  if (!done) throw CodecError(errors.message);
  if (error) throw CodecError(std::strerror(error));
}

ImageFile read_jpeg_header(const std::filesystem::path& file) {
  JpegReader reader;
  reader.open(file);
  return reader.header();
}

void read_jpeg(const std::filesystem::path& file, int max_channels, const RowSink& sink) {
  JpegReader reader;
  reader.open(file);
  reader.read(max_channels, sink);
}

}  // namespace prism::codec
