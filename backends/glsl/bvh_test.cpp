// The GPU BVH builder: every object reachable exactly once, boxes contain
// their children, leaves small, depth within the kernel's stack.
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

}  // namespace
}  // namespace prism::gpu
