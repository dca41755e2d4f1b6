// The host side both GPU backends share around a dispatch: how a frame is
// cut into tiles, the frame buffer's bytes, the trace kernel's ray records,
// and turning what a tile wrote back into an Image and ray counts. Only the
// API calls (GL or Vulkan) differ between the backends.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "gpu_layout.hpp"
#include "gpu_scene.hpp"
#include "kernel_source.hpp"
#include "prism/backend.hpp"

namespace prism::gpu {

// Trace kernel: 64 rays per work group, at most 65536 rays per dispatch.
constexpr int kTraceLocalSize = 64;
constexpr size_t kTraceRaysPerDispatch = 1 << 16;
// Render kernels: 8x8 work groups. On lavapipe 16x16 renders the showcase
// in the same time and 4x4 takes 1.8x as long.
constexpr int kRenderLocalSize = 8;

// The kernel options both backends build with: the work group size of the
// render or trace kernel (the one their dispatches divide by), the forced
// features (PRISM_KERNEL_FEATURES=all) and the API's glue code.
KernelOptions kernel_options(bool trace, const char* api_glue);

// Whether a backend may read the texels through a buffer texture
// (KernelOptions::texel_sampler) where they fit: yes, unless
// PRISM_GPU_TEXEL_BUFFER=0 (the tests compare the two paths).
bool texel_buffer_allowed();
// The same for the materials' uniform block (KernelOptions::material_block):
// PRISM_GPU_MATERIAL_BLOCK=0 turns it off.
bool material_block_allowed();

struct Tile {
  int x0, y0, width, height;
};

// How large a tile a device takes. A CPU driver (llvmpipe, lavapipe) gets
// about 0.25 M samples a tile, well under a second each, so a cancel or a
// progress report is never far off; a GPU gets up to 2 M (a 1920x1080 frame
// at 1 spp in one dispatch), since every tile costs a submission, a wait
// and a copy back. Either is cut further so that the output fits the
// device's largest storage buffer and 32-bit ray counters cannot overflow
// (at most `max_depth * max(1, lights)` rays of one kind a sample).
// PRISM_GPU_TILE_SAMPLES sets the samples a tile (64 .. 2^21), for tests.
// `min_tiles` cuts a frame into at least that many bands of rows: a backend
// that keeps two tiles in flight (OpenGL) stores one while the device
// renders the next.
struct TileBudget {
  long samples = 0;
  size_t max_output_bytes = 0;
  int lights = 0;
  int min_tiles = 1;
};
TileBudget tile_budget(bool cpu_device, size_t max_storage_bytes, int lights, int min_tiles = 1);

// Tile width and height for an image and spp under a budget: multiples of
// the 8x8 work group.
std::pair<int, int> tile_size(const ImageSettings& image, const TileBudget& budget);
// Every tile of the settings' region (or whole image) in row-major order,
// edge tiles clipped, in image coordinates; InputError for a bad region.
std::vector<Tile> tiles_of(const RenderSettings& settings, const TileBudget& budget);

// The output buffer's bytes for a tile of `pixels` with `planes` planes.
size_t output_bytes(size_t pixels, int planes);

// A black image (ids -1) of the requested size (the region's) and AOVs.
Image blank_image(const RenderSettings& settings);
// Copies a tile's pixels (the output's planes after the header, see
// gpu_layout.hpp) into the image: the planes `output_planes(settings)` says.
void store_tile(Image& image, const RenderSettings& settings, const float* planes, const Tile& tile);
// Where a GPU render's time goes, for `prism bench --profile` (stats keys
// "profile.<phase>"), as laps of the host's clock: set-up and submission (frame constants,
// buffers), the image's allocation (while the first tile renders), waiting
// for the device, and storing the tiles in the image. The kernel's own time
// on the device, from timestamps where the API gives them, is reported
// beside them as "profile.device: kernel" (inside the waits and the
// allocation, not a lap of its own). Off, it measures nothing.
class FrameProfile {
 public:
  explicit FrameProfile(bool on);
  void end_setup();
  void end_allocation();
  // After a tile's results are here; `kernel_ms` < 0 when not timed.
  void end_wait(double kernel_ms);
  void end_store();
  void add_to(BackendStats& stats) const;

 private:
  double lap();
  bool on_;
  std::chrono::steady_clock::time_point last_;
  double setup_ = 0, allocation_ = 0, wait_ = 0, store_ = 0, kernel_ = -1;
};

// Adds a tile's ray counters (the output buffer's header) to `stats`.
void add_ray_counters(BackendStats& stats, const uint32_t counters[kRayCounterCount]);

// The trace kernel's input records for `rays` (GpuTraceRay, or GpuTraceRayF
// with origins relative to the anchor in a float world), as bytes.
std::vector<unsigned char> trace_records(const PackedScene& packed, std::span<const TraceQuery> rays);
// Reads the kernel's answers (records as trace_records made them) back into `results`.
void read_trace_records(const PackedScene& packed, std::span<const unsigned char> records,
                        std::span<TraceResult> results);
// Bytes of one trace record.
size_t trace_record_bytes(const PackedScene& packed);

inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace prism::gpu
