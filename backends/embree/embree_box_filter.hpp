// The boxes of a few objects, tested against one ray all at once, in
// double: for scenes with up to BoxFilter::kMaxObjects objects in the BVH,
// the closest-hit and occlusion queries use this instead of Embree's
// traversal (embree_query.cpp, "Few objects", has the error argument).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "prism/scene.hpp"

namespace prism::embree {

class BoxFilter {
 public:
  // Up to this many objects the filter is cheaper than Embree's traversal
  // with its float ray and clipping (measured in embree_query.cpp).
  static constexpr size_t kMaxObjects = 16;

  BoxFilter() = default;
  // The world boxes of `ids` (ascending), each grown by `pad` on every side.
  BoxFilter(std::span<const int32_t> ids, std::span<const Object> objects, double pad);
  // Object `id` (one of the ids) has a new world box.
  void set_box(int32_t id, const Box3& box);

  size_t size() const { return ids_.size(); }
  size_t padded_size() const { return lo_[0].size(); }
  int32_t id(size_t slot) const { return ids_[slot]; }

  // Where a ray from `origin` with inverse direction `inv` (every component
  // finite) enters and leaves each box, clipped to [t0, t1]: slot k may hold
  // a point of the ray's part [t0, t1] only if enter[k] <= leave[k]. Both
  // spans hold padded_size() values (size() rounded up to even).
  void clip(const glm::dvec3& origin, const glm::dvec3& inv, double t0, double t1, std::span<double> enter,
            std::span<double> leave) const;

 private:
  double pad_ = 0;
  std::vector<int32_t> ids_;          // ascending
  std::vector<double> lo_[3], hi_[3];  // by slot, per axis: structure of arrays, for the vector unit
};

}  // namespace prism::embree
