// The Embree backend: Embree's BVH picks the candidate objects, the plugins
// intersect them in double (embree_query.hpp), and the core's CPU path
// (cpu_render.hpp) does cameras, light spheres and shading.

#include <chrono>
#include <cstdio>
#include <memory>

#include "embree_device.hpp"
#include "embree_query.hpp"
#include "prism/backend.hpp"
#include "prism/cpu_render.hpp"
#include "prism/errors.hpp"
#include "prism/primitive_abi.h"

namespace prism::embree {
namespace {

class EmbreeBackend final : public Backend {
 public:
  void prepare(const Scene& scene) override {
    query_.reset();
    const auto start = std::chrono::steady_clock::now();
    query_ = std::make_unique<EmbreeQuery>(scene, device_);
    stats_.info["precision"] = "double";
    stats_.counters["scene_bytes"] = double(device_.bytes()) + double(scene.packed_object_bytes());
    stats_.ms["build"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    scene_ = &scene;
  }

  Image render(const RenderSettings& settings) override {
    require_prepared();
    Image image = render_cpu(*scene_, *query_, settings, stats_);
    device_.check("rendering");
    return image;
  }

  std::vector<TraceResult> trace(std::span<const TraceQuery> rays) override {
    require_prepared();
    std::vector<TraceResult> results = trace_cpu(*scene_, *query_, rays, stats_);
    device_.check("tracing");
    return results;
  }

  BackendStats stats() const override { return stats_; }

 private:
  void require_prepared() const {
    if (query_ == nullptr) throw RuntimeError("embree backend: prepare() was not called");
  }

  Device device_;
  const Scene* scene_ = nullptr;
  std::unique_ptr<EmbreeQuery> query_;
  BackendStats stats_;
};

void probe(PrismBackendProbe* out) {
  probe_by_starting(out, [] { return "Embree " + Device().describe(); });
}

Backend* create() { return new EmbreeBackend(); }

constexpr PrismBackendDesc kDesc = {
    PRISM_BACKEND_ABI_VERSION,
    sizeof(PrismBackendDesc),
    "embree",
    "1.0.0 (Embree " RTC_VERSION_STRING ")",
    50,  // above the reference backend (10)
    &probe,
    &create,
};

}  // namespace
}  // namespace prism::embree

extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) { return &prism::embree::kDesc; }
