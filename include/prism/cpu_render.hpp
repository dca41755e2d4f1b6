// The CPU rendering path shared by the reference and Embree backends: they
// supply only the closest-hit and occlusion queries over the scene's objects;
// camera, sampling, light spheres and the whole of the spec's shading live
// here, once.
#pragma once

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "prism/backend.hpp"
#include "prism/geometry.hpp"

namespace prism {

// Up to two objects a shadow ray is known to miss: the convex object it
// leaves (PRISM_PRIMITIVE_CONVEX, from a front-facing hit) and one the
// caller has just tested. kMissId: none.
struct KnownClear {
  int32_t self = kMissId;
  int32_t tested = kMissId;
  bool has(int32_t id) const { return id == self || id == tested; }
};

// Rays as structure of arrays: ray j starts at (origin[0][j], origin[1][j],
// origin[2][j]) and runs along dir (unit length), up to tmax[j].
struct RayLanes {
  std::array<const double*, 3> origin{}, dir{};
  const double* tmax = nullptr;
  size_t count = 0;
};

class ObjectQuery {
 public:
  virtual ~ObjectQuery() = default;
  // Closest object hit with t > tmin (ties: lower object id). Light spheres excluded.
  virtual Hit closest(const Ray& ray, double tmin) const = 0;
  // The id of an object hit with 0 < t < tmax (any one), or kMissId.
  virtual int32_t occluder(const Ray& ray, double tmax) const = 0;
  // closest(ray, 0) for a camera ray, and occluder() for a shadow ray toward
  // scene light `light`. A backend may answer these from data it prepared
  // for the frame's camera and lights; the answers are the same.
  virtual Hit camera_closest(const Ray& ray) const { return closest(ray, 0.0); }
  // camera_closest for many camera rays at once (one tile's, as a rule):
  // hits[j] is camera_closest(rays[j]), bit for bit. A backend may share
  // work between them (one candidate list, one plugin call per packet).
  virtual void camera_closest_batch(std::span<const Ray> rays, Hit* hits) const {
    for (size_t j = 0; j < rays.size(); ++j) hits[j] = camera_closest(rays[j]);
  }
  // closest(ray, 0) for a ray that leaves a convex object's front face
  // outward (a reflected ray): that object, `self`, cannot be hit and a
  // query may skip it (kMissId: none).
  virtual Hit closest_leaving(const Ray& ray, int32_t self) const {
    (void)self;
    return closest(ray, 0.0);
  }
  // closest_leaving for many rays: hits[j] is closest_leaving(rays[j],
  // self[j]), bit for bit (its prim only where it holds an object's hit).
  // A backend may write each answer in place rather than return it.
  virtual void closest_leaving_batch(std::span<const Ray> rays, const int32_t* self, Hit* hits) const {
    for (size_t j = 0; j < rays.size(); ++j) hits[j] = closest_leaving(rays[j], self[j]);
  }
  // `clear` names objects the caller already knows do not block the ray; a
  // query may skip them (the answer is the same).
  virtual int32_t light_occluder(size_t light, const Ray& ray, double tmax, KnownClear clear = {}) const {
    (void)light;
    (void)clear;
    return occluder(ray, tmax);
  }
  // Many shadow rays toward `light` at once: what light_occluder looks up
  // for a ray before it tests objects, computed for every ray of `rays` (a
  // backend's own key, into keys[j]; kUnkeyed by default), so the lookups
  // run in the vector unit's lanes. keyed_light_occluder then answers ray j
  // as light_occluder does. kUnkeyed says the query has nothing cheaper for
  // the ray than its full search: the caller may then try a likely blocker
  // of its own first.
  static constexpr int32_t kUnkeyed = -1;
  virtual void light_keys(size_t light, const RayLanes& rays, int32_t* keys) const {
    (void)light;
    std::fill_n(keys, rays.count, kUnkeyed);
  }
  virtual int32_t keyed_light_occluder(size_t light, const Ray& ray, double tmax, KnownClear clear,
                                       int32_t key) const {
    (void)key;
    return light_occluder(light, ray, tmax, clear);
  }
  // keyed_light_occluder for every ray j of `rays` with cast[j] set, all at
  // once: blockers[j] is keyed_light_occluder(light, ray j, rays.tmax[j],
  // {self[j], kMissId}, keys[j]), the same object; kMissId where cast[j] is
  // 0. A backend may share work between rays of one key (one candidate list,
  // one plugin call per packet).
  virtual void keyed_light_occluders(size_t light, const RayLanes& rays, const int32_t* keys, const int32_t* self,
                                     const uint8_t* cast, int32_t* blockers) const {
    for (size_t j = 0; j < rays.count; ++j) {
      if (!cast[j]) {
        blockers[j] = kMissId;
        continue;
      }
      const Ray ray{{rays.origin[0][j], rays.origin[1][j], rays.origin[2][j]},
                    {rays.dir[0][j], rays.dir[1][j], rays.dir[2][j]}};
      blockers[j] = keyed_light_occluder(light, ray, rays.tmax[j], {self[j], kMissId}, keys[j]);
    }
  }
  // True when any object is hit with 0 < t < tmax.
  bool occluded(const Ray& ray, double tmax) const { return occluder(ray, tmax) != kMissId; }
  // The plugin entry the queries intersect with; the shading path's own
  // tests of one object (the last blocker, the surface's polish) follow it.
  virtual IntersectEntry entry() const { return kIntersectDouble; }
};

// Renders the whole image, tiles in parallel (TBB) unless `parallel` is false.
// The result does not depend on the thread count.
Image render_cpu(const Scene& scene, const ObjectQuery& query, const RenderSettings& settings,
                 BackendStats& stats, bool parallel = true);

// `prism trace` semantics: closest hit with t > tmin, light spheres included.
std::vector<TraceResult> trace_cpu(const Scene& scene, const ObjectQuery& query,
                                   std::span<const TraceQuery> rays, BackendStats& stats);

}  // namespace prism
