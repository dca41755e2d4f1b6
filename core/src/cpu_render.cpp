#include "prism/cpu_render.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <mutex>

#include "prism/camera.hpp"
#include "prism/cancel.hpp"
#include "shading.hpp"

namespace prism {

namespace {

constexpr int kTileSize = 16;

struct Frame {
  const Scene& scene;
  const ObjectQuery& query;
  const RenderSettings& settings;
  const CameraRays& camera_rays;
  PixelRect rect;  // the pixels rendered (the region, or the whole image)
  Image& image;    // rect-sized
  size_t index(int i, int j) const { return size_t(j - rect.y) * size_t(rect.width) + size_t(i - rect.x); }
};

void store3(float* out, const glm::dvec3& v) {
  for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(v[c]);
}

// One pixel: the mean of its samples, summed in sample order (so the result
// never depends on threads), plus the AOVs of sample 0.
void render_pixel(const Frame& f, Shader& shader, int i, int j) {
  const ImageSettings& s = f.settings.image;
  glm::dvec3 sum(0.0);
  for (int k = 0; k < s.spp; ++k) {
    Ray ray = f.camera_rays(i, j, sample_offset(k));
    SampleResult r = shader.trace_sample(ray, s.max_depth, k == 0 && f.settings.aov_path);
    sum += r.radiance;
    if (k == 0) {
      size_t p = f.index(i, j);
      if (f.settings.aov_id) f.image.id[p] = static_cast<float>(r.first_id);
      if (f.settings.aov_path) f.image.path[p] = static_cast<float>(r.path_hash);
      if (f.settings.aov_depth) f.image.depth[p] = static_cast<float>(r.first_t);
      if (f.settings.aov_normal) store3(&f.image.normal[p * 3], r.first_normal);
      if (f.settings.aov_albedo) store3(&f.image.albedo[p * 3], r.first_albedo);
    }
  }
  glm::dvec3 mean = sum / double(s.spp);
  float* out = &f.image.rgb[f.index(i, j) * 3];
  for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(mean[c]);
}

void render_tile(const Frame& f, int tile, int tiles_x, RayCounts& counts, PhaseProfile* profile) {
  const PixelRect& r = f.rect;
  Shader shader(f.scene, f.query, counts, profile);
  int x0 = r.x + (tile % tiles_x) * kTileSize, y0 = r.y + (tile / tiles_x) * kTileSize;
  for (int j = y0; j < std::min(y0 + kTileSize, r.y + r.height); ++j)
    for (int i = x0; i < std::min(x0 + kTileSize, r.x + r.width); ++i) render_pixel(f, shader, i, j);
}

uint64_t ray_total(const RayCounts& counts) {
  uint64_t total = 0;
  for (const uint64_t n : counts.n) total += n;
  return total;
}

void add_counts(BackendStats& stats, const RayCounts& counts) {
  for (int kind = 0; kind < kRayKinds; ++kind) {
    stats.rays_by_kind[ray_kind_name(kind)] += counts.n[size_t(kind)];
    stats.rays += counts.n[size_t(kind)];
  }
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Image render_cpu(const Scene& scene, const ObjectQuery& query, const RenderSettings& settings, BackendStats& stats,
                 bool parallel) {
  auto start = std::chrono::steady_clock::now();
  check_region(settings);
  const ImageSettings& s = settings.image;
  const PixelRect rect = render_rect(settings);
  Image image;
  image.width = rect.width;
  image.height = rect.height;
  const size_t pixels = size_t(rect.width) * size_t(rect.height);
  assign_channel(image.rgb, pixels * 3, 0.0f);
  assign_aovs(image, settings);
  const CameraRays camera_rays(settings.camera ? *settings.camera : scene.camera, s.width, s.height);
  Frame frame{scene, query, settings, camera_rays, rect, image};
  const int tiles_x = (rect.width + kTileSize - 1) / kTileSize;
  const int tiles = tiles_x * ((rect.height + kTileSize - 1) / kTileSize);
  std::atomic<int> done{0};
  std::atomic<uint64_t> traced{0};  // rays of the tiles done, for RenderSettings::rays_traced
  std::mutex counts_mutex;
  RayCounts total;
  PhaseProfile total_profile;
  auto run = [&](int begin, int end) {
    RayCounts counts;
    PhaseProfile profile;
    for (int tile = begin; tile < end; ++tile) {
      if (cancel_requested()) break;  // the rest of the range is skipped; thrown below
      const uint64_t before = ray_total(counts);
      render_tile(frame, tile, tiles_x, counts, settings.profile ? &profile : nullptr);
      const uint64_t rays = traced += ray_total(counts) - before;
      int finished = ++done;
      report_progress(settings, double(finished) / tiles, rays);
    }
    std::lock_guard lock(counts_mutex);
    total.add(counts);
    total_profile.add(profile);
  };
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) { run(r.begin(), r.end()); });
  else
    run(0, tiles);
  throw_if_cancelled();
  add_counts(stats, total);
  if (settings.profile) {
    for (int phase = 0; phase < kPhases; ++phase)
      stats.ms[std::string(ms_key::kProfilePrefix) + kPhaseNames[phase]] += total_profile.ms[size_t(phase)];
  }
  stats.ms[ms_key::kRender] += ms_since(start);
  return image;
}

std::vector<TraceResult> trace_cpu(const Scene& scene, const ObjectQuery& query, std::span<const TraceQuery> rays,
                                   BackendStats& stats) {
  auto start = std::chrono::steady_clock::now();
  std::vector<TraceResult> results(rays.size());
  RayCounts counts;
  Shader shader(scene, query, counts);
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i % 4096 == 0) throw_if_cancelled();  // a few ms of rays between checks
    Ray ray{rays[i].origin, rays[i].dir};
    Hit hit = shader.closest(ray, rays[i].tmin);
    TraceResult& r = results[i];
    r.t = hit.t;
    r.id = hit.id;
    if (hit.id >= 0) {
      const SurfacePoint surface = surface_of(scene.objects[size_t(hit.id)], ray, hit.prim, query.entry(), false);
      r.t = surface.t;
      r.normal = surface.normal;
    } else if (hit.found()) {
      r.normal = light_sphere_normal(scene, ray, hit);
    }
  }
  throw_if_cancelled();  // a plugin fault in the last rays (request_stop_for_fault)
  stats.rays += rays.size();
  stats.rays_by_kind[ray_kind::kTrace] += rays.size();
  stats.ms[ms_key::kRender] += ms_since(start);
  return results;
}

}  // namespace prism
