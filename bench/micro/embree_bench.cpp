// Microbenchmarks of the Embree path through the embree backend plugin,
// loaded by prism::Registry as the app loads it:
//
//   trace/showcase        Backend::trace of a batch of camera rays, scenes/showcase.json
//   trace/spheres         the same on the many-sphere scene of bench/make_spheres.cpp
//   render/showcase       Backend::render of the showcase at 640x360, 1 spp: one frame
//                         per iteration (ms per frame, wall time; the render is parallel)
//
// trace: one iteration is one trace() call of kRays rays (single-threaded,
// as trace_cpu is); counters rays/s (items_per_second), time_per_ray (CPU
// time), hit_fraction, build_ms (prepare). Camera rays through pixels and
// offsets drawn by a fixed-seed splitmix64, so every run traces the same rays.
//
// Extra flags (after Google Benchmark's own):
//   --showcase=FILE       the showcase scene (default: <source>/scenes/showcase.json)
//   --spheres=N           spheres generated in memory (default 100000; same scene as
//                         `prism_make_spheres -n N`)
//   --spheres_file=FILE   load this scene instead of generating one
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "prism/backend.hpp"
#include "prism/camera.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "spheres_scene.hpp"

namespace {

constexpr size_t kRays = 16384;
constexpr uint64_t kSeed = 0x5052534d45424e43ull;  // "PRSMEBNC"

struct Options {
  std::string showcase = PRISM_SOURCE_DIR "/scenes/showcase.json";
  long spheres = 100000;
  std::string spheres_file;
} options;

using Rng = prism::bench_tools::SplitMix64;

prism::Registry& registry() {
  static prism::Registry r;
  return r;
}

// A scene prepared in the embree backend, loaded on first use and kept for
// the whole run; `error` set when that failed.
struct Prepared {
  std::string error;
  std::optional<prism::Scene> scene;
  std::shared_ptr<const prism::BackendPlugin> plugin;  // keeps the .so loaded while `backend` lives
  std::unique_ptr<prism::Backend> backend;
  std::vector<prism::TraceQuery> rays;  // camera rays
  double hit_fraction = 0.0;
  double build_ms = 0.0;
};

std::vector<prism::TraceQuery> camera_rays(const prism::Scene& scene, uint64_t seed) {
  const int w = scene.image.width, h = scene.image.height;
  Rng rng{seed};
  std::vector<prism::TraceQuery> rays(kRays);
  for (auto& q : rays) {
    const int i = int(rng.next() % uint64_t(w)), j = int(rng.next() % uint64_t(h));
    const glm::dvec2 offset(rng.uniform(0, 1), rng.uniform(0, 1));
    const prism::Ray ray = prism::camera_ray(scene.camera, w, h, i, j, offset);
    q.origin = ray.origin;
    q.dir = ray.dir;
    q.tmin = 0.0;
  }
  return rays;
}

// Emptied by main before exit: the backends (the Embree device, TBB) must
// go before static destruction starts.
std::map<std::string, Prepared> cache;

Prepared& prepared(const std::string& which) {
  auto [it, inserted] = cache.try_emplace(which);
  Prepared& p = it->second;
  if (!inserted) return p;
  try {
    p.plugin = registry().backend("embree");
    const PrismBackendProbe probe = p.plugin->probe();
    if (!probe.usable) throw std::runtime_error(std::string("embree backend cannot run here: ") + probe.reason);
    if (which == "showcase") {
      p.scene = prism::load_scene(options.showcase, registry());
    } else if (!options.spheres_file.empty()) {
      p.scene = prism::load_scene(options.spheres_file, registry());
    } else {
      p.scene = prism::load_scene_from_string(prism::bench_tools::spheres_scene_json(options.spheres, 1), ".", registry(),
                                              "<" + std::to_string(options.spheres) + " spheres>");
    }
    p.backend = p.plugin->create();
    p.backend->prepare(*p.scene);
    const auto stats = p.backend->stats();
    if (auto b = stats.ms.find("build"); b != stats.ms.end()) p.build_ms = b->second;
    p.rays = camera_rays(*p.scene, kSeed);
    size_t hits = 0;
    for (const prism::TraceResult& r : p.backend->trace(p.rays)) hits += r.id != -1;
    p.hit_fraction = double(hits) / double(p.rays.size());
  } catch (const std::exception& e) {
    p.error = which + ": " + e.what();
  }
  return p;
}

void bench_trace(benchmark::State& state, const char* which) {
  Prepared& p = prepared(which);
  if (!p.error.empty()) {
    state.SkipWithError(p.error.c_str());
    return;
  }
  for (auto _ : state) {
    std::vector<prism::TraceResult> results = p.backend->trace(p.rays);
    benchmark::DoNotOptimize(results.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.rays.size()));
  // CPU seconds per ray, shown as e.g. "250ns" (kInvert of the rays/s rate).
  state.counters["time_per_ray"] = benchmark::Counter(
      double(p.rays.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["hit_fraction"] = p.hit_fraction;
  state.counters["objects"] = double(p.scene->objects.size());
  state.counters["build_ms"] = p.build_ms;
}

void bench_render(benchmark::State& state, const char* which) {
  Prepared& p = prepared(which);
  if (!p.error.empty()) {
    state.SkipWithError(p.error.c_str());
    return;
  }
  prism::RenderSettings settings;
  settings.image = p.scene->image;
  settings.image.width = 640;
  settings.image.height = 360;
  settings.image.spp = 1;
  const uint64_t rays_before = p.backend->stats().rays;
  for (auto _ : state) {
    prism::Image image = p.backend->render(settings);
    benchmark::DoNotOptimize(image.rgb.data());
  }
  const double rays = double(p.backend->stats().rays - rays_before);
  // Every ray of the frame (camera, shadow, reflect, ...): rays/s over wall time.
  state.SetItemsProcessed(int64_t(rays));
  state.counters["rays_per_frame"] = benchmark::Counter(rays, benchmark::Counter::kAvgIterations);
  state.counters["time_per_ray"] = benchmark::Counter(rays, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

bool parse_flag(const char* arg, const char* name, std::string& value) {
  const size_t n = std::strlen(name);
  if (std::strncmp(arg, name, n) != 0 || arg[n] != '=') return false;
  value = arg + n + 1;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    std::string value;
    if (parse_flag(argv[i], "--showcase", value)) {
      options.showcase = value;
    } else if (parse_flag(argv[i], "--spheres", value)) {
      options.spheres = std::strtol(value.c_str(), nullptr, 10);
      if (options.spheres < 1 || options.spheres > 10000000) {
        std::fprintf(stderr, "%s: --spheres must be 1..10000000\n", argv[0]);
        return 1;
      }
    } else if (parse_flag(argv[i], "--spheres_file", value)) {
      options.spheres_file = value;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  benchmark::RegisterBenchmark("trace/showcase", bench_trace, "showcase")->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("trace/spheres", bench_trace, "spheres")->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("render/showcase", bench_render, "showcase")
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->MeasureProcessCPUTime();
  benchmark::AddCustomContext("trace_rays_per_iteration", std::to_string(kRays));
  benchmark::AddCustomContext("spheres", options.spheres_file.empty() ? std::to_string(options.spheres)
                                                                       : options.spheres_file);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  cache.clear();
  return 0;
}
