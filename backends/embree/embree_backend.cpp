// The Embree backend: Embree's BVH picks the candidate objects, the plugins
// intersect them in double (embree_query.hpp), and the core's CPU path
// (cpu_render.hpp) does cameras, light spheres and shading.

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>

#include "embree_device.hpp"
#include "embree_query.hpp"
#include "embree_update.hpp"
#include "prism/backend.hpp"
#include "prism/backend_fingerprint.hpp"
#include "prism/cpu_render.hpp"
#include "prism/errors.hpp"
#include "prism/primitive_abi.h"

namespace prism::embree {
namespace {

// Updates (embree_update.hpp) either layer the moved objects over the main
// tree, which costs microseconds but slows every later ray a little, or
// build the BVH again. Measured on this 2-core machine (quiet to loaded): a
// build costs ~0.3-0.6 us per BVH object (0.1 ms for 294 spheres, 3-7 ms
// for 10,000, 35-60 ms for 100,000); the layers ~0.02-0.09 us per ray
// (+2-6 ms per 100,000 rays of the 10,000-sphere field, +4-9 ms on 100,000
// spheres). Break-even lies between ~5 and ~30 rays per object in a frame,
// so an update layers while the last frame traced fewer than
// kLayerRaysPerObject rays per BVH object: a 64x48 frame of 10,000 spheres
// layers, a 640x360 one (~1 M rays) builds again, and a 640x360 frame of
// 100,000 spheres layers.
constexpr double kLayerRaysPerObject = 15;

class EmbreeBackend final : public Backend {
 public:
  EmbreeBackend() {
    for (const char* name : {counter::kPrepares, counter::kUpdates, counter::kObjectsUploaded, counter::kBvhBuilds,
                             counter::kBvhRefits, counter::kKernelBuilds}) {
      stats_.counters[name] = 0;
    }
  }

  void prepare(const Scene& scene) override {
    build(scene);
    stats_.counters[counter::kPrepares] += 1;
  }

  // Objects added or removed, or an edit EmbreeQuery::update refuses, build
  // the BVH again (every object read again); other object edits update it in
  // place (counted as a refit: the main tree is kept). Materials, lights,
  // textures and the environment are read from the scene at render time.
  void update(const Scene& scene, const SceneChanges& changes) override {
    stats_.counters[counter::kUpdates] += 1;
    if (query_ == nullptr || scene_ != &scene || changes.objects_added_or_removed) {
      build(scene);
      return;
    }
    if (changes.objects.empty()) return;
    const auto start = std::chrono::steady_clock::now();
    UpdateResult result = UpdateResult::kNeedsBuild;
    try {
      const bool layer = double(last_frame_rays_) < kLayerRaysPerObject * double(query_->bvh_object_count());
      result = query_->update(changes.objects, layer);
    } catch (...) {
      query_.reset();  // half updated: unusable
      scene_ = nullptr;
      throw;
    }
    if (result == UpdateResult::kNeedsBuild) {
      build(scene);
      return;
    }
    stats_.counters[counter::kObjectsUploaded] += double(changes.objects.size());
    stats_.counters[counter::kBvhRefits] += result == UpdateResult::kUpdated ? 1 : 0;
    stats_.counters[counter::kSceneBytes] = double(device_.bytes()) + double(scene.packed_object_bytes());
    stats_.ms[ms_key::kUpdate] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  Image render(const RenderSettings& settings) override {
    require_prepared();
    const uint64_t before = stats_.rays;
    query_->prepare_views((settings.camera ? *settings.camera : scene_->camera).position);
    Image image = render_cpu(*scene_, *query_, settings, stats_);
    last_frame_rays_ = stats_.rays - before;
    device_.check("rendering");
    return image;
  }

  std::vector<TraceResult> trace(std::span<const TraceQuery> rays) override {
    require_prepared();
    const uint64_t before = stats_.rays;
    std::vector<TraceResult> results = trace_cpu(*scene_, *query_, rays, stats_);
    last_frame_rays_ = stats_.rays - before;
    device_.check("tracing");
    return results;
  }

  BackendStats stats() const override { return stats_; }

 private:
  void require_prepared() const {
    if (query_ == nullptr) throw RuntimeError("embree backend: prepare() was not called");
  }

  void build(const Scene& scene) {
    query_.reset();
    scene_ = nullptr;
    const auto start = std::chrono::steady_clock::now();
    query_ = std::make_unique<EmbreeQuery>(scene, device_);
    stats_.info[info_key::kPrecision] = "double";
    stats_.counters[counter::kSceneBytes] = double(device_.bytes()) + double(scene.packed_object_bytes());
    stats_.counters[counter::kObjectsUploaded] += double(scene.objects.size());
    stats_.counters[counter::kBvhBuilds] += query_->bvh_object_count() > 0 ? 1 : 0;
    stats_.ms[ms_key::kBuild] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    scene_ = &scene;
  }

  Device device_;
  const Scene* scene_ = nullptr;
  uint64_t last_frame_rays_ = 0;  // rays the last render() or trace() traced
  std::unique_ptr<EmbreeQuery> query_;
  BackendStats stats_;
};

void probe(PrismBackendProbe* out) {
  probe_by_starting(out, [] { return "Embree " + Device().describe(); });
}

Backend* create() { return new EmbreeBackend(); }

constexpr PrismBackendDesc kDesc = backend_desc("embree", "1.0.0 (Embree " RTC_VERSION_STRING ")",
                                                 50,  // above the reference backend (10)
                                                 &probe, &create);

}  // namespace
}  // namespace prism::embree

extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) { return &prism::embree::kDesc; }
