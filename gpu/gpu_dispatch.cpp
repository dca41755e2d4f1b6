#include "gpu_dispatch.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "prism/errors.hpp"

namespace prism::gpu {

KernelOptions kernel_options(bool trace, const char* api_glue) {
  KernelOptions options;
  options.trace = trace;
  options.all_features = all_features_forced();
  options.api_glue = api_glue;
  options.local_size_x = trace ? kTraceLocalSize : kRenderLocalSize;
  options.local_size_y = trace ? 1 : kRenderLocalSize;
  return options;
}

bool texel_buffer_allowed() { return env_number("PRISM_GPU_TEXEL_BUFFER", 1.0, 0.0, 1.0) != 0.0; }
bool material_block_allowed() { return env_number("PRISM_GPU_MATERIAL_BLOCK", 1.0, 0.0, 1.0) != 0.0; }

static_assert(std::size(kRayKindNames) <= kRayCounterCount);

namespace {
constexpr long kCpuSamplesPerTile = 1 << 18;
constexpr long kGpuSamplesPerTile = 1 << 21;
// gpu/kernel.glsl scrambles a tile's work groups as k * kGroupScramblePrime mod n
// in 32 bits: the product must fit, and the prime must exceed the group count.
constexpr uint64_t kMaxGroupsPerTile = kGpuSamplesPerTile / (kRenderLocalSize * kRenderLocalSize);
static_assert(kMaxGroupsPerTile * kGroupScramblePrime < (uint64_t(1) << 32) && kMaxGroupsPerTile < kGroupScramblePrime);

int round_up8(long n) { return int((n + 7) / 8 * 8); }
}  // namespace

TileBudget tile_budget(bool cpu_device, size_t max_storage_bytes, int lights, int min_tiles) {
  TileBudget budget;
  budget.min_tiles = std::max(1, min_tiles);
  const double fallback = double(cpu_device ? kCpuSamplesPerTile : kGpuSamplesPerTile);
  budget.samples = long(env_number("PRISM_GPU_TILE_SAMPLES", fallback, 64, double(kGpuSamplesPerTile)));
  budget.max_output_bytes = max_storage_bytes;
  budget.lights = lights;
  return budget;
}

size_t output_bytes(size_t pixels, int planes) { return kOutputHeaderBytes + pixels * kPixelPlaneBytes * size_t(planes); }

std::pair<int, int> tile_size(const ImageSettings& image, const TileBudget& budget) {
  // Ray counters are 32 bits: at most 2^32 - 1 rays of a kind in a tile.
  const long rays_per_sample = long(std::max(1, image.max_depth)) * std::max(1, budget.lights);
  const long samples = std::min(budget.samples, long((uint64_t(1) << 32) / uint64_t(rays_per_sample + 1)));
  long pixels = std::max<long>(64, samples / image.spp);
  const size_t plane_bytes = kPixelPlaneBytes * kMaxOutputPlanes;
  if (budget.max_output_bytes > kOutputHeaderBytes + 64 * plane_bytes)
    pixels = std::min<long>(pixels, long((budget.max_output_bytes - kOutputHeaderBytes) / plane_bytes));
  // A CPU-sized tile keeps its 512-pixel rows (measured with llvmpipe); a
  // larger one spans the image's width.
  const int max_width = pixels <= kCpuSamplesPerTile ? 512 : round_up8(pixels / 8);
  const int w = round_up8(std::min(image.width, max_width));
  const int h = std::max(8, int(pixels / w) / 8 * 8);
  const int band = round_up8((long(image.height) + budget.min_tiles - 1) / budget.min_tiles);
  return {w, std::min({h, band, round_up8(image.height)})};
}

std::vector<Tile> tiles_of(const RenderSettings& settings, const TileBudget& budget) {
  check_region(settings);
  const auto [tw, th] = tile_size(settings.image, budget);
  const PixelRect r = render_rect(settings);
  std::vector<Tile> tiles;
  for (int y0 = r.y; y0 < r.y + r.height; y0 += th)
    for (int x0 = r.x; x0 < r.x + r.width; x0 += tw)
      tiles.push_back({x0, y0, std::min(tw, r.x + r.width - x0), std::min(th, r.y + r.height - y0)});
  return tiles;
}

Image blank_image(const RenderSettings& settings) {
  const PixelRect r = render_rect(settings);
  Image image;
  image.width = r.width;
  image.height = r.height;
  const size_t n = size_t(image.width) * image.height;
  assign_channel(image.rgb, n * 3, 0.0f);
  assign_aovs(image, settings);
  return image;
}

void store_tile(Image& image, const RenderSettings& settings, const float* planes, const Tile& tile) {
  const PixelRect r = render_rect(settings);
  const size_t plane = size_t(tile.width) * size_t(tile.height) * 4;  // floats
  const float* rgb_id = planes;
  const float* normal_path = planes + plane;
  const float* albedo_depth = planes + 2 * plane;
  const bool more = output_planes(settings) > 1;
  const auto store_row = [&](int j) {
    const size_t row = size_t(tile.y0 - r.y + j) * size_t(image.width) + size_t(tile.x0 - r.x);
    const size_t from = size_t(j) * size_t(tile.width);
    for (int i = 0; i < tile.width; ++i) std::copy_n(rgb_id + (from + i) * 4, 3, &image.rgb[(row + i) * 3]);
    if (settings.aov_id)
      for (int i = 0; i < tile.width; ++i) image.id[row + i] = rgb_id[(from + i) * 4 + 3];
    if (!more) return;
    for (int i = 0; i < tile.width; ++i) {
      const size_t p = row + i, q = (from + i) * 4;
      if (settings.aov_path) image.path[p] = normal_path[q + 3];
      if (settings.aov_depth) image.depth[p] = albedo_depth[q + 3];
      if (settings.aov_normal) std::copy_n(normal_path + q, 3, &image.normal[p * 3]);
      if (settings.aov_albedo) std::copy_n(albedo_depth + q, 3, &image.albedo[p * 3]);
    }
  };
  // A GPU's frame comes back in one tile of up to 2 M pixels: copied by
  // every core (measured on a 16-core host: 10.4 ms on one for 1920x1080).
  tbb::parallel_for(tbb::blocked_range<int>(0, tile.height, 16), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) store_row(j);
  });
}

