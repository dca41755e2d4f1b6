// Closest-hit and occlusion queries over a scene's objects in double
// precision. Embree's float32 BVH only chooses which bounded objects a ray
// may hit; every hit is computed and compared in double by the primitive
// plugins (prism::intersect_object). Unbounded objects (planes, unclipped
// quadrics) and a few outsized ones are tested beside the BVH, brute force.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "embree_device.hpp"
#include "prism/cpu_render.hpp"

namespace prism::embree {

// Embree's coordinates: world - center, every float box grown by `pad`
// (the error bound is derived in embree_query.cpp).
struct Frame {
  glm::dvec3 center{0};  // C, the middle of the BVH objects' union box
  glm::dvec3 half{0};    // half extents of that box
  double pad = 0;
};

class EmbreeQuery final : public ObjectQuery {
 public:
  // Builds the BVH over `scene`'s bounded objects; `scene` and `device`
  // must outlive the query. Throws RuntimeError on an Embree error.
  EmbreeQuery(const Scene& scene, Device& device);
  ~EmbreeQuery() override;

  Hit closest(const Ray& ray, double tmin) const override;
  int32_t occluder(const Ray& ray, double tmax) const override;

  const Frame& frame() const { return frame_; }
  size_t bvh_object_count() const { return bvh_ids_.size(); }
  size_t brute_force_count() const { return brute_ids_.size(); }
  size_t geometry_count() const { return groups_.size(); }

  struct TypeGroup;  // the objects of one primitive type: one RTC user geometry

 private:
  struct SceneDeleter {
    void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
  };
  void build(Device& device);
  // [t0, t1]: the part of the ray inside the BVH's box grown by 2 * pad.
  bool clip(const Ray& ray, double& t0, double& t1) const;
  // Whether the double arithmetic that moves the origin to world t = shift
  // stays far inside the padding (else the ray takes the brute-force path).
  bool shift_is_exact_enough(const Ray& ray, double shift) const;

  const Scene& scene_;
  Frame frame_;
  std::vector<int32_t> bvh_ids_;    // ascending
  std::vector<int32_t> brute_ids_;  // ascending: unbounded objects and outliers
  std::vector<std::unique_ptr<TypeGroup>> groups_;
  std::unique_ptr<RTCSceneTy, SceneDeleter> rtc_;
};

}  // namespace prism::embree
