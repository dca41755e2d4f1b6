// The on-disk cache folder both GPU backends keep compiled kernels in, and
// the file handling around it. What goes in a cache file (a GL program
// binary, SPIR-V with a Vulkan pipeline cache) is each backend's own.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace prism::gpu {

// $PRISM_CACHE_DIR/<api>, else $XDG_CACHE_HOME/prism/<api>, else
// ~/.cache/prism/<api>. Empty when none can be named.
std::filesystem::path program_cache_dir(const std::string& api);

// A cache file larger than this is not read (a miss): GL program binaries
// and SPIR-V with its pipeline cache are a few MiB.
inline constexpr std::uintmax_t kMaxCacheFileBytes = std::uintmax_t(256) << 20;

// The file's bytes, or nothing when it cannot be read, is not a regular
// file or is larger than kMaxCacheFileBytes (a cache miss).
std::optional<std::string> read_cache_file(const std::filesystem::path& file);

// Writes the file atomically; a cache that cannot be written only costs the
// next run a compile, so failures are ignored.
void write_cache_file(const std::filesystem::path& file, const std::string& bytes);

// The notice before a compile, with why, from the kernel's cache state
// ("miss", "stale", "corrupt", "disabled", "unsupported"): "compiling the
// opengl kernel for this scene (cached afterwards)…".
std::string compile_notice(const std::string& backend, const std::string& cache_state);

// Keeps the generated source of a kernel that failed to build where the user
// can read it (the cache folder, else the temporary folder) and returns the
// file name, or "(not saved)".
std::string save_failed_source(const std::string& api, const std::string& source, const std::string& key);

}  // namespace prism::gpu
