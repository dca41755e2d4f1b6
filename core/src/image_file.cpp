#include "prism/image_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>
#include <cstring>
#include <fstream>

#include "image_codecs.hpp"
#include "image_module.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"

namespace prism {

namespace {

const ImageModule& image_module() {
  static const auto* module = static_cast<const ImageModule*>(codec::load_core_module("libprism_oiio.so", PRISM_IMAGE_MODULE_SYMBOL));
  return *module;
}

// OpenImageIO reads whatever it is given, and some of its format readers
// never finish on an endless stream (its IFF reader spins on /dev/zero); a
// FIFO would block. So only a regular file (or a link to one) is an image.
// A missing file is left to OpenImageIO, whose message says so.
void require_regular_file(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError("cannot read image '" + file.string() + "': not a regular file");
}

}  // namespace

namespace {

std::string pixel_limit_error(const ImageFile& header, size_t max_pixels) {
  const size_t pixels = size_t(header.width) * size_t(header.height);
  if (pixels <= max_pixels) return "";
  return "the image has " + std::to_string(pixels) + " pixels, more than the limit of " + std::to_string(max_pixels);
}

// Through OpenImageIO, for the formats and variants Prism's own readers leave to it.
void read_rows_with_oiio(const std::filesystem::path& file, size_t max_pixels, int max_channels,
                         const ImageRowSink& sink) {
  ImageFile image;
  std::string error = image_module().read(file, max_pixels, max_channels, image);
  if (!error.empty()) throw InputError("cannot read image '" + file.string() + "': " + error);
  std::vector<float> pixels = std::move(image.pixels);
  sink.header(image);
  const size_t row = size_t(image.width) * size_t(image.channels);
  for (int y = 0; y < image.height; ++y) sink.row(y, pixels.data() + size_t(y) * row);
}

void read_rows_natively(codec::Format format, const std::filesystem::path& file, int max_channels,
                        const codec::RowSink& sink) {
  switch (format) {
    case codec::Format::Png: return codec::read_png(file, max_channels, sink);
    case codec::Format::Jpeg: return codec::read_jpeg(file, max_channels, sink);
    default: return codec::read_exr(file, max_channels, sink);
  }
}

ImageFile read_header_natively(codec::Format format, const std::filesystem::path& file) {
  switch (format) {
    case codec::Format::Png: return codec::read_png_header(file);
    case codec::Format::Jpeg: return codec::read_jpeg_header(file);
    default: return codec::read_exr_header(file);
  }
}

// The format from the file's first bytes; a file that cannot be opened is an InputError here.
codec::Format format_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot read image '" + file.string() + "': " + std::strerror(errno));
  return codec::format_of_file(file);
}

}  // namespace

void read_image_rows(const std::filesystem::path& file, size_t max_pixels, int max_channels, const ImageRowSink& sink) {
  require_regular_file(file);
  const codec::Format format = format_of(file);
  if (format != codec::Format::Other) {
    codec::RowSink checked{[&](const ImageFile& header) {
                                   const std::string error = pixel_limit_error(header, max_pixels);
                                   if (!error.empty()) throw codec::CodecError(error);
                                   sink.header(header);
                                 },
                                 [&](int y, const float* values) {
                                   throw_if_cancelled();
                                   sink.row(y, values);
                                 },
                                 {}};
    if (sink.codes8) {
      checked.codes8 = [&](int y, const unsigned char* codes) {
        throw_if_cancelled();
        sink.codes8(y, codes);
      };
    }
    try {
      return read_rows_natively(format, file, max_channels, checked);
    } catch (const codec::CodecError& e) {
      throw InputError("cannot read image '" + file.string() + "': " + e.what());
    } catch (const codec::Unsupported&) {
      // left to OpenImageIO below
    }
  }
  read_rows_with_oiio(file, max_pixels, max_channels, sink);
}

