#include "prism/image_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "image_codecs.hpp"
#include "image_module.hpp"
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

// The file a write replaces: `file`, or the end of the chain of symbolic
// links it names (a dangling link's target too), so the link stays a link.
// Only a regular file (or nothing yet) is written through a link: a link to
// a device, a FIFO or a folder (a cache entry pointing at /dev/zero) is
// itself replaced, so a write never renames a file over /dev/zero.
fs::path write_target(const fs::path& file) {
  fs::path target = file;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(target, ec))) {
      const fs::file_status status = fs::status(target, ec);
      return !fs::exists(status) || fs::is_regular_file(status) ? target : file;
    }
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) return target;
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  throw RuntimeError("cannot write " + file.string() + ": too many levels of symbolic links");
}

[[noreturn]] void fail_writing(const fs::path& file, int error) {
  throw RuntimeError("cannot write " + file.string() + ": " + std::strerror(error));
}

// A replaced file keeps its permission bits (not its owner: that needs root).
void keep_mode(const fs::path& target, int fd, const fs::path& file) {
  struct stat old {};
  if (::stat(target.c_str(), &old) != 0 || !S_ISREG(old.st_mode)) return;
  if (::fchmod(fd, old.st_mode & 07777) != 0) fail_writing(file, errno);
}

// Creates and removes the temporary file the write will use: access() alone
// passes where the write later fails (root, read-only mounts, /proc).
void probe_temporary(const fs::path& file) {
  const fs::path tmp = temporary_name(write_target(file));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    if (error == EEXIST) return;  // a stale file of that name: the folder takes files
    throw RuntimeError(file.string() + ": cannot create a file in its folder: " + std::strerror(error));
  }
  ::close(fd);
  ::unlink(tmp.c_str());
}

// libjpeg's scale: 95 keeps a rendering's edges and gradients visibly intact.
constexpr int kJpegQuality = 95;

// round(255 * oetf(clamp(v))) of each value, the 8-bit sRGB code.
void srgb8_codes(const float* linear, size_t count, unsigned char* codes) {
  for (size_t i = 0; i < count; ++i) codes[i] = linear_to_srgb8(linear[i]);
}

ImageFile png_pixels(const Image& image) {
  ImageFile file{image.width, image.height, 3, {}, PixelFormat::UInt8, {}};
  file.pixels.resize(image.rgb.size());
  // In parallel: a 1280x720 frame's 2.8 M values took ~15 ms on one thread.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, file.pixels.size(), 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      // The code over 255, so the writer's own quantisation gives the code back.
      file.pixels[i] = static_cast<float>(linear_to_srgb8(image.rgb[i]) / 255.0);
    }
  });
  return file;
}

// The rendering as PNG rows: its sRGB codes, quantised once, row by row as
// the writer filters them (no float copy of the image).
codec::PngRows png_rows(const Image& image) {
  const size_t values = size_t(image.width) * 3;
  return {image.width, image.height, 3, false,
          [&image, values](int y, unsigned char* samples) { srgb8_codes(&image.rgb[size_t(y) * values], values, samples); }};
}

ImageFile exr_pixels(const Image& image) {
  std::vector<std::string> names = {"R", "G", "B"};
  if (!image.id.empty()) names.push_back("id");
  if (!image.path.empty()) names.push_back("path");
  if (!image.depth.empty()) names.push_back("Z");  // EXR's name for depth
  if (!image.normal.empty()) names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
  if (!image.albedo.empty()) names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B"});
  const size_t channels = names.size(), pixels = size_t(image.width) * image.height;
  ImageFile file{image.width, image.height, int(channels), names, PixelFormat::Float, {}};
  file.pixels.resize(pixels * channels);
  for (size_t p = 0; p < pixels; ++p) {
    float* out = &file.pixels[p * channels];
    std::copy_n(&image.rgb[p * 3], 3, out);
    size_t c = 3;
    if (!image.id.empty()) out[c++] = image.id[p];
    if (!image.path.empty()) out[c++] = image.path[p];
    if (!image.depth.empty()) out[c++] = image.depth[p];
    if (!image.normal.empty()) {
      std::copy_n(&image.normal[p * 3], 3, out + c);
      c += 3;
    }
    if (!image.albedo.empty()) std::copy_n(&image.albedo[p * 3], 3, out + c);
  }
  return file;
}

