// The table libprism_oiio.so exports; internal to the core (same build, so
// C++ types may cross it).
#pragma once

#include <string>

#include "prism/image_file.hpp"

namespace prism {

struct ImageModule {
  // Return an empty string on success, else the reason.
  // Reads the first `max_channels` channels at most.
  std::string (*read)(const std::filesystem::path& file, size_t max_pixels, int max_channels, ImageFile& out);
  // The size, channels and format from the file's header; no pixels.
  std::string (*read_header)(const std::filesystem::path& file, ImageFile& out);
  std::string (*write)(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage);
};

// Writes `image` to `file` (by name; the extension picks the format) with
// OpenImageIO, loading libprism_oiio.so the first time: "" or the reason.
std::string write_with_openimageio(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage);

}  // namespace prism

extern "C" {
typedef const prism::ImageModule* (*PrismImageModuleFn)(void);
#define PRISM_IMAGE_MODULE_SYMBOL "prism_image_module"
}
