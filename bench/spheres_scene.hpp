// What the benchmark tools share: a small portable random generator and the
// N-sphere benchmark scene (prism_make_spheres writes it to a file, the
// Embree microbenchmark builds it in memory). Header-only, no Prism types.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace prism::bench_tools {

// splitmix64: tiny, portable (the same numbers everywhere), good enough for
// placing spheres and drawing rays.
struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1p-53; }
};

namespace detail {
template <class... Args>
void append(std::string& out, const char* format, Args... args) {
  char buffer[512];
  const int n = std::snprintf(buffer, sizeof buffer, format, args...);
  out.append(buffer, size_t(std::max(0, std::min(n, int(sizeof buffer) - 1))));
}
}  // namespace detail

// A scene of `count` spheres on a jittered cubic grid (cells of side 2,
// filled x, then z, then y), four materials, a point and a directional
// light. The text depends only on `count` and `seed` (fixed formatting).
inline std::string spheres_scene_json(long count, uint64_t seed) {
  const long side = static_cast<long>(std::ceil(std::cbrt(static_cast<double>(count)) - 1e-9));
  const double half = static_cast<double>(side);  // the grid spans [-side, side]
  std::string out;
  out.reserve(size_t(count) * 110 + 1024);
  detail::append(out,
                 "{\n  \"prism\": 1,\n"
                 "  \"camera\": {\"position\": [%.9g, %.9g, %.9g], \"look_at\": [0, 0, 0], \"fov_y\": 50},\n"
                 "  \"image\": {\"width\": 640, \"height\": 360, \"spp\": 1, \"max_depth\": 4},\n"
                 "  \"background\": {\"color\": [0.05, 0.07, 0.12]},\n"
                 "  \"ambient\": [0.04, 0.04, 0.04],\n",
                 -1.5 * half, 1.1 * half, -2.7 * half);
  out += "  \"materials\": {\n"
         "    \"red\": {\"color\": [0.8, 0.2, 0.15], \"specular\": 0.3},\n"
         "    \"green\": {\"color\": [0.2, 0.7, 0.3]},\n"
         "    \"blue\": {\"color\": [0.2, 0.3, 0.85], \"specular\": 0.5, \"shininess\": 64},\n"
         "    \"mirror\": {\"color\": [0.9, 0.9, 0.9], \"reflect\": 0.6}\n"
         "  },\n";
  detail::append(out,
                 "  \"lights\": [\n"
                 "    {\"type\": \"point\", \"position\": [%.9g, %.9g, %.9g], \"intensity\": 0.9},\n"
                 "    {\"type\": \"directional\", \"direction\": [-0.3, -1, 0.4], \"intensity\": 0.4}\n"
                 "  ],\n"
                 "  \"objects\": [\n",
                 1.5 * half, 3.0 * half, -2.0 * half);
  const char* materials[] = {"red", "green", "blue", "mirror"};
  SplitMix64 rng{seed};
  for (long i = 0; i < count; ++i) {
    const long x = i % side, z = (i / side) % side, y = i / (side * side);
    const double cx = 2.0 * x - half + 1 + rng.uniform(-0.4, 0.4);
    const double cy = 2.0 * y - half + 1 + rng.uniform(-0.4, 0.4);
    const double cz = 2.0 * z - half + 1 + rng.uniform(-0.4, 0.4);
    const double radius = rng.uniform(0.2, 0.6);
    detail::append(out,
                   "    {\"type\": \"sphere\", \"center\": [%.6f, %.6f, %.6f], \"radius\": %.6f, \"material\": \"%s\"}%s\n",
                   cx, cy, cz, radius, materials[rng.next() % 4], i + 1 < count ? "," : "");
  }
  out += "  ]\n}\n";
  return out;
}

}  // namespace prism::bench_tools
