// Image output through OpenImageIO. Files are written to a temporary name in
// the target folder and renamed when complete, so a failed write never
// leaves a partial file or clobbers an old one.
#pragma once

#include <filesystem>

#include "prism/backend.hpp"

namespace prism {

// .png: 8-bit sRGB of the clamped values; .exr: linear float RGB plus the
// `id` / `path` channels the image carries. Throws InputError for an
// unsupported extension and RuntimeError when the file cannot be written.
void write_image(const Image& image, const std::filesystem::path& file);

// Checked before rendering starts: InputError unless `file` has one of
// `extensions`; RuntimeError unless its folder exists and is writable.
void check_output_path(const std::filesystem::path& file, const std::vector<std::string>& extensions);

// Writes `contents` to `file` atomically (temporary name, then rename).
void write_text_file_atomically(const std::filesystem::path& file, const std::string& contents);

}  // namespace prism