ImageFile read_image_file(const std::filesystem::path& file, size_t max_pixels, int max_channels) {
  ImageFile image;
  size_t row_floats = 0;
  read_image_rows(file, max_pixels, max_channels,
                  {[&](const ImageFile& header) {
                     image = header;
                     row_floats = size_t(header.width) * size_t(header.channels);
                     image.pixels.reserve(row_floats * size_t(header.height));
                   },
                   [&](int, const float* values) { image.pixels.insert(image.pixels.end(), values, values + row_floats); }});
  return image;
}

ImageFile read_image_header(const std::filesystem::path& file) {
  require_regular_file(file);
  const codec::Format format = format_of(file);
  if (format != codec::Format::Other) {
    try {
      return read_header_natively(format, file);
    } catch (const codec::CodecError& e) {
      throw InputError("cannot read image '" + file.string() + "': " + e.what());
    } catch (const codec::Unsupported&) {
      // left to OpenImageIO below
    }
  }
  ImageFile image;
  std::string error = image_module().read_header(file, image);
  if (!error.empty()) throw InputError("cannot read image '" + file.string() + "': " + error);
  return image;
}

void write_image_file(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage) {
  const codec::Format format = codec::format_of_extension(file);
  write_file_atomically(file, [&](const std::filesystem::path& temporary, int fd) {
    try {
      if (format == codec::Format::Png) return codec::write_png(fd, image, storage);
      if (format == codec::Format::Exr) return codec::write_exr(fd, image, storage);
    } catch (const codec::CodecError& e) {
      throw RuntimeError("cannot write " + file.string() + ": " + e.what());
    }
    // OpenImageIO opens the temporary by its name (which keeps the extension, so it picks the writer).
    std::string error = image_module().write(temporary, image, storage);
    if (!error.empty()) throw RuntimeError("cannot write " + file.string() + ": " + error);
  });
}

std::string write_with_openimageio(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage) {
  return image_module().write(file, image, storage);
}

bool openimageio_loaded() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("libprism_oiio.so") != std::string::npos || line.find("libOpenImageIO") != std::string::npos)
      return true;
  return false;
}

namespace {

// One channel's values in both images, folded into the running comparison.
// A non-finite value matches only the same non-finite value (NaN with NaN,
// +inf with +inf); any other pair with one fails its pixel, and its error is
// infinite.
// The difference is a float subtraction and the PSNR's peak is the largest
// magnitude in either image (at least 1), as OpenImageIO's.
struct ComparisonSums {
  double error = 0, squared_error = 0;
  float peak = 1;
};

double channel_error(float a, float b, ComparisonSums& sums) {
  if (std::isfinite(a) && std::isfinite(b)) {
    const double error = std::abs(a - b);
    sums.error += error;
    sums.squared_error += error * error;
    sums.peak = std::max({sums.peak, std::abs(a), std::abs(b)});
    return error;
  }
  const bool same = (std::isnan(a) && std::isnan(b)) || a == b;
  return same ? 0 : std::numeric_limits<double>::infinity();
}

}  // namespace

ImageComparison compare_image_files(const ImageFile& a, const ImageFile& b, float threshold) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw InputError("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) + "x" +
                     std::to_string(a.channels) + " image with a " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + "x" + std::to_string(b.channels) + " one");
  ImageComparison c;
  ComparisonSums sums;
  const size_t pixels = size_t(a.width) * size_t(a.height);
  for (size_t p = 0; p < pixels; ++p) {
    bool over = false;
    for (int channel = 0; channel < a.channels; ++channel) {
      const size_t i = p * size_t(a.channels) + size_t(channel);
      const double error = channel_error(a.pixels[i], b.pixels[i], sums);
      if (error > c.max_error) {  // the first of equal largest errors
        c.max_error = error;
        c.max_x = int(p % size_t(a.width));
        c.max_y = int(p / size_t(a.width));
        c.max_channel = channel;
      }
      over = over || error > double(threshold);
    }
    c.pixels_over += over;
  }
  const double values = double(pixels) * a.channels;
  c.mean_error = sums.error / values;
  c.rms_error = std::sqrt(sums.squared_error / values);
  c.psnr = 20.0 * std::log10(sums.peak / c.rms_error);  // infinite for equal images
  return c;
}

}  // namespace prism
