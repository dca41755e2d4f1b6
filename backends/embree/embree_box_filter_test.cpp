// BoxFilter (embree_box_filter.hpp) against an exact slab test in long
// double: a ray's part that meets a box is never filtered out, one that
// passes a box by a clear margin is.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "embree_box_filter.hpp"
#include "embree_test_scenes.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

// Where the line o + t d enters and leaves `box`, in long double; empty
// (enter > leave) where it misses.
std::pair<long double, long double> exact_clip(const glm::dvec3& o, const glm::dvec3& d, const Box3& box) {
  long double enter = -1e300L, leave = 1e300L;
  for (int a = 0; a < 3; ++a) {
    const long double near = ((long double)box.lo[a] - o[a]) / d[a], far = ((long double)box.hi[a] - o[a]) / d[a];
    enter = std::max(enter, std::min(near, far));
    leave = std::min(leave, std::max(near, far));
  }
  return {enter, leave};
}

// Boxes near the origin and small ones far from it; rays through points on
// their faces, edges and corners or inside them, from near and from far:
// each keeps its box, and the same ray ended just before the padded box
// (1e-9 relative) drops it, so the filter is tight as well as safe.
TEST(BoxFilter, KeepsEveryBoxTheRayMeetsAndDropsTheOnesItPassesBy) {
  Rng rng(21);
  int kept = 0, dropped = 0;
  for (const auto& [offset, scale] : {std::pair{glm::dvec3(0), 1.0}, std::pair{glm::dvec3(1e4, -2e3, 3e3), 1e-2}}) {
    std::vector<Object> objects(BoxFilter::kMaxObjects - 1);  // odd: the spare slot is used
    std::vector<int32_t> ids;
    for (size_t i = 0; i < objects.size(); ++i) {
      const glm::dvec3 c = offset + scale * glm::dvec3(uniform(rng, -6, 6), uniform(rng, -6, 6), uniform(rng, -6, 6));
      const glm::dvec3 h = scale * glm::dvec3(uniform(rng, 0.01, 1), uniform(rng, 0.01, 1), uniform(rng, 0.01, 1));
      objects[i].world_bounds = Box3{c - h, c + h};
      ids.push_back(int32_t(i));
    }
    const double pad = 4e-6 * 7 * scale + 0x1p-40 * (std::abs(offset.x) + 7 * scale);  // as embree_query.cpp pads
    const BoxFilter filter(ids, objects, pad);
    ASSERT_EQ(filter.padded_size(), BoxFilter::kMaxObjects);
    for (int i = 0; i < 20000; ++i) {
      const size_t target = rng() % objects.size();
      const Box3& box = objects[target].world_bounds;
      glm::dvec3 p(uniform(rng, box.lo.x, box.hi.x), uniform(rng, box.lo.y, box.hi.y), uniform(rng, box.lo.z, box.hi.z));
      for (int a = 0; a < 3; ++a) {  // on a face, an edge or a corner, half of the time each
        if (rng() % 2) p[a] = rng() % 2 ? box.lo[a] : box.hi[a];
      }
      const glm::dvec3 d = random_unit(rng);
      const double s = scale * std::pow(10.0, uniform(rng, -1, 4));  // the point's t
      const glm::dvec3 o = p - s * d;
      std::array<double, BoxFilter::kMaxObjects> enter, leave;
      // A part of the ray that holds the point: the box must be kept.
      filter.clip(o, 1.0 / d, s * uniform(rng, 0, 1), s * uniform(rng, 1, 2), enter, leave);
      ASSERT_LE(enter[target], leave[target]) << "box " << target << " dropped, ray through a point of it";
      ++kept;
      // A part that ends just before the padded box (by 1e-9 relative): dropped.
      const Box3 padded{box.lo - pad, box.hi + pad};
      const auto [exact_enter, exact_leave] = exact_clip(o, d, padded);
      const double before = double(exact_enter) - 1e-9 * (scale + std::abs(double(exact_enter)));
      if (before > 0) {
        filter.clip(o, 1.0 / d, 0.0, before, enter, leave);
        EXPECT_GT(enter[target], leave[target]) << "box " << target << " kept, ray ends before it";
        ++dropped;
      }
    }
  }
  EXPECT_GT(dropped, 10000);
  std::printf("[   info   ] %d rays through boxes kept them, %d ending before them dropped them\n", kept, dropped);
}

// A box moved by set_box is tested where it is now.
TEST(BoxFilter, SetBoxMovesTheBox) {
  std::vector<Object> objects(3);
  for (int i = 0; i < 3; ++i) objects[size_t(i)].world_bounds = Box3{glm::dvec3(3.0 * i), glm::dvec3(3.0 * i + 1)};
  const std::vector<int32_t> ids = {0, 1, 2};
  BoxFilter filter(ids, objects, 1e-6);
  const glm::dvec3 o(0.5, 0.5, -10), inv(1.0 / 1e-9, 1.0 / 1e-9, 1.0);  // nearly along +z through x = y = 0.5
  std::array<double, BoxFilter::kMaxObjects> enter, leave;
  filter.clip(o, inv, 0.0, 100.0, enter, leave);
  EXPECT_LE(enter[0], leave[0]);
  EXPECT_GT(enter[1], leave[1]);
  filter.set_box(1, Box3{glm::dvec3(0, 0, 5), glm::dvec3(1, 1, 6)});
  filter.clip(o, inv, 0.0, 100.0, enter, leave);
  EXPECT_LE(enter[1], leave[1]);
  EXPECT_NEAR(enter[1], 15.0 - 1e-6, 1e-9);  // enters the padded box at z = 5 - pad
  EXPECT_GT(enter[2], leave[2]);
}

