#include "prism/cpu_render.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <memory>

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

// One pixel from its samples' results: the mean of their radiance, summed
// in sample order (so the result never depends on threads), plus the AOVs
// of sample 0.
void store_pixel(const Frame& f, int i, int j, std::span<const SampleResult> samples) {
  glm::dvec3 sum(0.0);
  for (const SampleResult& r : samples) sum += r.radiance;
  const SampleResult& r = samples.front();
  const size_t p = f.index(i, j);
  if (f.settings.aov_id) f.image.id[p] = static_cast<float>(r.first_id);
  if (f.settings.aov_path) f.image.path[p] = static_cast<float>(r.path_hash);
  if (f.settings.aov_depth) f.image.depth[p] = static_cast<float>(r.first_t);
  if (f.settings.aov_normal) store3(&f.image.normal[p * 3], r.first_normal);
  if (f.settings.aov_albedo) store3(&f.image.albedo[p * 3], r.first_albedo);
  store3(&f.image.rgb[p * 3], sum / double(samples.size()));
}

// The shader lights its points in batches: a tile's samples (as many whole
// pixels' as kSamplesPerFinish holds, or one pixel's at a high spp) are
// traced, then finished and stored together.
static_assert(Shader::kSamplesPerFinish == size_t(kTileSize) * kTileSize);

// The camera rays of up to this many samples are made before they are
// traced, together (CameraRays::make_batch), so that their divisions and
// square roots overlap; made one at a time between traces, each waited for
// its own (~4 % of a showcase frame by perf).
constexpr size_t kRaysMadeAhead = Shader::kSamplesPerFinish;
static_assert(kRaysMadeAhead <= CameraRays::kBatch);

// Room for kRaysMadeAhead samples, kept across the tiles of a range.
struct SampleBuffers {
  std::vector<double> x = std::vector<double>(kRaysMadeAhead), y = std::vector<double>(kRaysMadeAhead);  // on the image plane
  std::vector<Ray> rays = std::vector<Ray>(kRaysMadeAhead);
  std::vector<Hit> hits = std::vector<Hit>(kRaysMadeAhead);
  std::vector<uint8_t> want_path = std::vector<uint8_t>(kRaysMadeAhead);
};

// What a render thread keeps from one range of tiles to the next: its
// shader (whose state between tiles is its buffers and the guesses of
// likely shadow blockers, which change no answer), its sample buffers and
// its counts.
struct Worker {
  RayCounts counts;
  PhaseProfile profile;
  Shader shader;
  SampleBuffers buffers;
  Worker(const Scene& scene, const ObjectQuery& query, bool profiled)
      : shader(scene, query, counts, profiled ? &profile : nullptr) {}
};

void render_tile(const Frame& f, int tile, int tiles_x, Shader& shader, SampleBuffers& b) {
  const PixelRect& r = f.rect;
  const ImageSettings& s = f.settings.image;
  const size_t spp = size_t(s.spp);
  const int x0 = r.x + (tile % tiles_x) * kTileSize, y0 = r.y + (tile / tiles_x) * kTileSize;
  const int x1 = std::min(x0 + kTileSize, r.x + r.width), y1 = std::min(y0 + kTileSize, r.y + r.height);
  // Pixel by pixel in rows, each pixel's samples in order.
  struct Cursor {
    int i, j, k;
  };
  auto next_pixel = [&](Cursor& c) {
    if (++c.i == x1) c = {x0, c.j + 1, 0};
  };
  auto next_sample = [&](Cursor& c) {
    if (++c.k < s.spp) return;
    c.k = 0;
    next_pixel(c);
  };
  const CameraRays::Cone cone = f.camera_rays.cone(x0, y0, x1, y1);
  shader.set_camera_cone(f.camera_rays.position(), cone.axis, cone.cos_half);
  const size_t pixels = size_t(x1 - x0) * size_t(y1 - y0);
  const size_t pixels_per_finish = std::max<size_t>(1, Shader::kSamplesPerFinish / spp);
  Cursor made{x0, y0, 0}, stored{x0, y0, 0};
  for (size_t first_pixel = 0; first_pixel < pixels; first_pixel += pixels_per_finish) {
    const size_t count = std::min(pixels_per_finish, pixels - first_pixel);
    const size_t samples = count * spp;
    for (size_t first = 0; first < samples; first += kRaysMadeAhead) {
      const size_t n = std::min(kRaysMadeAhead, samples - first);
      for (size_t q = 0; q < n; ++q, next_sample(made)) {
        const glm::dvec2 offset = sample_offset(made.k);
        b.x[q] = made.i + offset.x;
        b.y[q] = made.j + offset.y;
        b.want_path[q] = made.k == 0 && f.settings.aov_path;
      }
      f.camera_rays.make_batch(b.x.data(), b.y.data(), n, b.rays.data());
      const std::span<const Ray> rays = std::span(b.rays).first(n);
      shader.camera_hits(rays, b.hits.data());
      shader.trace_samples(rays, b.hits.data(), b.want_path.data(), s.max_depth);
    }
    const std::span<const SampleResult> results = shader.finish();
    for (size_t p = 0; p < count; ++p, next_pixel(stored)) store_pixel(f, stored.i, stored.j, results.subspan(p * spp, spp));
  }
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
  // One worker per thread for the whole frame, built on the thread's first
  // range of tiles: a frame splits into some 128 ranges at 640x360, and a
  // worker per range built a shader's buffers (some 300 KB) 128 times.
  tbb::enumerable_thread_specific<std::unique_ptr<Worker>> workers;
  auto run = [&](int begin, int end) {
    std::unique_ptr<Worker>& slot = workers.local();
    if (!slot) slot = std::make_unique<Worker>(scene, query, settings.profile);
    Worker& w = *slot;
    // Isolated: were a tile to wait on TBB work of its own, this thread
    // could meanwhile take another range of this loop, with the same worker.
    tbb::this_task_arena::isolate([&] {
      for (int tile = begin; tile < end; ++tile) {
        if (cancel_requested()) break;  // the rest of the range is skipped; thrown below
        const uint64_t before = ray_total(w.counts);
        render_tile(frame, tile, tiles_x, w.shader, w.buffers);
        const uint64_t rays = traced += ray_total(w.counts) - before;
        int finished = ++done;
        report_progress(settings, double(finished) / tiles, rays);
      }
    });
  };
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) { run(r.begin(), r.end()); });
  else
    run(0, tiles);
  throw_if_cancelled();
  RayCounts total;
  PhaseProfile total_profile;
  for (const std::unique_ptr<Worker>& w : workers) {
    if (!w) continue;
    total.add(w->counts);
    total_profile.add(w->profile);
  }
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
