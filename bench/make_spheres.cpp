// Writes a Prism scene of N spheres (default 100,000) on a jittered cubic
// grid, for benchmarks: prism_make_spheres [-n COUNT] [-s SEED] -o FILE.json
// The output depends only on COUNT and SEED (bench/spheres_scene.hpp).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "spheres_scene.hpp"

namespace {

int usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [-n COUNT] [-s SEED] -o FILE.json\n", argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  long count = 100000;
  uint64_t seed = 1;
  const char* path = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (i + 1 < argc && std::strcmp(argv[i], "-n") == 0) {
      count = std::strtol(argv[++i], nullptr, 10);
    } else if (i + 1 < argc && std::strcmp(argv[i], "-s") == 0) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (i + 1 < argc && std::strcmp(argv[i], "-o") == 0) {
      path = argv[++i];
    } else {
      return usage(argv[0]);
    }
  }
  if (path == nullptr || count < 1 || count > 10000000) return usage(argv[0]);
  const std::string text = prism::bench_tools::spheres_scene_json(count, seed);
  std::FILE* out = std::fopen(path, "w");
  if (out == nullptr) {
    std::perror(path);
    return 1;
  }
  const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size();
  if (std::fclose(out) != 0 || !written) {
    std::perror(path);
    return 1;
  }
  return 0;
}