FrameProfile::FrameProfile(bool on) : on_(on), last_(std::chrono::steady_clock::now()) {}

double FrameProfile::lap() {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
  last_ = now;
  return ms;
}

void FrameProfile::end_setup() {
  if (on_) setup_ += lap();
}

void FrameProfile::end_allocation() {
  if (on_) allocation_ += lap();
}

void FrameProfile::end_wait(double kernel_ms) {
  if (!on_) return;
  wait_ += lap();
  if (kernel_ms >= 0) kernel_ = std::max(kernel_, 0.0) + kernel_ms;
}

void FrameProfile::end_store() {
  if (on_) store_ += lap();
}

void FrameProfile::add_to(BackendStats& stats) const {
  if (!on_) return;
  const std::string p = ms_key::kProfilePrefix;
  stats.ms[p + "set-up and submission"] += setup_;
  stats.ms[p + "image allocation"] += allocation_;
  stats.ms[p + "device wait"] += wait_;
  stats.ms[p + "store in image"] += store_;
  if (kernel_ >= 0) stats.ms[p + ms_key::kDevicePhasePrefix + "kernel"] += kernel_;
}

void add_ray_counters(BackendStats& stats, const uint32_t counters[kRayCounterCount]) {
  for (size_t k = 0; k < std::size(kRayKindNames); ++k) {
    stats.rays_by_kind[kRayKindNames[k]] += counters[k];
    stats.rays += counters[k];
  }
}

size_t trace_record_bytes(const PackedScene& packed) {
  return packed.float_world ? sizeof(GpuTraceRayF) : sizeof(GpuTraceRay);
}

namespace {

template <class Record>
void store_records(std::span<const TraceQuery> rays, const glm::dvec3& anchor, unsigned char* out) {
  using W = std::remove_reference_t<decltype(Record{}.origin_tmin[0])>;
  for (size_t i = 0; i < rays.size(); ++i) {
    const TraceQuery& q = rays[i];
    const glm::dvec3 o = q.origin - anchor;
    const Record r{{W(o.x), W(o.y), W(o.z), W(q.tmin)}, {W(q.dir.x), W(q.dir.y), W(q.dir.z), W(0)}, {}, {}, {}};
    std::memcpy(out + i * sizeof r, &r, sizeof r);
  }
}

template <class Record>
void load_records(std::span<const unsigned char> bytes, std::span<TraceResult> results) {
  for (size_t i = 0; i < results.size(); ++i) {
    Record r;
    std::memcpy(&r, bytes.data() + i * sizeof r, sizeof r);
    TraceResult& out = results[i];
    out.t = r.t_normal[0];
    out.id = r.id[0];
    out.normal = {r.t_normal[1], r.t_normal[2], r.t_normal[3]};
  }
}

}  // namespace

std::vector<unsigned char> trace_records(const PackedScene& packed, std::span<const TraceQuery> rays) {
  std::vector<unsigned char> bytes(rays.size() * trace_record_bytes(packed));
  if (packed.float_world) store_records<GpuTraceRayF>(rays, packed.anchor, bytes.data());
  else store_records<GpuTraceRay>(rays, glm::dvec3(0), bytes.data());
  return bytes;
}

void read_trace_records(const PackedScene& packed, std::span<const unsigned char> records,
                        std::span<TraceResult> results) {
  if (packed.float_world) load_records<GpuTraceRayF>(records, results);
  else load_records<GpuTraceRay>(records, results);
}

}  // namespace prism::gpu
