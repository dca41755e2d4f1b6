// Microbenchmarks of each primitive plugin's CPU intersector, driven through
// its descriptor exactly as the core calls it: the plugin .so is loaded by
// prism::Registry, a record is packed by `validate` + `pack`, and rays are
// given in the local frame. The objects and their rays are each primitive's
// bench cases, from its folder (tests/cases/primitive_cases.hpp): a
// primitive added with its cases is benchmarked with no change here.
//
//   intersect/<type>/{hit,miss}        desc->intersect, one call per ray
//   intersect_batch/<type>/{hit,miss}  desc->intersect_batch over the whole batch
//   surface/<type>                     desc->surface for each hit of the hit batch
//
// One iteration handles a batch of kRays (1024) rays; the counters give
// rays/s (items_per_second) and time_per_ray (CPU time per ray). Rays are
// deterministic (own splitmix64 RNG, a fixed seed per type). Hit rays aim at a point inside a solid or on
// a surface, so they must hit: the setup checks every one and the benchmark
// fails (SkipWithError) if one misses. Miss rays start at the same places and
// aim into the object's bounding box grown by 1.5x (the rays a BVH would hand
// the intersector), kept only when they miss.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "primitive_cases.hpp"
#include "prism/primitive_abi.h"
#include "prism/registry.hpp"
#include "spheres_scene.hpp"

namespace {

constexpr size_t kRays = 1024;
constexpr uint64_t kSeed = 0x5052534d42454e43ull;  // "PRSMBENC"
constexpr double kInf = std::numeric_limits<double>::infinity();

using prism::cases::BenchCase;
using Rng = prism::cases::BenchRng;
using prism::cases::bench_ray;

// One benchmarked object: a primitive's bench case (from its folder).
struct Case {
  std::string type;
  const BenchCase* bench;
};

// Every primitive's bench cases (tests/cases/primitive_cases.hpp), by type.
std::vector<Case> cases() {
  std::vector<Case> c;
  for (const prism::cases::PrimitiveCases* cases : prism::cases::all_primitive_cases())
    for (const BenchCase& bench : cases->bench) c.push_back({cases->type, &bench});
  return c;
}

// A seed of the type's own (FNV-1a of its name), so adding a type changes no other type's rays.
uint64_t seed_for(const std::string& type) {
  uint64_t h = 14695981039346656037ull ^ kSeed;
  for (char ch : type) {
    h ^= uint8_t(ch);
    h *= 1099511628211ull;
  }
  return h;
}

// A packed object of one plugin with its ray batches; `error` set when the
// setup failed (the benchmarks then report it through SkipWithError).
struct Fixture {
  std::string type;
  std::string error;
  std::shared_ptr<const prism::PrimitivePlugin> plugin;  // keeps the .so loaded
  const PrismPrimitiveDesc* desc = nullptr;
  std::vector<glm::dvec4> record;  // 16-aligned storage for the record
  std::vector<PrismRay> hit_rays, miss_rays;
  std::vector<PrismHit> hits;  // desc->intersect of hit_rays, for `surface`
  std::vector<double> tmin, tmax;

