// The Backend interface every renderer plugin implements, and the entry
// point through which the registry finds it. No backend-specific type
// crosses this interface.
//
// The boundary is a C++ plugin interface, not a C one: the scene, settings
// and results that cross it are C++ types (vectors, strings, paths,
// std::function) and `create` returns a C++ object. Only the entry symbol
// has C linkage, so that dlsym finds it by an unmangled name. A backend
// therefore works only with a core whose compiler, standard library and
// type layouts are its own: the descriptor carries a fingerprint of them
// (prism/backend_fingerprint.hpp), which the registry compares with its
// own before it reads anything else.
#pragma once

#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "prism/scene.hpp"
#include "prism/stats_keys.hpp"

namespace prism {

// A rectangle of an image's pixels; (x, y) is its top-left pixel.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
  friend bool operator==(const PixelRect&, const PixelRect&) = default;
};

struct RenderSettings {
  ImageSettings image;  // the scene's, with command-line overrides applied
  // Renders only these pixels of the image (a tile of a distributed render):
  // the Image is region-sized, its row 0 the region's top row, and every
  // pixel equals the same pixel of a whole-image render, bit for bit.
  std::optional<PixelRect> region;
  // Renders from this camera instead of the scene's (an interactive viewer
  // moves it every frame without preparing the scene again).
  std::optional<Camera> camera;
  bool aov_id = false;
  bool aov_path = false;
  // Sample 0's first hit (docs/scene-format.md, "Output files and image
  // channels"): its t, its outward normal, its surface colour.
  bool aov_depth = false;
  bool aov_normal = false;
  bool aov_albedo = false;
  // Called with the fraction done (0..1) from any thread; may be empty.
  std::function<void(double)> progress;
  // Called, as `progress` is and just before it, with the rays this call has
  // traced so far (all kinds, as BackendStats::rays counts them), so that a
  // front end can show the ray rate while the first frame renders. May be empty.
  std::function<void(uint64_t)> rays_traced;
  // Time the phases of the frame (backends that can: BackendStats::ms
  // "profile.<phase>", milliseconds summed over threads). Off by default:
  // the clock reads cost a few percent.
  bool profile = false;
};

// A rendered frame: linear RGB, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;   // width * height * 3
  std::vector<float> id;    // width * height when aov_id, else empty
  std::vector<float> path;  // width * height when aov_path, else empty
  std::vector<float> depth;   // width * height when aov_depth (+inf on a miss), else empty
  std::vector<float> normal;  // width * height * 3 when aov_normal (0 on a miss), else empty
  std::vector<float> albedo;  // width * height * 3 when aov_albedo (0 on a miss), else empty
};

struct TraceQuery {
  glm::dvec3 origin{0};
  glm::dvec3 dir{0, 0, 1};  // normalized by the caller
  double tmin = 0.0;
};

struct TraceResult {
  double t = 0;        // +inf on a miss
  int32_t id = -1;     // object id, -2-k for light k's sphere, -1 miss
  glm::dvec3 normal{0};  // outward unit normal, 0 on a miss
};

// Counters and phase times a backend reports (`--stats`), under the keys of
// prism/stats_keys.hpp.
struct BackendStats {
  std::vector<std::string> kernel_features;  // GPU backends: what was compiled in
  uint64_t rays = 0;                         // every ray traced, all kinds
  std::map<std::string, uint64_t> rays_by_kind;  // camera, shadow, reflect, refract, ...
  std::map<std::string, double> ms;              // build, compile, render, ...
  std::map<std::string, double> counters;        // e.g. GL compile/link calls
  std::map<std::string, std::string> info;       // e.g. device name, program cache hit/miss
};

// What changed in a prepared scene since the backend last saw it (the
// library API's live updates, prism/api.hpp). The Scene is the same object
// the backend prepared, edited in place.
struct SceneChanges {
  // Objects whose record, frame or material changed; ids unchanged. Ascending, unique.
  std::vector<uint32_t> objects;
  bool objects_added_or_removed = false;  // ids may have shifted: what holds objects is rebuilt
  bool materials = false;   // a material changed or was added
  bool lights = false;      // a light changed, was added or removed
  bool textures = false;    // a texture was added
  bool environment = false; // background, ambient or shadow_ambient
  bool any() const {
    return !objects.empty() || objects_added_or_removed || materials || lights || textures || environment;
  }
};

// What a backend calls each time a piece of the frame is done: `rays_traced`
// with the rays traced so far in this call, then `progress` with the fraction done.
inline void report_progress(const RenderSettings& settings, double fraction, uint64_t rays) {
  if (settings.rays_traced) settings.rays_traced(rays);
  if (settings.progress) settings.progress(fraction);
}

// The pixels a render covers: the region, or the whole image.
inline PixelRect render_rect(const RenderSettings& settings) {
  return settings.region.value_or(PixelRect{0, 0, settings.image.width, settings.image.height});
}

