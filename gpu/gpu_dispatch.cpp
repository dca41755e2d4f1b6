#include "gpu_dispatch.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <type_traits>

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
constexpr long kSamplesPerTile = 1 << 18;
// gpu/kernel.glsl scrambles a tile's work groups as k * kGroupScramblePrime mod n
// in 32 bits: the product must fit, and the prime must exceed the group count.
constexpr uint64_t kMaxGroupsPerTile = kSamplesPerTile / (kRenderLocalSize * kRenderLocalSize);
static_assert(kMaxGroupsPerTile * kGroupScramblePrime < (uint64_t(1) << 32) && kMaxGroupsPerTile < kGroupScramblePrime);
}

std::pair<int, int> tile_size(const ImageSettings& image) {
  const long pixels = std::max<long>(64, kSamplesPerTile / image.spp);
  const int w = (std::min(image.width, 512) + 7) / 8 * 8;
  const int h = int(std::max<long>(8, pixels / w / 8 * 8));
  return {w, std::min(h, (image.height + 7) / 8 * 8)};
}

std::vector<Tile> tiles_of(const RenderSettings& settings) {
  check_region(settings);
  const auto [tw, th] = tile_size(settings.image);
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
  image.rgb.assign(n * 3, 0.0f);
  assign_aovs(image, settings);
  return image;
}

void store_tile(Image& image, const RenderSettings& settings, const GpuPixel* pixels, const Tile& tile) {
  const PixelRect r = render_rect(settings);
  for (int j = 0; j < tile.height; ++j) {
    for (int i = 0; i < tile.width; ++i) {
      const GpuPixel& px = pixels[size_t(j) * tile.width + i];
      const size_t p = size_t(tile.y0 - r.y + j) * size_t(image.width) + size_t(tile.x0 - r.x + i);
      std::copy_n(px.rgb, 3, &image.rgb[p * 3]);
      if (settings.aov_id) image.id[p] = px.id;
      if (settings.aov_path) image.path[p] = px.path;
      if (settings.aov_depth) image.depth[p] = px.depth;
      if (settings.aov_normal) std::copy_n(px.normal, 3, &image.normal[p * 3]);
      if (settings.aov_albedo) std::copy_n(px.albedo, 3, &image.albedo[p * 3]);
    }
  }
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
