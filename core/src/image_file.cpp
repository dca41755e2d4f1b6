#include "prism/image_file.hpp"

#include <dlfcn.h>

#include <mutex>

#include "image_module.hpp"
#include "prism/errors.hpp"

namespace prism {

namespace {

// libprism_oiio.so lives beside libprism_core.so (build and install trees alike).
std::filesystem::path module_path() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&read_image_file), &info) && info.dli_fname)
    return std::filesystem::path(info.dli_fname).parent_path() / "libprism_oiio.so";
  return "libprism_oiio.so";
}

const ImageModule& image_module() {
  static std::once_flag once;
  static const ImageModule* module = nullptr;
  static std::string error;
  std::call_once(once, [] {
    const std::filesystem::path path = module_path();
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept for the life of the process
    if (!handle) {
      const char* why = dlerror();
      error = "cannot load image support " + path.string() + ": " + (why ? why : "dlopen failed");
      return;
    }
    auto entry = reinterpret_cast<PrismImageModuleFn>(dlsym(handle, PRISM_IMAGE_MODULE_SYMBOL));
    if (!entry) error = "cannot load image support: " + path.string() + " has no " + PRISM_IMAGE_MODULE_SYMBOL;
    else module = entry();
  });
  if (!module) throw RuntimeError(error);
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

ImageFile read_image_file(const std::filesystem::path& file, size_t max_pixels, int max_channels) {
  require_regular_file(file);
  ImageFile image;
  std::string error = image_module().read(file, max_pixels, max_channels, image);
  if (!error.empty()) throw InputError("cannot read image '" + file.string() + "': " + error);
  return image;
}

ImageFile read_image_header(const std::filesystem::path& file) {
  require_regular_file(file);
  ImageFile image;
  std::string error = image_module().read_header(file, image);
  if (!error.empty()) throw InputError("cannot read image '" + file.string() + "': " + error);
  return image;
}

void write_image_file(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage) {
  std::string error = image_module().write(file, image, storage);
  if (!error.empty()) throw RuntimeError("cannot write " + file.string() + ": " + error);
}

ImageComparison compare_image_files(const ImageFile& a, const ImageFile& b, float threshold) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw InputError("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) + "x" +
                     std::to_string(a.channels) + " image with a " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + "x" + std::to_string(b.channels) + " one");
  return image_module().compare(a, b, threshold);
}

}  // namespace prism