// `channel.assign(n, value)`, with the new memory of a large channel mapped
// in one call before the fill (Linux's MADV_POPULATE_WRITE) instead of one
// page fault at a time: a fresh 1280x720 RGB frame (11 MB, ~2700 pages)
// took 5.2-5.6 ms that way on the 2-core VM, 3.0-3.6 ms this way. Where
// the kernel lacks it the fill faults the pages in as before.
void assign_channel(std::vector<float>& channel, size_t n, float value);

// Sizes the AOV channels `settings` asks for to `image`'s pixels, each with
// its value for a pixel no ray reached: id -1, path 0, depth +inf, normal
// and albedo 0.
inline void assign_aovs(Image& image, const RenderSettings& settings) {
  const size_t n = size_t(image.width) * size_t(image.height);
  if (settings.aov_id) assign_channel(image.id, n, -1.0f);
  if (settings.aov_path) assign_channel(image.path, n, 0.0f);
  if (settings.aov_depth) assign_channel(image.depth, n, std::numeric_limits<float>::infinity());
  if (settings.aov_normal) assign_channel(image.normal, n * 3, 0.0f);
  if (settings.aov_albedo) assign_channel(image.albedo, n * 3, 0.0f);
}

// InputError unless the region lies inside the image and is not empty.
void check_region(const RenderSettings& settings);

// The arithmetic a backend intersects in (`--precision`). `float32` runs
// each plugin's float instantiation (PrismPrimitiveDesc::intersect_float on
// the CPU); `float64` the double one; `automatic` lets the backend choose
// (every backend today: double).
enum class Precision { automatic, float32, float64 };

// "auto", "float", "double": the `--precision` spellings.
const char* precision_name(Precision precision);
// The Precision spelt `text`, or nullopt.
std::optional<Precision> parse_precision(std::string_view text);

class Backend {
 public:
  virtual ~Backend() = default;
  // Called before prepare. The default accepts automatic and float64 and
  // throws InputError for float32: a backend with a float path overrides it.
  virtual void set_precision(Precision precision);
  // Build acceleration structures for `scene`, which outlives the backend's use of it.
  virtual void prepare(const Scene& scene) = 0;
  // Brings the backend up to date with `scene` (the one last prepared, edited
  // in place) after `changes`. A backend that cannot do better prepares again.
  virtual void update(const Scene& scene, const SceneChanges& changes) {
    (void)changes;
    prepare(scene);
  }
  virtual Image render(const RenderSettings& settings) = 0;
  virtual std::vector<TraceResult> trace(std::span<const TraceQuery> rays) = 0;
  virtual BackendStats stats() const = 0;
};

}  // namespace prism

// 3: Backend::update; 4: RenderSettings::profile; 5: PrismBackendDesc::layout_fingerprint;
// 6: Backend::set_precision; 7: ObjectQuery::light_keys and keyed_light_occluder;
// 8: ObjectQuery::camera_closest_batch and keyed_light_occluders; 9: ObjectQuery::closest_leaving_batch
#define PRISM_BACKEND_ABI_VERSION 9u
#define PRISM_BACKEND_ENTRY_SYMBOL "prism_backend_entry"

struct PrismBackendProbe {
  int usable;          // 1: can run on this machine
  char reason[256];    // why not, when usable == 0; a short description otherwise
};

// What a backend plugin's entry function returns. Build it with
// prism::backend_desc (prism/backend_fingerprint.hpp), which fills in the
// first three members as the plugin is compiled.
struct PrismBackendDesc {
  uint32_t abi_version;  // PRISM_BACKEND_ABI_VERSION; must stay the first member
  uint32_t desc_size;
  // prism::backend_layout_fingerprint() as the plugin saw it; at offset 8 in
  // every version from 5 on, checked right after abi_version.
  uint64_t layout_fingerprint;
  const char* name;
  const char* version;
  int speed_rank;  // `-b auto` picks the usable backend with the highest rank
  void (*probe)(PrismBackendProbe* out);
  // Creates the backend; throws prism::RuntimeError when it cannot start.
  prism::Backend* (*create)();
};

// The entry function (C linkage, named PRISM_BACKEND_ENTRY_SYMBOL).
typedef const PrismBackendDesc* (*PrismBackendEntryFn)(void);

namespace prism {

// A probe that tries to start what the backend needs: `describe()` returns a
// short description of what it found (the device, the library version), or
// throws with the reason the backend cannot run here.
template <class Describe>
void probe_by_starting(PrismBackendProbe* out, Describe describe) noexcept {
  try {
    const std::string found = describe();
    out->usable = 1;
    std::snprintf(out->reason, sizeof out->reason, "%s", found.c_str());
  } catch (const std::exception& e) {
    out->usable = 0;
    std::snprintf(out->reason, sizeof out->reason, "%s", e.what());
  }
}

}  // namespace prism
