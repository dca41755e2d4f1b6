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
  size_t padded_size() const { return lo_[0].size(); }  // size() rounded up to a multiple of 8
  int32_t id(size_t slot) const { return ids_[slot]; }

  // Where a ray from `origin` with inverse direction `inv` (every component
  // finite) enters and leaves each box, clipped to [t0, t1]: slot k may hold
  // a point of the ray's part [t0, t1] only if enter[k] <= leave[k]. Both
  // spans hold padded_size() values. Returns those slots (below size()) as
  // a mask, bit k for slot k: a caller visits only them (most rays enter
  // one box or none) instead of comparing every slot again. `width` picks
  // the vector width (2, 4 or 8 doubles, one of clip_widths()); 0, the
  // widest this processor has. Every width gives the same bits.
  uint32_t clip(const glm::dvec3& origin, const glm::dvec3& inv, double t0, double t1, std::span<double> enter,
                std::span<double> leave, int width = 0) const;
  // The vector widths this processor runs: 2 (SSE2), then 4 (AVX2) and 8
  // (AVX-512F) where it has them. On the showcase (8 boxes) width 4 took
  // the clip from 14.4 M to 7.6 M of a 320x180 frame's 256 M instructions
  // (callgrind, which has no AVX-512).
  static std::vector<int> clip_widths();

  // The boxes' slabs by axis, for the vector loops of the .cpp.
  struct Slabs {
    const double* lo[3];
    const double* hi[3];
  };

 private:
  static constexpr size_t kSlotMultiple = 8;  // the widest vector's doubles
  static_assert(kMaxObjects % kSlotMultiple == 0, "callers size their arrays by kMaxObjects");
  static_assert(kMaxObjects <= 32, "clip's mask has a bit a slot");
  using ClipFunction = uint32_t (*)(const Slabs&, size_t, const glm::dvec3&, const glm::dvec3&, double, double,
                                    double*, double*);
  static ClipFunction clip_function(int width);

  double pad_ = 0;
  std::vector<int32_t> ids_;          // ascending
  std::vector<double> lo_[3], hi_[3];  // by slot, per axis: structure of arrays, for the vector unit
  ClipFunction clip_ = nullptr;       // the widest of clip_widths()
};

}  // namespace prism::embree
