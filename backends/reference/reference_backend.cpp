// The reference backend: the ground truth every other backend is judged
// against. Scalar, double precision, brute force over every object in id
// order (no acceleration structure to get wrong), the core's shading.
// With --precision float it intersects through each plugin's float
// instantiation instead (intersect_float): the CPU model of a float GPU
// kernel, which the stability suite measures; shading stays double.
#include <chrono>
#include <cstdio>

#include "prism/backend_fingerprint.hpp"
#include "prism/cpu_render.hpp"
#include "prism/primitive_abi.h"

namespace prism {
namespace {

class BruteForceQuery : public ObjectQuery {
 public:
  BruteForceQuery(const Scene& scene, IntersectEntry entry) : scene_(scene), entry_(entry) {}

  Hit closest(const Ray& ray, double tmin) const override {
    Hit best;
    for (size_t id = 0; id < scene_.objects.size(); ++id) {
      PrismHit hit;
      // Visiting ids in order and asking for t strictly below the best keeps the lower id on ties.
      double tmax = best.found() ? std::nextafter(best.t, 0.0) : kInfinity;
      if (intersect_object(scene_.objects[id], ray, tmin, tmax, hit, entry_) && hit.t < best.t) {
        best.t = hit.t;
        best.id = static_cast<int32_t>(id);
        best.prim = hit;
      }
    }
    return best;
  }

  int32_t occluder(const Ray& ray, double tmax) const override {
    for (size_t id = 0; id < scene_.objects.size(); ++id) {
      if (blocks(scene_.objects[id], ray, tmax, entry_)) return static_cast<int32_t>(id);
    }
    return kMissId;
  }

  IntersectEntry entry() const override { return entry_; }

 private:
  const Scene& scene_;
  IntersectEntry entry_;
};

class ReferenceBackend : public Backend {
 public:
  ReferenceBackend() {
    for (const char* name : {counter::kPrepares, counter::kUpdates, counter::kObjectsUploaded, counter::kBvhBuilds,
                             counter::kBvhRefits, counter::kKernelBuilds}) {
      stats_.counters[name] = 0;
    }
  }

  // Every precision: auto is double, the reference's own.
  void set_precision(Precision precision) override {
    entry_ = precision == Precision::float32 ? kIntersectFloat : kIntersectDouble;
  }

  void prepare(const Scene& scene) override {
    scene_ = &scene;
    query_ = std::make_unique<BruteForceQuery>(scene, entry_);
    stats_.info[info_key::kPrecision] = entry_ == kIntersectFloat ? "float" : "double";
    stats_.counters[counter::kSceneBytes] = double(scene.packed_object_bytes());
    stats_.counters[counter::kPrepares] += 1;
    stats_.counters[counter::kObjectsUploaded] += double(scene.objects.size());
    stats_.ms[ms_key::kBuild] = 0.0;  // nothing to build: that is the point of this backend
  }

  // The query reads the scene on every ray, so an edit needs nothing: the
  // changed objects (every object when some were added or removed) count as
  // read again.
  void update(const Scene& scene, const SceneChanges& changes) override {
    stats_.counters[counter::kUpdates] += 1;
    if (scene_ != &scene) query_ = std::make_unique<BruteForceQuery>(scene, entry_);
    scene_ = &scene;
    stats_.counters[counter::kSceneBytes] = double(scene.packed_object_bytes());
    stats_.counters[counter::kObjectsUploaded] +=
        double(changes.objects_added_or_removed ? scene.objects.size() : changes.objects.size());
  }

  Image render(const RenderSettings& settings) override { return render_cpu(*scene_, *query_, settings, stats_); }
  std::vector<TraceResult> trace(std::span<const TraceQuery> rays) override {
    return trace_cpu(*scene_, *query_, rays, stats_);
  }
  BackendStats stats() const override { return stats_; }

 private:
  const Scene* scene_ = nullptr;
  IntersectEntry entry_ = kIntersectDouble;
  std::unique_ptr<BruteForceQuery> query_;
  BackendStats stats_;
};

void probe(PrismBackendProbe* out) {
  out->usable = 1;
  std::snprintf(out->reason, sizeof out->reason, "CPU, double precision (float with --precision float), brute force");
}

Backend* create() { return new ReferenceBackend(); }

}  // namespace
}  // namespace prism

extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) {
  static constexpr PrismBackendDesc desc = prism::backend_desc("reference", "1.0.0", 10, prism::probe, prism::create);
  return &desc;
}
