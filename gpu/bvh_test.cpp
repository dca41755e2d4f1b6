// The GPU BVH builder: every object reachable exactly once, boxes contain
// their children, leaves small, depth within the kernel's stack. Its refit:
// the same topology with bounds recomputed bottom-up, and an SAH cost that
// tells a refit worth keeping from one that calls for a rebuild.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "bvh.hpp"

namespace prism::gpu {
namespace {

bool contains(const Box3& outer, const Box3& inner) {
  return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

// Walks the tree, checking containment; returns the objects seen in leaf order.
void walk(const Bvh& bvh, std::span<const Box3> boxes, uint32_t node, std::vector<uint32_t>& seen) {
  const BvhNode& n = bvh.nodes[node];
  if (n.leaf()) {
    for (uint32_t i = n.first; i < n.first + n.count; ++i) {
      EXPECT_TRUE(contains(n.bounds, boxes[bvh.order[i]]));
      seen.push_back(bvh.order[i]);
    }
    return;
  }
  ASSERT_LT(n.first + 1, bvh.nodes.size());
  EXPECT_TRUE(contains(n.bounds, bvh.nodes[n.first].bounds));
  EXPECT_TRUE(contains(n.bounds, bvh.nodes[n.first + 1].bounds));
  walk(bvh, boxes, n.first, seen);
  walk(bvh, boxes, n.first + 1, seen);
}

void check_tree(std::span<const Box3> boxes, const Bvh& bvh) {
  std::vector<uint32_t> seen;
  walk(bvh, boxes, 0, seen);
  std::sort(seen.begin(), seen.end());
  ASSERT_EQ(seen.size(), boxes.size());
  for (uint32_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], i);
  EXPECT_LE(bvh.depth, kBvhMaxDepth);
}

TEST(Bvh, EmptyInputGivesNoNodes) {
  Bvh bvh = build_bvh({});
  EXPECT_TRUE(bvh.nodes.empty());
  EXPECT_TRUE(bvh.order.empty());
}

TEST(Bvh, FewObjectsMakeOneLeaf) {
  std::vector<Box3> boxes = {{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {3, 1, 1}}};
  Bvh bvh = build_bvh(boxes);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].count, 2u);
  EXPECT_EQ(bvh.nodes[0].bounds.lo, glm::dvec3(0, 0, 0));
  EXPECT_EQ(bvh.nodes[0].bounds.hi, glm::dvec3(3, 1, 1));
}

TEST(Bvh, TwoClustersSplitBetweenThem) {
  // Four unit boxes near x = 0 and four near x = 100: SAH must split the clusters.
  std::vector<Box3> boxes;
  for (int i = 0; i < 4; ++i) boxes.push_back({{double(i), 0, 0}, {i + 0.5, 1, 1}});
  for (int i = 0; i < 4; ++i) boxes.push_back({{100.0 + i, 0, 0}, {100.5 + i, 1, 1}});
  Bvh bvh = build_bvh(boxes);
  check_tree(boxes, bvh);
  ASSERT_EQ(bvh.nodes.size(), 3u);
  const BvhNode& left = bvh.nodes[bvh.nodes[0].first];
  const BvhNode& right = bvh.nodes[bvh.nodes[0].first + 1];
  EXPECT_EQ(left.count, 4u);
  EXPECT_EQ(right.count, 4u);
  EXPECT_EQ(left.bounds.hi.x, 3.5);
  EXPECT_EQ(right.bounds.lo.x, 100.0);
}

TEST(Bvh, RandomBoxesAreAllReachable) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-1000, 1000), size(0.01, 5);
  std::vector<Box3> boxes;
  for (int i = 0; i < 5000; ++i) {
    glm::dvec3 c(pos(rng), pos(rng), pos(rng));
    glm::dvec3 h(size(rng), size(rng), size(rng));
    boxes.push_back({c - h, c + h});
  }
  Bvh bvh = build_bvh(boxes);
  check_tree(boxes, bvh);
  for (const BvhNode& n : bvh.nodes) {
    if (n.leaf()) {
      EXPECT_LE(n.count, kBvhLeafSize);
    }
  }
}

TEST(Bvh, IdenticalBoxesStillBuildAShallowTree) {
  // No plane separates identical boxes; the median fallback keeps depth ~log2(n).
  std::vector<Box3> boxes(10000, Box3{{0, 0, 0}, {1, 1, 1}});
  Bvh bvh = build_bvh(boxes);
  check_tree(boxes, bvh);
  EXPECT_LE(bvh.depth, 14);  // ceil(log2(10000 / 4)) = 12, plus slack for uneven halves
}

std::vector<Box3> random_boxes(uint32_t seed, int count, double spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-spread, spread), size(0.05, 1.0);
  std::vector<Box3> boxes;
  for (int i = 0; i < count; ++i) {
    glm::dvec3 c(pos(rng), pos(rng), pos(rng));
    glm::dvec3 h(size(rng), size(rng), size(rng));
    boxes.push_back({c - h, c + h});
  }
  return boxes;
}

// The bounds of `node` recomputed here from the boxes, recursively: what a
// bottom-up refit must give every node.
Box3 recomputed(const Bvh& bvh, std::span<const Box3> boxes, uint32_t node, std::vector<Box3>& out) {
  const BvhNode& n = bvh.nodes[node];
  Box3 b = n.leaf() ? boxes[bvh.order[n.first]] : recomputed(bvh, boxes, n.first, out);
  const auto add = [&](const Box3& o) {
    b.lo = glm::min(b.lo, o.lo);
    b.hi = glm::max(b.hi, o.hi);
  };
  if (n.leaf()) {
    for (uint32_t i = n.first + 1; i < n.first + n.count; ++i) add(boxes[bvh.order[i]]);
  } else {
    add(recomputed(bvh, boxes, n.first + 1, out));
  }
  out[node] = b;
  return b;
}