// A closest-hit query clips to (tmin, infinity) until it has a hit; the
// padding slots' boxes, at +infinity, then "meet" the ray there, but the
// mask names only the real boxes the ray meets, at every width.
TEST(BoxFilter, MaskHoldsTheBoxesMetAndNoPaddingSlot) {
  std::vector<Object> objects(3);
  objects[0].world_bounds = Box3{glm::dvec3(2, -1, -1), glm::dvec3(3, 1, 1)};     // on the ray
  objects[1].world_bounds = Box3{glm::dvec3(2, 5, -1), glm::dvec3(3, 6, 1)};      // beside it
  objects[2].world_bounds = Box3{glm::dvec3(10, -1, -1), glm::dvec3(11, 1, 1)};   // on it, further
  const std::vector<int32_t> ids = {0, 1, 2};
  const BoxFilter filter(ids, objects, 1e-6);
  const glm::dvec3 o(0, 0, 0), inv(1.0, 1.0 / 1e-9, 1.0 / 1e-9);  // nearly along +x
  for (int width : BoxFilter::clip_widths()) {
    std::array<double, BoxFilter::kMaxObjects> enter, leave;
    EXPECT_EQ(filter.clip(o, inv, 0.0, std::numeric_limits<double>::infinity(), enter, leave, width), 0b101u)
        << "width " << width;
    EXPECT_EQ(filter.clip(o, inv, 0.0, 5.0, enter, leave, width), 0b001u) << "width " << width;
  }
}

// Every vector width this processor runs gives, bit for bit, the slab test
// written out here one box at a time (the .cpp's claim), on boxes of every
// size and rays from near and far, some of them along an axis (inverse
// direction 1e300).
TEST(BoxFilter, EveryVectorWidthGivesTheScalarSlabTestsBits) {
  Rng rng(5);
  std::vector<Object> objects(BoxFilter::kMaxObjects - 3);
  std::vector<int32_t> ids;
  for (size_t i = 0; i < objects.size(); ++i) {
    const double scale = std::pow(10.0, uniform(rng, -3, 3));
    const glm::dvec3 c = scale * glm::dvec3(uniform(rng, -6, 6), uniform(rng, -6, 6), uniform(rng, -6, 6));
    const glm::dvec3 h = scale * glm::dvec3(uniform(rng, 0.01, 1), uniform(rng, 0.01, 1), uniform(rng, 0.01, 1));
    objects[i].world_bounds = Box3{c - h, c + h};
    ids.push_back(int32_t(i));
  }
  const double pad = 1e-5;
  const BoxFilter filter(ids, objects, pad);
  const std::vector<int> widths = BoxFilter::clip_widths();
  std::printf("[   info   ] vector widths here:");
  for (int w : widths) std::printf(" %d", w);
  std::printf("\n");
  ASSERT_EQ(widths.front(), 2);
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 o = std::pow(10.0, uniform(rng, -2, 4)) * random_unit(rng);
    glm::dvec3 inv = 1.0 / random_unit(rng);
    if (i % 7 == 0) inv[size_t(i % 3)] = (i % 2 ? 1e300 : -1e300);
    const double t0 = uniform(rng, 0, 1), t1 = t0 + std::pow(10.0, uniform(rng, -1, 5));
    for (int width : widths) {
      std::array<double, BoxFilter::kMaxObjects> enter, leave;
      const uint32_t entered = filter.clip(o, inv, t0, t1, enter, leave, width);
      ASSERT_EQ(entered >> objects.size(), 0u) << "width " << width << ": a padding slot in the mask";
      for (size_t k = 0; k < objects.size(); ++k) {
        double t_in = t0, t_out = t1;
        for (int a = 0; a < 3; ++a) {
          const double near = (objects[k].world_bounds.lo[a] - pad - o[a]) * inv[a];
          const double far = (objects[k].world_bounds.hi[a] + pad - o[a]) * inv[a];
          t_in = std::max(t_in, std::min(near, far));
          t_out = std::min(t_out, std::max(near, far));
        }
        ASSERT_EQ(std::bit_cast<uint64_t>(enter[k]), std::bit_cast<uint64_t>(t_in)) << "width " << width << ", box " << k;
        ASSERT_EQ(std::bit_cast<uint64_t>(leave[k]), std::bit_cast<uint64_t>(t_out)) << "width " << width << ", box " << k;
        ASSERT_EQ((entered >> k) & 1u, t_in <= t_out ? 1u : 0u) << "width " << width << ", box " << k;
      }
    }
  }
}

}  // namespace
}  // namespace prism::embree
