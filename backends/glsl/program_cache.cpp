#include "program_cache.hpp"

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "prism/image_io.hpp"

namespace prism::gpu {

namespace fs = std::filesystem;

fs::path program_cache_dir(const std::string& api) {
  if (const char* dir = std::getenv("PRISM_CACHE_DIR"); dir && *dir) return fs::path(dir) / api;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "prism" / api;
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "prism" / api;
  return {};
}

std::optional<std::string> read_cache_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_cache_file(const fs::path& file, const std::string& bytes) {
  try {
    fs::create_directories(file.parent_path());
    write_text_file_atomically(file, bytes);
  } catch (const std::exception&) {
  }
}

std::string save_failed_source(const std::string& api, const std::string& source, const std::string& key) {
  fs::path dir = program_cache_dir(api);
  if (dir.empty()) dir = fs::temp_directory_path();
  const fs::path file = dir / ("failed-" + key + ".comp");
  try {
    fs::create_directories(dir);
    write_text_file_atomically(file, source);
    return file.string();
  } catch (const std::exception&) {
    return "(not saved)";
  }
}

}  // namespace prism::gpu