bool same(const Box3& a, const Box3& b) { return a.lo == b.lo && a.hi == b.hi; }

TEST(BvhRefit, AMovedBoxGivesBoundsThatContainEveryBoxAndEqualABottomUpRecomputation) {
  std::vector<Box3> boxes = random_boxes(11, 600, 50);
  Bvh bvh = build_bvh(boxes);
  const Bvh built = bvh;
  boxes[123].lo += glm::dvec3(40, -7, 3);  // out of its leaf's box, and of the root's
  boxes[123].hi += glm::dvec3(40, -7, 3);
  boxes[123].hi.x += 60;
  const std::vector<uint32_t> moved = {123};
  const std::vector<uint32_t> changed = refit_bvh(bvh, boxes, moved);

  check_tree(boxes, bvh);
  std::vector<Box3> expected(bvh.nodes.size());
  recomputed(bvh, boxes, 0, expected);
  std::vector<uint32_t> differ;
  ASSERT_EQ(bvh.nodes.size(), built.nodes.size());
  for (uint32_t n = 0; n < bvh.nodes.size(); ++n) {
    EXPECT_TRUE(same(bvh.nodes[n].bounds, expected[n])) << "node " << n;
    EXPECT_EQ(bvh.nodes[n].first, built.nodes[n].first) << "node " << n;  // the topology is kept
    EXPECT_EQ(bvh.nodes[n].count, built.nodes[n].count) << "node " << n;
    if (!same(bvh.nodes[n].bounds, built.nodes[n].bounds)) differ.push_back(n);
  }
  EXPECT_EQ(bvh.order, built.order);
  EXPECT_EQ(changed, differ);
  ASSERT_FALSE(changed.empty());
  EXPECT_EQ(changed.front(), 0u);  // the root grew
  EXPECT_EQ(bvh.nodes[0].bounds.hi.x, boxes[123].hi.x);

  Bvh full = built;  // recomputing every node agrees with recomputing the moved box's path
  EXPECT_EQ(refit_bvh(full, boxes), differ);
  for (uint32_t n = 0; n < bvh.nodes.size(); ++n) EXPECT_TRUE(same(full.nodes[n].bounds, bvh.nodes[n].bounds));
}

TEST(BvhRefit, NothingMovedChangesNothing) {
  const std::vector<Box3> boxes = random_boxes(3, 100, 20);
  Bvh bvh = build_bvh(boxes);
  const std::vector<uint32_t> moved = {5, 6, 7};
  EXPECT_TRUE(refit_bvh(bvh, boxes, moved).empty());
  EXPECT_TRUE(refit_bvh(bvh, boxes).empty());
  EXPECT_EQ(sah_cost(bvh), bvh.built_cost);
}

TEST(BvhSah, CostIsHalfAreasOfInnerNodesPlusLeafAreasTimesCounts) {
  // The two clusters of TwoClustersSplitBetweenThem: a root 103.5 x 1 x 1
  // (half area 103.5 + 1 + 103.5) over two leaves 3.5 x 1 x 1 of four boxes.
  std::vector<Box3> boxes;
  for (int i = 0; i < 4; ++i) boxes.push_back({{double(i), 0, 0}, {i + 0.5, 1, 1}});
  for (int i = 0; i < 4; ++i) boxes.push_back({{100.0 + i, 0, 0}, {100.5 + i, 1, 1}});
  const Bvh bvh = build_bvh(boxes);
  EXPECT_EQ(sah_cost(bvh), 208.0 + 2 * 4 * 8.0);
  EXPECT_EQ(bvh.built_cost, 272.0);
}

TEST(BvhSah, AJitteredBoxStaysWithinTheRefitRatio) {
  std::vector<Box3> boxes = random_boxes(5, 2000, 100);
  Bvh bvh = build_bvh(boxes);
  for (uint32_t i : {10u, 500u, 1999u}) {
    boxes[i].lo += glm::dvec3(0.5, -0.25, 0.1);
    boxes[i].hi += glm::dvec3(0.5, -0.25, 0.1);
  }
  const std::vector<uint32_t> moved = {10, 500, 1999};
  refit_bvh(bvh, boxes, moved);
  EXPECT_LT(sah_cost(bvh), 1.05 * bvh.built_cost);
  EXPECT_LE(sah_cost(bvh), kBvhRefitMaxCostRatio * bvh.built_cost);
}

TEST(BvhSah, ManyBoxesScatteringFarPassTheRatioThatCallsForARebuild) {
  // 2000 boxes within 20 units; then one in ten flies anywhere within 1000.
  std::vector<Box3> boxes = random_boxes(9, 2000, 20);
  Bvh bvh = build_bvh(boxes);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> far(-1000, 1000);
  std::vector<uint32_t> moved;
  for (uint32_t i = 0; i < boxes.size(); i += 10) {
    const glm::dvec3 to(far(rng), far(rng), far(rng));
    const glm::dvec3 half = 0.5 * (boxes[i].hi - boxes[i].lo);
    boxes[i] = {to - half, to + half};
    moved.push_back(i);
  }
  refit_bvh(bvh, boxes, moved);
  check_tree(boxes, bvh);
  const double refitted = sah_cost(bvh);
  EXPECT_GT(refitted, kBvhRefitMaxCostRatio * bvh.built_cost);
  // ... and a rebuild is indeed much better than the refitted tree.
  EXPECT_LT(build_bvh(boxes).built_cost * kBvhRefitMaxCostRatio, refitted);
}

}  // namespace
}  // namespace prism::gpu