  const void* rec() const { return record.data(); }
  bool intersect(const PrismRay& ray, PrismHit& hit) const { return desc->intersect(rec(), &ray, 0.0, kInf, &hit) != 0; }
};

// The checked field values in field order, as the core hands them to validate and pack.
std::optional<std::vector<double>> field_values(const PrismPrimitiveDesc& desc, const Case& c, std::string& error) {
  std::vector<double> values;
  for (uint32_t f = 0; f < desc.field_count; ++f) {
    const PrismField& field = desc.fields[f];
    const std::vector<double>* given = nullptr;
    for (const auto& [name, v] : c.bench->fields)
      if (name == std::string(field.name)) given = &v;
    if (given) {
      if (given->size() != field.count) {
        error = std::string(field.name) + ": wrong number of values";
        return std::nullopt;
      }
      values.insert(values.end(), given->begin(), given->end());
    } else if (field.defaults) {
      values.insert(values.end(), field.defaults, field.defaults + field.count);
    } else {
      error = std::string(field.name) + ": required and not given";
      return std::nullopt;
    }
  }
  return values;
}

void setup(Fixture& fx, const Case& c, prism::Registry& registry) {
  fx.type = c.type;
  try {
    fx.plugin = registry.primitive(c.type);
  } catch (const std::exception& e) {
    fx.error = std::string("cannot load the plugin: ") + e.what();
    return;
  }
  fx.desc = &fx.plugin->desc();
  const PrismPrimitiveDesc& desc = *fx.desc;
  const auto values = field_values(desc, c, fx.error);
  if (!values) return;
  PrismError err{};
  if (desc.validate(values->data(), &err) != 0) {
    fx.error = std::string("invalid fields: ") + err.field + ": " + err.message;
    return;
  }
  fx.record.assign((desc.record_size + sizeof(glm::dvec4) - 1) / sizeof(glm::dvec4), glm::dvec4(0.0));
  desc.pack(values->data(), fx.record.data());

  const BenchCase& bench = *c.bench;
  Rng rng{{seed_for(c.type)}};
  for (size_t i = 0; i < kRays; ++i) fx.hit_rays.push_back(bench_ray(bench.origin(rng), bench.hit_target(rng)));

  std::function<PrismRay(Rng&)> candidate = bench.miss_candidate;
  if (!candidate) {
    double lo[3], hi[3];
    if (!desc.bounds(fx.rec(), lo, hi)) {
      fx.error = "unbounded: the case needs its own miss rays";
      return;
    }
    const glm::dvec3 mid = 0.5 * (glm::dvec3(lo[0], lo[1], lo[2]) + glm::dvec3(hi[0], hi[1], hi[2]));
    const glm::dvec3 half = 0.75 * (glm::dvec3(hi[0], hi[1], hi[2]) - glm::dvec3(lo[0], lo[1], lo[2]));
    candidate = [&bench, mid, half](Rng& r) {
      const glm::dvec3 o = bench.origin(r);
      const glm::dvec3 target = mid + half * glm::dvec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
      return bench_ray(o, target);
    };
  }
  PrismHit scratch{};
  for (size_t tries = 0; fx.miss_rays.size() < kRays; ++tries) {
    if (tries > 1000 * kRays) {
      fx.error = "could not find enough miss rays";
      return;
    }
    const PrismRay ray = candidate(rng);
    if (!fx.intersect(ray, scratch)) fx.miss_rays.push_back(ray);
  }

  // Every hit ray must hit (single and batch agree), every miss ray miss.
  fx.tmin.assign(kRays, 0.0);
  fx.tmax.assign(kRays, kInf);
  fx.hits.resize(kRays);
  for (size_t i = 0; i < kRays; ++i) {
    if (!fx.intersect(fx.hit_rays[i], fx.hits[i])) {
      fx.error = "hit ray " + std::to_string(i) + " missed";
      return;
    }
  }
  std::vector<PrismHit> batch(kRays);
  std::vector<uint8_t> found(kRays);
  desc.intersect_batch(fx.rec(), kRays, fx.hit_rays.data(), fx.tmin.data(), fx.tmax.data(), batch.data(), found.data());
  for (size_t i = 0; i < kRays; ++i) {
    if (!found[i] || batch[i].t != fx.hits[i].t) {
      fx.error = "intersect_batch disagrees with intersect on hit ray " + std::to_string(i);
      return;
    }
  }
  desc.intersect_batch(fx.rec(), kRays, fx.miss_rays.data(), fx.tmin.data(), fx.tmax.data(), batch.data(), found.data());
  for (size_t i = 0; i < kRays; ++i) {
    if (found[i]) {
      fx.error = "intersect_batch hits miss ray " + std::to_string(i);
      return;
    }
  }
}

// rays/s (items_per_second) and time_per_ray: CPU seconds per ray, shown
// as e.g. "12.3ns" (kInvert of the rays/s rate).
void count_rays(benchmark::State& state, size_t rays_per_iteration) {
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays_per_iteration));
  state.counters["time_per_ray"] = benchmark::Counter(
      double(rays_per_iteration), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void bench_intersect(benchmark::State& state, const Fixture* fx, bool hit) {
  if (!fx->error.empty()) {
    state.SkipWithError(fx->error.c_str());
    return;
  }
  const auto intersect = fx->desc->intersect;
  const void* rec = fx->rec();
  const std::vector<PrismRay>& rays = hit ? fx->hit_rays : fx->miss_rays;
  PrismHit out{};
  for (auto _ : state) {
    for (const PrismRay& ray : rays) {
      int found = intersect(rec, &ray, 0.0, kInf, &out);
      benchmark::DoNotOptimize(found);
      benchmark::DoNotOptimize(out);
    }
  }
  count_rays(state, rays.size());
}

void bench_intersect_batch(benchmark::State& state, const Fixture* fx, bool hit) {
  if (!fx->error.empty()) {
    state.SkipWithError(fx->error.c_str());
    return;
  }
  const auto batch = fx->desc->intersect_batch;
  const std::vector<PrismRay>& rays = hit ? fx->hit_rays : fx->miss_rays;
  std::vector<PrismHit> hits(rays.size());
  std::vector<uint8_t> found(rays.size());
  for (auto _ : state) {
    batch(fx->rec(), rays.size(), rays.data(), fx->tmin.data(), fx->tmax.data(), hits.data(), found.data());
    benchmark::DoNotOptimize(hits.data());
    benchmark::DoNotOptimize(found.data());
    benchmark::ClobberMemory();
  }
  count_rays(state, rays.size());
}

void bench_surface(benchmark::State& state, const Fixture* fx) {
  if (!fx->error.empty()) {
    state.SkipWithError(fx->error.c_str());
    return;
  }
  const auto surface = fx->desc->surface;
  const void* rec = fx->rec();
  PrismSurface out{};
  for (auto _ : state) {
    for (size_t i = 0; i < fx->hit_rays.size(); ++i) {
      surface(rec, &fx->hit_rays[i], &fx->hits[i], &out);
      benchmark::DoNotOptimize(out);
    }
  }
  count_rays(state, fx->hit_rays.size());
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  prism::Registry registry;
  static const std::vector<Case> all = cases();
  static std::vector<Fixture> fixtures(all.size());
  for (size_t i = 0; i < all.size(); ++i) setup(fixtures[i], all[i], registry);

  for (const Fixture& fx : fixtures) {
    for (bool hit : {true, false}) {
      const std::string suffix = fx.type + (hit ? "/hit" : "/miss");
      benchmark::RegisterBenchmark(("intersect/" + suffix).c_str(), bench_intersect, &fx, hit)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark(("intersect_batch/" + suffix).c_str(), bench_intersect_batch, &fx, hit)
          ->Unit(benchmark::kMicrosecond);
    }
    benchmark::RegisterBenchmark(("surface/" + fx.type).c_str(), bench_surface, &fx)->Unit(benchmark::kMicrosecond);
  }
  benchmark::AddCustomContext("rays_per_iteration", std::to_string(kRays));
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
