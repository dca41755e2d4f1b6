#include "program_cache.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>

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
  // Only a regular file (a link is followed) of a plausible size: a folder,
  // a device (/dev/zero) or a 2 GB file at an entry's name is a miss, and
  // the program is compiled again.
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::is_regular_file(status)) return std::nullopt;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec || size > kMaxCacheFileBytes) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes(size_t(size), '\0');
  in.read(bytes.data(), std::streamsize(size));
  if (size_t(in.gcount()) != size || in.peek() != std::char_traits<char>::eof()) return std::nullopt;  // it changed
  return bytes;
}

void write_cache_file(const fs::path& file, const std::string& bytes) {
  try {
    fs::create_directories(file.parent_path());
    write_text_file_atomically(file, bytes);
  } catch (const std::exception& e) {
    // The render goes on without the cache, but say so once: silence would
    // leave every later run compiling again with nobody knowing why.
    static std::once_flag warned;
    std::call_once(warned, [&] {
      std::fprintf(stderr, "prism: warning: the program cache is not written (%s); kernels are compiled on every run\n",
                   e.what());
    });
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

namespace {
std::string compile_reason(const std::string& cache_state) {
  if (cache_state == "miss") return "cached afterwards";
  if (cache_state == "stale") return "the driver changed since it was cached; cached afterwards";
  if (cache_state == "corrupt") return "its program-cache entry was damaged; cached afterwards";
  if (cache_state == "unsupported") return "the driver keeps no compiled programs";
  return "no program cache";
}
}  // namespace

std::string compile_notice(const std::string& backend, const std::string& cache_state) {
  return "compiling the " + backend + " kernel for this scene (" + compile_reason(cache_state) + ")\u2026";
}

}  // namespace prism::gpu
