#include "embree_box_filter.hpp"

#include <algorithm>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace prism::embree {

BoxFilter::BoxFilter(std::span<const int32_t> ids, std::span<const Object> objects, double pad)
    : pad_(pad), ids_(ids.begin(), ids.end()) {
  // An even length for the two-wide loop; the spare slot's box, at
  // +infinity, meets no ray with a finite inverse direction.
  const size_t slots = ids_.size() + ids_.size() % 2;
  for (int a = 0; a < 3; ++a) {
    lo_[a].assign(slots, std::numeric_limits<double>::infinity());
    hi_[a].assign(slots, std::numeric_limits<double>::infinity());
  }
  for (const int32_t id : ids_) set_box(id, objects[size_t(id)].world_bounds);
}

void BoxFilter::set_box(int32_t id, const Box3& box) {
  const size_t slot = size_t(std::ranges::lower_bound(ids_, id) - ids_.begin());
  for (int a = 0; a < 3; ++a) {
    lo_[a][slot] = box.lo[a] - pad_;
    hi_[a][slot] = box.hi[a] + pad_;
  }
}

#if defined(__SSE2__)
// Two boxes at a time. _mm_min_pd(a, b) is (a < b ? a : b) lane by lane,
// exactly the scalar form below, so both give the same bits.
void BoxFilter::clip(const glm::dvec3& origin, const glm::dvec3& inv, double t0, double t1, std::span<double> enter,
                     std::span<double> leave) const {
  const __m128d o[3] = {_mm_set1_pd(origin.x), _mm_set1_pd(origin.y), _mm_set1_pd(origin.z)};
  const __m128d r[3] = {_mm_set1_pd(inv.x), _mm_set1_pd(inv.y), _mm_set1_pd(inv.z)};
  for (size_t k = 0; k < ids_.size(); k += 2) {  // the arrays are padded to an even length
    __m128d t_in = _mm_set1_pd(t0), t_out = _mm_set1_pd(t1);
    for (int a = 0; a < 3; ++a) {
      const __m128d near = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&lo_[a][k]), o[a]), r[a]);
      const __m128d far = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(&hi_[a][k]), o[a]), r[a]);
      t_in = _mm_max_pd(_mm_min_pd(far, near), t_in);     // max(t_in, min(near, far)), NaN-free
      t_out = _mm_min_pd(_mm_max_pd(far, near), t_out);
    }
    _mm_storeu_pd(&enter[k], t_in);
    _mm_storeu_pd(&leave[k], t_out);
  }
}
#else
void BoxFilter::clip(const glm::dvec3& origin, const glm::dvec3& inv, double t0, double t1, std::span<double> enter,
                     std::span<double> leave) const {
  for (size_t k = 0; k < ids_.size(); ++k) {
    double t_in = t0, t_out = t1;
    for (int a = 0; a < 3; ++a) {
      const double near = (lo_[a][k] - origin[a]) * inv[a], far = (hi_[a][k] - origin[a]) * inv[a];
      const double low = far < near ? far : near, high = near < far ? far : near;
      t_in = low < t_in ? t_in : low;
      t_out = high < t_out ? high : t_out;
    }
    enter[k] = t_in;
    leave[k] = t_out;
  }
}
#endif

}  // namespace prism::embree
