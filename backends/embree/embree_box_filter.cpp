#include "embree_box_filter.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace prism::embree {

namespace {

// Vectors of 2, 4 and 8 doubles (GCC's vector extensions): the same loop
// compiles to SSE2, AVX2 or AVX-512 in the functions below.
using Doubles2 = double __attribute__((vector_size(16)));
using Doubles4 = double __attribute__((vector_size(32)));
using Doubles8 = double __attribute__((vector_size(64)));
// The lane indices __builtin_shuffle takes for each.
template <class V> struct LanesOf;
template <> struct LanesOf<Doubles2> { using type = int64_t __attribute__((vector_size(16))); };
template <> struct LanesOf<Doubles4> { using type = int64_t __attribute__((vector_size(32))); };
template <> struct LanesOf<Doubles8> { using type = int64_t __attribute__((vector_size(64))); };

// x in every lane. An out-parameter, not a return value: a vector wider
// than the baseline's may not cross a function's boundary (GCC's -Wpsabi),
// even inlined. A shuffle of lane 0, because GCC 12 turns a loop of lane
// stores, or x - V{}, into one masked move per lane.
template <class V>
[[gnu::always_inline]] inline void splat(V& v, double x) {
  v = V{};
  v[0] = x;
  v = __builtin_shuffle(v, typename LanesOf<V>::type{});
}

// Every lane computes exactly the scalar slab test: (lo - o) * inv and
// (hi - o) * inv, then min and max written as a < b ? a : b (the vector
// unit's own min and max), so every width gives the same bits.
template <class V>
[[gnu::always_inline]] inline void clip_boxes(const BoxFilter::Slabs& slabs, size_t count, const glm::dvec3& origin,
                                              const glm::dvec3& inv, double t0, double t1, double* enter,
                                              double* leave) {
  constexpr size_t kWidth = sizeof(V) / sizeof(double);
  V o[3], r[3];
  for (int a = 0; a < 3; ++a) {
    splat(o[a], origin[a]);
    splat(r[a], inv[a]);
  }
  for (size_t k = 0; k < count; k += kWidth) {  // the slabs are padded to a multiple of every width
    V t_in, t_out, lo, hi;
    splat(t_in, t0);
    splat(t_out, t1);
    for (int a = 0; a < 3; ++a) {
      std::memcpy(&lo, slabs.lo[a] + k, sizeof(V));
      std::memcpy(&hi, slabs.hi[a] + k, sizeof(V));
      const V near = (lo - o[a]) * r[a];
      const V far = (hi - o[a]) * r[a];
      const V low = far < near ? far : near, high = near < far ? far : near;
      t_in = low < t_in ? t_in : low;
      t_out = high < t_out ? high : t_out;
    }
    std::memcpy(enter + k, &t_in, sizeof(V));
    std::memcpy(leave + k, &t_out, sizeof(V));
  }
}

// The slots below `count` whose box the ray meets (enter <= leave, false
// for a NaN), bit k for slot k, read back from what clip_boxes just wrote,
// four slots at a time (one compare, one move of the sign bits), for the
// 4- and 8-wide clips alike (read back as whole 512-bit vectors instead,
// the showcase measured no faster: docs/architecture.md). The padding
// slots' boxes lie at +infinity, where a ray with no hit yet (t1 infinite)
// "meets" them: they are masked off.
#if defined(__x86_64__)
[[gnu::target("avx2")]] uint32_t slots_met(size_t count, const double* enter, const double* leave) {
  uint32_t met = 0;
  for (size_t k = 0; k < count; k += 4) {
    const __m256d meets = _mm256_cmp_pd(_mm256_loadu_pd(enter + k), _mm256_loadu_pd(leave + k), _CMP_LE_OQ);
    met |= uint32_t(_mm256_movemask_pd(meets)) << k;
  }
  return count >= 32 ? met : met & ((1u << count) - 1);
}
#endif

uint32_t clip2(const BoxFilter::Slabs& s, size_t n, const glm::dvec3& o, const glm::dvec3& inv, double t0, double t1,
               double* enter, double* leave) {
  clip_boxes<Doubles2>(s, n, o, inv, t0, t1, enter, leave);
  uint32_t met = 0;
  for (size_t k = 0; k < n; ++k) met |= uint32_t(enter[k] <= leave[k]) << k;
  return met;
}

#if defined(__x86_64__)
[[gnu::target("avx2")]] uint32_t clip4(const BoxFilter::Slabs& s, size_t n, const glm::dvec3& o,
                                       const glm::dvec3& inv, double t0, double t1, double* enter, double* leave) {
  clip_boxes<Doubles4>(s, n, o, inv, t0, t1, enter, leave);
  return slots_met(n, enter, leave);
}

[[gnu::target("avx512f")]] uint32_t clip8(const BoxFilter::Slabs& s, size_t n, const glm::dvec3& o,
                                          const glm::dvec3& inv, double t0, double t1, double* enter, double* leave) {
  clip_boxes<Doubles8>(s, n, o, inv, t0, t1, enter, leave);
  return slots_met(n, enter, leave);
}
#endif

}  // namespace

std::vector<int> BoxFilter::clip_widths() {
  std::vector<int> widths = {2};
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx2")) widths.push_back(4);
  if (__builtin_cpu_supports("avx512f")) widths.push_back(8);
#endif
  return widths;
}

BoxFilter::ClipFunction BoxFilter::clip_function(int width) {
  switch (width) {
#if defined(__x86_64__)
    case 4: return &clip4;
    case 8: return &clip8;
#endif
    default: return &clip2;
  }
}

BoxFilter::BoxFilter(std::span<const int32_t> ids, std::span<const Object> objects, double pad)
    : pad_(pad), ids_(ids.begin(), ids.end()), clip_(clip_function(clip_widths().back())) {
  // A length the widest vector divides; the spare slots' boxes, at
  // +infinity, meet no ray with a finite inverse direction.
  const size_t slots = (ids_.size() + kSlotMultiple - 1) / kSlotMultiple * kSlotMultiple;
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

uint32_t BoxFilter::clip(const glm::dvec3& origin, const glm::dvec3& inv, double t0, double t1, std::span<double> enter,
                         std::span<double> leave, int width) const {
  const ClipFunction f = width == 0 ? clip_ : clip_function(width);
  const Slabs slabs{{lo_[0].data(), lo_[1].data(), lo_[2].data()}, {hi_[0].data(), hi_[1].data(), hi_[2].data()}};
  return f(slabs, ids_.size(), origin, inv, t0, t1, enter.data(), leave.data());
}

}  // namespace prism::embree
