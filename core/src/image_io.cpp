#include "prism/image_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/image_file.hpp"
#include "prism/texture.hpp"

namespace fs = std::filesystem;

namespace prism {

namespace {

std::string lower_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// A temporary name beside `file` (same folder, so the rename is atomic),
// keeping the extension so OpenImageIO picks the right writer. Appended
// piece by piece: GCC 12 at -O3 misreports `"." + string` as overlapping
// memory (-Wrestrict, GCC bug 105329).
fs::path temporary_name(const fs::path& file) {
  // pid and a counter: two threads writing the same target (two renders,
  // two kernel caches) must not share a temporary file.
  static std::atomic<unsigned> serial{0};
  std::string name = ".";
  name += file.stem().string();
  name += ".tmp" + std::to_string(::getpid());
  name += "-" + std::to_string(serial++);
  name += file.extension().string();
  return file.parent_path() / name;
}

// Runs `write` on a temporary file, then renames it over `file`; on any
// failure (or a cancel request) the temporary is removed and `file` is untouched.
template <typename WriteFn>
void write_atomically(const fs::path& file, WriteFn write) {
  const fs::path tmp = temporary_name(file);
  // Known to prism's deadline handler, which removes it if a signal's grace period runs out.
  struct Registered {
    int slot;
    ~Registered() { unregister_temporary_file(slot); }
  } registered{register_temporary_file(tmp.c_str())};
  try {
    write(tmp);
    // An interrupted run leaves the older file as it was, even when the
    // request came in while this one was being written.
    throw_if_cancelled();
    std::error_code ec;
    fs::rename(tmp, file, ec);
    if (ec) throw RuntimeError("cannot write " + file.string() + ": " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

// Creates and removes the temporary file the write will use: access() alone
// passes where the write later fails (root, read-only mounts, /proc).
void probe_temporary(const fs::path& file) {
  const fs::path tmp = temporary_name(file);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    if (error == EEXIST) return;  // a stale file of that name: the folder takes files
    throw RuntimeError(file.string() + ": cannot create a file in its folder: " + std::strerror(error));
  }
  ::close(fd);
  ::unlink(tmp.c_str());
}

void write_png(const Image& image, const fs::path& path) {
  ImageFile file{image.width, image.height, 3, {}, PixelFormat::UInt8, {}};
  file.pixels.resize(image.rgb.size());
  for (size_t i = 0; i < file.pixels.size(); ++i) {
    // round(255 * oetf(clamp(v))) exactly, so the writer's own quantisation is a no-op.
    double v = std::clamp(double(image.rgb[i]), 0.0, 1.0);
    file.pixels[i] = static_cast<float>(std::lround(255.0 * linear_to_srgb(v)) / 255.0);
  }
  write_image_file(path, file, PixelFormat::UInt8);
}

void write_exr(const Image& image, const fs::path& path) {
  std::vector<std::string> names = {"R", "G", "B"};
  if (!image.id.empty()) names.push_back("id");
  if (!image.path.empty()) names.push_back("path");
  const size_t channels = names.size(), pixels = size_t(image.width) * image.height;
  ImageFile file{image.width, image.height, int(channels), names, PixelFormat::Float, {}};
  file.pixels.resize(pixels * channels);
  for (size_t p = 0; p < pixels; ++p) {
    float* out = &file.pixels[p * channels];
    std::copy_n(&image.rgb[p * 3], 3, out);
    size_t c = 3;
    if (!image.id.empty()) out[c++] = image.id[p];
    if (!image.path.empty()) out[c++] = image.path[p];
  }
  write_image_file(path, file, PixelFormat::Float);
}

}  // namespace

void check_output_path(const fs::path& file, const std::vector<std::string>& extensions) {
  const std::string ext = lower_extension(file);
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
    std::string list;
    for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
    throw InputError(file.string() + ": unsupported output type '" + ext + "' (expected " + list + ")");
  }
  fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  std::error_code ec;
  // An output that cannot be written is a run-time failure (exit 1) in the
  // format's terms, but it is found here, before any rendering.
  if (!fs::is_directory(folder, ec)) throw RuntimeError(file.string() + ": folder " + folder.string() + " does not exist");
  if (::access(folder.c_str(), W_OK) != 0)
    throw RuntimeError(file.string() + ": folder " + folder.string() + " is not writable");
  if (fs::is_directory(file, ec)) throw RuntimeError(file.string() + ": is a folder");
  probe_temporary(file);
}

void write_image(const Image& image, const fs::path& file) {
  const std::string ext = lower_extension(file);
  if (ext != ".png" && ext != ".exr") throw InputError(file.string() + ": unsupported output type '" + ext + "'");
  write_atomically(file, [&](const fs::path& tmp) { ext == ".png" ? write_png(image, tmp) : write_exr(image, tmp); });
}

void write_text_file_atomically(const fs::path& file, const std::string& contents) {
  write_atomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << contents;
    out.close();
    if (!out) throw RuntimeError("cannot write " + file.string());
  });
}

}  // namespace prism