// The nearest folder above `file` that exists, for the message about a missing one.
fs::path nearest_existing(fs::path folder) {
  std::error_code ec;
  while (!folder.empty() && !fs::exists(fs::symlink_status(folder, ec))) {
    if (folder == folder.parent_path()) break;
    folder = folder.parent_path();
  }
  return folder;
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
  if (!fs::is_directory(folder, ec)) {
    // "a/b.png" where "a" is a file: "a" is not a folder (it exists).
    const fs::path existing = nearest_existing(folder);
    if (!existing.empty() && !fs::is_directory(existing, ec))
      throw RuntimeError(file.string() + ": " + existing.string() + " is not a folder");
    throw RuntimeError(file.string() + ": folder " + folder.string() + " does not exist");
  }
  if (::access(folder.c_str(), W_OK) != 0)
    throw RuntimeError(file.string() + ": folder " + folder.string() + " is not writable");
  if (fs::is_directory(file, ec)) throw RuntimeError(file.string() + ": is a folder");
  probe_temporary(file);
}

StagedFile::StagedFile(const fs::path& file, const std::function<void(const fs::path&, int)>& write)
    : file_(file), target_(write_target(file)), temporary_(temporary_name(target_)) {
  // Known to prism's deadline handler, which removes it if a signal's grace period runs out.
  deadline_slot_ = register_temporary_file(temporary_.c_str());
  const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    unregister_temporary_file(deadline_slot_);
    fail_writing(file_, error);
  }
  try {
    keep_mode(target_, fd, file_);
    try {
      write(temporary_, fd);
    } catch (const codec::CodecError& e) {
      throw RuntimeError("cannot write " + file_.string() + ": " + e.what());
    }
    // On disk before it replaces anything: a crash or a full disk found
    // only at write-back must not leave an empty file under the old name.
    if (::fsync(fd) != 0) fail_writing(file_, errno);
  } catch (...) {
    ::close(fd);
    std::error_code ignored;
    fs::remove(temporary_, ignored);
    unregister_temporary_file(deadline_slot_);
    throw;
  }
  if (::close(fd) != 0) {
    const int error = errno;
    std::error_code ignored;
    fs::remove(temporary_, ignored);
    unregister_temporary_file(deadline_slot_);
    fail_writing(file_, error);
  }
}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : file_(std::move(other.file_)), target_(std::move(other.target_)), temporary_(std::move(other.temporary_)),
      committed_(other.committed_), deadline_slot_(other.deadline_slot_) {
  other.committed_ = true;  // the moved-from object owns no temporary
  other.deadline_slot_ = -1;
}

StagedFile::~StagedFile() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
  }
  unregister_temporary_file(deadline_slot_);
}

void StagedFile::commit() {
  // An interrupted run leaves the older file as it was, even when the
  // request came in while this one was being written.
  throw_if_cancelled();
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) fail_writing(file_, errno);
  // The folder is not synced: after a crash the name holds the old file or
  // the new one, both whole, and that sync would cost a render ~5 ms.
  committed_ = true;
}

void write_file_atomically(const fs::path& file, const std::function<void(const fs::path&, int)>& write) {
  StagedFile(file, write).commit();
}

const std::vector<std::string>& image_output_extensions() {
  static const std::vector<std::string> extensions = {".png", ".exr", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr"};
  return extensions;
}

StagedFile stage_image(const Image& image, const fs::path& file) {
  const std::string ext = lower_extension(file);
  const auto& known = image_output_extensions();
  if (std::find(known.begin(), known.end(), ext) == known.end())
    throw InputError(file.string() + ": unsupported output type '" + ext + "'");
  return StagedFile(file, [&](const fs::path& temporary, int fd) {
    if (ext == ".png") return codec::write_png(fd, png_rows(image));
    if (ext == ".exr") return codec::write_exr(fd, exr_pixels(image), PixelFormat::Float);
    if (ext == ".jpg" || ext == ".jpeg") return codec::write_jpeg(fd, png_pixels(image), kJpegQuality);
    if (ext == ".hdr") return codec::write_hdr(fd, exr_pixels(image));
    // TIFF through OpenImageIO (libtiff reports failed writes), which writes
    // the temporary by its name: it keeps the extension, so OpenImageIO
    // picks the format. The error names the file asked for.
    const std::string error = write_with_openimageio(temporary, png_pixels(image), PixelFormat::UInt8);
    if (!error.empty()) throw RuntimeError("cannot write " + file.string() + ": " + error);
  });
}

void write_png_to(const Image& image, int fd, const std::string& name) {
  try {
    codec::write_png(fd, png_rows(image));
  } catch (const codec::CodecError& e) {
    throw RuntimeError("cannot write " + name + ": " + e.what());
  }
}

void write_image(const Image& image, const fs::path& file) { stage_image(image, file).commit(); }

StagedFile stage_text_file(const fs::path& file, const std::string& contents) {
  return StagedFile(file, [&](const fs::path&, int fd) { codec::write_all(fd, contents.data(), contents.size()); });
}

void write_text_file_atomically(const fs::path& file, const std::string& contents) {
  stage_text_file(file, contents).commit();
}

}  // namespace prism
