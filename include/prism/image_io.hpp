// Image and text output. Every file is written to a temporary name beside
// its target, checked write by write, flushed to disk (fsync) and only then
// renamed over the target: a failed write (a full disk, a cancel request)
// never leaves a partial file or clobbers an old one, and the error names
// the file the caller asked for. Replacing a file keeps its permissions; a
// symbolic link is written through (the temporary goes beside the link's
// target and replaces the target), as cp does.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "prism/backend.hpp"

namespace prism {

// A file completely written (and fsynced) under a temporary name, not yet in
// place: stage several, then commit them together, so a failure while
// writing the second leaves the first's older file as it was.
class StagedFile {
 public:
  // Calls `write(temporary, fd)` to fill the temporary (fd is open for
  // writing; `write` may instead write by name, in place). RuntimeError
  // naming `file` when anything fails; nothing is left behind then.
  StagedFile(const std::filesystem::path& file,
             const std::function<void(const std::filesystem::path& temporary, int fd)>& write);
  StagedFile(StagedFile&& other) noexcept;
  StagedFile& operator=(StagedFile&&) = delete;
  StagedFile(const StagedFile&) = delete;
  ~StagedFile();  // removes the temporary unless it was committed

  // Renames the temporary over the target. Throws Cancelled when a stop was
  // requested (the older file stays), RuntimeError when the rename fails.
  void commit();

 private:
  std::filesystem::path file_, target_, temporary_;
  bool committed_ = false;
  // The temporary's slot in the list the signal deadline removes (cancel.hpp).
  int deadline_slot_ = -1;
};

// .png: 8-bit sRGB of the clamped values; .exr: linear float RGB plus the
// `id` / `path` channels the image carries; .jpg/.jpeg (quality 95) and
// .tif/.tiff: the same 8-bit codes as PNG; .hdr: linear RGB as Radiance
// RGBE. All through Prism's own writers but TIFF, which goes through
// OpenImageIO (loaded then). Throws InputError for an unsupported extension
// and RuntimeError when the file cannot be written.
void write_image(const Image& image, const std::filesystem::path& file);
StagedFile stage_image(const Image& image, const std::filesystem::path& file);

// The extensions write_image takes (lower case; any case is accepted).
const std::vector<std::string>& image_output_extensions();

// Writes `image` as the PNG write_image would to the open file descriptor
// `fd` (not closed): `prism render -o -` to standard output. RuntimeError
// naming `name` when a write fails.
void write_png_to(const Image& image, int fd, const std::string& name);

// Checked before rendering starts: InputError unless `file` has one of
// `extensions`; RuntimeError unless its folder exists and is writable.
void check_output_path(const std::filesystem::path& file, const std::vector<std::string>& extensions);

// Writes `contents` to `file` atomically (temporary name, then rename).
void write_text_file_atomically(const std::filesystem::path& file, const std::string& contents);
StagedFile stage_text_file(const std::filesystem::path& file, const std::string& contents);

// StagedFile(file, write).commit().
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<void(const std::filesystem::path& temporary, int fd)>& write);

}  // namespace prism
