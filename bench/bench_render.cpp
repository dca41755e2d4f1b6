// Times a backend on a scene: load, prepare (build) and N renders, median.
//   prism_bench_render SCENE [-b BACKEND] [--width W] [--height H] [--repeat N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "prism/backend.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// CPU time of the whole process (all threads), ms: less sensitive than wall
// time to other load on the machine.
double cpu_ms() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto ms = [](const timeval& t) { return t.tv_sec * 1e3 + t.tv_usec * 1e-3; };
  return ms(usage.ru_utime) + ms(usage.ru_stime);
}

int usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s SCENE [-b BACKEND] [--width W] [--height H] [--repeat N]\n", argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage(argv[0]);
  const std::string scene_path = argv[1];
  std::string backend_name = "embree";
  int width = -1, height = -1, repeat = 3;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "-b") == 0) {
      backend_name = argv[i + 1];
    } else if (std::strcmp(argv[i], "--width") == 0) {
      width = std::atoi(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--height") == 0) {
      height = std::atoi(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--repeat") == 0) {
      repeat = std::max(1, std::atoi(argv[i + 1]));
    } else {
      return usage(argv[0]);
    }
  }
  try {
    prism::Registry registry;
    auto start = std::chrono::steady_clock::now();
    const prism::Scene scene = prism::load_scene(scene_path, registry);
    const double load_ms = ms_since(start);
    auto backend = registry.backend(backend_name)->create();
    start = std::chrono::steady_clock::now();
    backend->prepare(scene);
    const double prepare_ms = ms_since(start);
    prism::RenderSettings settings;
    settings.image = scene.image;
    if (width > 0) settings.image.width = width;
    if (height > 0) settings.image.height = height;
    prism::check_image_settings(settings.image, "command line");
    std::vector<double> renders, cpu;
    for (int i = 0; i < repeat; ++i) {
      start = std::chrono::steady_clock::now();
      const double cpu_start = cpu_ms();
      backend->render(settings);
      renders.push_back(ms_since(start));
      cpu.push_back(cpu_ms() - cpu_start);
    }
    const auto stats = backend->stats();
    std::printf("scene %s: %zu objects, backend %s, %dx%d spp %d\n", scene_path.c_str(), scene.objects.size(),
                backend_name.c_str(), settings.image.width, settings.image.height, settings.image.spp);
    std::printf("load %.1f ms, prepare %.1f ms (build %.1f ms)\n", load_ms, prepare_ms,
                stats.ms.count("build") ? stats.ms.at("build") : 0.0);
    std::printf("render ms:");
    for (double ms : renders) std::printf(" %.1f", ms);
    std::sort(renders.begin(), renders.end());
    std::sort(cpu.begin(), cpu.end());
    std::printf("  median %.1f (cpu %.1f)  rays/render %.0f\n", renders[renders.size() / 2], cpu[cpu.size() / 2],
                double(stats.rays) / repeat);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
