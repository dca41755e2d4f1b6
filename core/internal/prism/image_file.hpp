// Reading and writing image files. PNG, JPEG and OpenEXR go through libpng,
// libjpeg-turbo and OpenEXR directly. Every other format, and comparisons,
// go through OpenImageIO, whose ~250 dependent libraries take more than half
// a second to load: it lives in a module (libprism_oiio.so beside
// libprism_core.so) loaded the first time it is needed, so `prism render` to
// PNG or EXR, `trace` and `list` never load it.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace prism {

enum class PixelFormat { UInt8, UInt16, Half, Float, Other };

struct ImageFile {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::string> channel_names;  // empty: the format's defaults
  PixelFormat format = PixelFormat::Float;  // as stored in the file
  std::vector<float> pixels;  // width * height * channels; integer formats scaled to [0, 1]
};

// A comparison of two images over every channel: errors are absolute
// differences, summed in double. The figures are ImageBufAlgo::compare's for
// finite images (tested against it); computed here, so a comparison does not
// load OpenImageIO's libraries.
struct ImageComparison {
  double mean_error = 0, rms_error = 0, psnr = 0, max_error = 0;
  int max_x = 0, max_y = 0, max_channel = 0;  // where the largest error is
  long pixels_over = 0;  // pixels with a channel differing by more than the threshold
};

// Compares two images of the same size and channel count. Throws InputError
// when they do not match.
ImageComparison compare_image_files(const ImageFile& a, const ImageFile& b, float threshold);

// Reads every pixel as float, alpha unassociated (never premultiplied).
// Refuses images over `max_pixels`; keeps the first `max_channels` channels
// only (so memory is bounded however many an EXR holds). Throws InputError.
ImageFile read_image_file(const std::filesystem::path& file, size_t max_pixels = size_t(1) << 28,
                          int max_channels = std::numeric_limits<int>::max());

// An 8-bit code's value as every reader here gives it (OpenImageIO's
// conversion: the code times 1 / 255, in float).
inline float code8_value(unsigned code) { return float(code) * (1.0f / 255.0f); }

// Receives a decoded image one row at a time, top to bottom (see read_image_rows).
struct ImageRowSink {
  // Once, before the first row: size, channels, names and format (no pixels).
  std::function<void(const ImageFile& header)> header;
  // `values`: width * channels floats, integer formats scaled to [0, 1].
  std::function<void(int y, const float* values)> row;
  // Optional: for an 8-bit PNG, the rows as their width * channels codes
  // instead of `row` (each code's value is code8_value of it), so that a
  // sink that maps codes through a table skips the floats.
  std::function<void(int y, const unsigned char* codes)> codes8 = {};
};

// read_image_file without the whole image in memory: refuses images over
// `max_pixels` from their header, then hands the rows to `sink` as they are
// decoded, checking the stop request (prism::cancel) as it goes. Throws
// InputError, or what the sink throws.
void read_image_rows(const std::filesystem::path& file, size_t max_pixels, int max_channels, const ImageRowSink& sink);

// The size, channel count, channel names and format from the file's header,
// without its pixels (`pixels` stays empty). Throws InputError.
ImageFile read_image_header(const std::filesystem::path& file);

// Writes `image` stored as `storage` (PNG: UInt8/UInt16, EXR: Half/Float),
// atomically (see write_file_atomically in image_io.hpp). Throws RuntimeError.
void write_image_file(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage);

// Whether OpenImageIO (libprism_oiio.so or libOpenImageIO) is mapped into
// this process, from /proc/self/maps: `prism render --stats` reports it.
bool openimageio_loaded();

}  // namespace prism
