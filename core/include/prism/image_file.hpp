// Reading and writing image files (PNG, JPG, EXR, ... through OpenImageIO).
// OpenImageIO and its ~250 dependent libraries take about a second to load,
// so they live in a module (libprism_oiio.so beside libprism_core.so) that is
// loaded the first time an image is read or written: `prism trace`, `list`
// and every run that fails validation before touching an image start fast.
#pragma once

#include <filesystem>
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

// OpenImageIO's comparison of two images (ImageBufAlgo::compare), over every
// channel: errors are absolute differences.
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

// The size, channel count, channel names and format from the file's header,
// without its pixels (`pixels` stays empty). Throws InputError.
ImageFile read_image_header(const std::filesystem::path& file);

// Writes `image` stored as `storage` (PNG: UInt8/UInt16, EXR: Half/Float),
// in place (callers that need atomicity write to a temporary name). Throws RuntimeError.
void write_image_file(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage);

}  // namespace prism
