// The Backend interface every renderer plugin implements, and the versioned
// C entry point through which the registry finds it. No backend-specific
// type crosses this interface.
#pragma once

#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prism/scene.hpp"

namespace prism {

struct RenderSettings {
  ImageSettings image;  // the scene's, with command-line overrides applied
  // Renders from this camera instead of the scene's (an interactive viewer
  // moves it every frame without preparing the scene again).
  std::optional<Camera> camera;
  bool aov_id = false;
  bool aov_path = false;
  // Called with the fraction done (0..1) from any thread; may be empty.
  std::function<void(double)> progress;
};

// A rendered frame: linear RGB, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;   // width * height * 3
  std::vector<float> id;    // width * height when aov_id, else empty
  std::vector<float> path;  // width * height when aov_path, else empty
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

// The ray kinds of BackendStats::rays_by_kind, in the order every backend
// counts them (the CPU shader's RayKind, the GPU kernels' counters).
inline constexpr const char* kRayKindNames[] = {"camera", "shadow", "reflect", "refract", "alpha", "shade1"};

// Counters and phase times a backend reports (`--stats`).
struct BackendStats {
  std::vector<std::string> kernel_features;  // GPU backends: what was compiled in
  uint64_t rays = 0;                         // every ray traced, all kinds
  std::map<std::string, uint64_t> rays_by_kind;  // camera, shadow, reflect, refract, ...
  std::map<std::string, double> ms;              // build, compile, render, ...
  std::map<std::string, double> counters;        // e.g. GL compile/link calls
  std::map<std::string, std::string> info;       // e.g. device name, program cache hit/miss
};

class Backend {
 public:
  virtual ~Backend() = default;
  // Build acceleration structures for `scene`, which outlives the backend's use of it.
  virtual void prepare(const Scene& scene) = 0;
  virtual Image render(const RenderSettings& settings) = 0;
  virtual std::vector<TraceResult> trace(std::span<const TraceQuery> rays) = 0;
  virtual BackendStats stats() const = 0;
};

}  // namespace prism

extern "C" {

#define PRISM_BACKEND_ABI_VERSION 2u
#define PRISM_BACKEND_ENTRY_SYMBOL "prism_backend_entry"

typedef struct PrismBackendProbe {
  int usable;          // 1: can run on this machine
  char reason[256];    // why not, when usable == 0; a short description otherwise
} PrismBackendProbe;

typedef struct PrismBackendDesc {
  uint32_t abi_version;  // PRISM_BACKEND_ABI_VERSION; must stay the first member
  uint32_t desc_size;
  const char* name;
  const char* version;
  int speed_rank;  // `-b auto` picks the usable backend with the highest rank
  void (*probe)(PrismBackendProbe* out);
  // Creates the backend; throws prism::RuntimeError when it cannot start.
  prism::Backend* (*create)();
} PrismBackendDesc;

typedef const PrismBackendDesc* (*PrismBackendEntryFn)(void);
}

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
