// Writes a Prism scene of N spheres (default 100,000) on a jittered cubic
// grid, for benchmarks: prism_make_spheres [-n COUNT] [-s SEED] -o FILE.json
// The output depends only on COUNT and SEED (own RNG, fixed formatting).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

// splitmix64: tiny, portable, good enough for placing spheres.
struct Rng {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1p-53; }
};

int usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [-n COUNT] [-s SEED] -o FILE.json\n", argv0);
  return 2;
}

void write_header(std::FILE* out, double half) {
  std::fprintf(out,
               "{\n  \"prism\": 1,\n"
               "  \"camera\": {\"position\": [%.9g, %.9g, %.9g], \"look_at\": [0, 0, 0], \"fov_y\": 50},\n"
               "  \"image\": {\"width\": 640, \"height\": 360, \"spp\": 1, \"max_depth\": 4},\n"
               "  \"background\": {\"color\": [0.05, 0.07, 0.12]},\n"
               "  \"ambient\": [0.04, 0.04, 0.04],\n"
               "  \"materials\": {\n"
               "    \"red\": {\"color\": [0.8, 0.2, 0.15], \"specular\": 0.3},\n"
               "    \"green\": {\"color\": [0.2, 0.7, 0.3]},\n"
               "    \"blue\": {\"color\": [0.2, 0.3, 0.85], \"specular\": 0.5, \"shininess\": 64},\n"
               "    \"mirror\": {\"color\": [0.9, 0.9, 0.9], \"reflect\": 0.6}\n"
               "  },\n"
               "  \"lights\": [\n"
               "    {\"type\": \"point\", \"position\": [%.9g, %.9g, %.9g], \"intensity\": 0.9},\n"
               "    {\"type\": \"directional\", \"direction\": [-0.3, -1, 0.4], \"intensity\": 0.4}\n"
               "  ],\n"
               "  \"objects\": [\n",
               -1.5 * half, 1.1 * half, -2.7 * half, 1.5 * half, 3.0 * half, -2.0 * half);
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

  // Cells of side 2 on a cube of `side`^3 cells, filled x, then z, then y.
  const long side = static_cast<long>(std::ceil(std::cbrt(static_cast<double>(count)) - 1e-9));
  const double half = static_cast<double>(side);  // the grid spans [-side, side]
  const char* materials[] = {"red", "green", "blue", "mirror"};
  std::FILE* out = std::fopen(path, "w");
  if (out == nullptr) {
    std::perror(path);
    return 1;
  }
  write_header(out, half);
  Rng rng{seed};
  for (long i = 0; i < count; ++i) {
    const long x = i % side, z = (i / side) % side, y = i / (side * side);
    const double cx = 2.0 * x - half + 1 + rng.uniform(-0.4, 0.4);
    const double cy = 2.0 * y - half + 1 + rng.uniform(-0.4, 0.4);
    const double cz = 2.0 * z - half + 1 + rng.uniform(-0.4, 0.4);
    const double radius = rng.uniform(0.2, 0.6);
    std::fprintf(out, "    {\"type\": \"sphere\", \"center\": [%.6f, %.6f, %.6f], \"radius\": %.6f, \"material\": \"%s\"}%s\n",
                 cx, cy, cz, radius, materials[rng.next() % 4], i + 1 < count ? "," : "");
  }
  std::fprintf(out, "  ]\n}\n");
  if (std::fclose(out) != 0) {
    std::perror(path);
    return 1;
  }
  return 0;
}
