// Prism's own readers and writers for PNG (libpng), JPEG (libjpeg-turbo) and
// OpenEXR: the formats `prism render` writes and scenes use as textures.
// They start in a millisecond where OpenImageIO's ~250 libraries take half a
// second, so OpenImageIO (libprism_oiio.so) is only loaded for other formats,
// and for variants these readers leave to it (CMYK JPEG, deep EXR). Their results equal OpenImageIO's for the same file:
// the same channel order, the same float values, unassociated alpha.
#pragma once

#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include "prism/image_file.hpp"

namespace prism::codec {

enum class Format { Png, Jpeg, Exr, Other };

// From the file's first bytes; Other when it cannot be read or is none of the three.
Format format_of_file(const std::filesystem::path& file);
// From the extension (.png, .jpg/.jpeg, .exr, any case).
Format format_of_extension(const std::filesystem::path& file);

// Why a file cannot be read or written: the message the caller puts after the file's name.
class CodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// The file is valid but in a variant these readers leave to OpenImageIO.
class Unsupported : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Receives the decoded image one row at a time, top to bottom: `values` holds
// width * channels floats (integer formats scaled to [0, 1]). `header` is
// called once before the first row with the size, channels and format
// (pixels empty); it may throw to stop before anything is decoded.
struct RowSink {
  std::function<void(const ImageFile& header)> header;
  std::function<void(int y, const float* values)> row;
  // Optional (PNG only): 8-bit rows as codes instead of `row` (ImageRowSink::codes8).
  std::function<void(int y, const unsigned char* codes)> codes8 = {};
};

// Headers only; CodecError / Unsupported. OpenEXR's libraries cost a
// process some 5 ms of start-up, so the EXR functions load them on first
// use from libprism_exr.so (beside libprism_core.so).
ImageFile read_png_header(const std::filesystem::path& file);
ImageFile read_jpeg_header(const std::filesystem::path& file);
ImageFile read_exr_header(const std::filesystem::path& file);

// Decodes rows into `sink`, at most `max_channels` channels per pixel (the
// first ones in OpenImageIO's order). The sink checks the stop request.
void read_png(const std::filesystem::path& file, int max_channels, const RowSink& sink);
void read_jpeg(const std::filesystem::path& file, int max_channels, const RowSink& sink);
void read_exr(const std::filesystem::path& file, int max_channels, const RowSink& sink);

// Write `image` to the open file descriptor `fd` (not closed; every write is
// checked). PNG: UInt8 or UInt16, values round(v * max) of v clamped to [0, 1],
// fastest zlib level. EXR: Half or Float, zip compression, the image's channel names.
void write_png(int fd, const ImageFile& image, PixelFormat storage);
// PNG from rows the caller quantises: `row(y, samples)` fills row y's
// width * channels samples as the file stores them (8-bit codes, or 16-bit
// big-endian), called in parallel for different rows. A rendering writes its
// sRGB codes straight from its linear floats this way, without a float copy
// of the image quantised a second time.
struct PngRows {
  int width = 0, height = 0, channels = 0;
  bool sixteen = false;
  std::function<void(int y, unsigned char* samples)> row;
};
void write_png(int fd, const PngRows& rows);
void write_exr(int fd, const ImageFile& image, PixelFormat storage);
// JPEG (1 or 3 channels): the values' 8-bit codes, as PNG stores them, at
// libjpeg's `quality` (1 to 100).
void write_jpeg(int fd, const ImageFile& image, int quality);
// Radiance RGBE (.hdr) of the first three channels, linear values, scanlines
// uncompressed (a reader tells them from run-length ones).
void write_hdr(int fd, const ImageFile& image);

// Writes all of `size` bytes to `fd`, retrying short writes: 0, or the errno
// of the failure. Inline: libprism_exr.so uses it too.
inline int write_fully(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return EIO;
    bytes += n;
    size -= size_t(n);
  }
  return 0;
}
// The same, throwing CodecError with the system's message.
void write_all(int fd, const void* data, size_t size);

// The table libprism_exr.so exports. Each function returns "" or the error;
// `unsupported` says the file is valid but left to OpenImageIO.
struct ExrModule {
  std::string (*read_header)(const std::filesystem::path& file, ImageFile& out, bool& unsupported);
  std::string (*read)(const std::filesystem::path& file, int max_channels, const RowSink& sink, bool& unsupported);
  std::string (*write)(int fd, const ImageFile& image, PixelFormat storage);
};

// dlopen()s `file_name` from beside libprism_core.so (build and install
// trees alike) and calls its entry `symbol`; RuntimeError when it cannot.
const void* load_core_module(const std::string& file_name, const char* symbol);

}  // namespace prism::codec

extern "C" {
typedef const prism::codec::ExrModule* (*PrismExrModuleFn)(void);
#define PRISM_EXR_MODULE_SYMBOL "prism_exr_module"
}
