// A bounding volume hierarchy for the GPU kernels: built on the host with a
// binned surface-area heuristic, flattened depth-first so that an inner
// node's two children are adjacent (`first`, `first + 1`) and a leaf's
// objects are a contiguous run of `order`.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prism/scene.hpp"

namespace prism::gpu {

struct BvhNode {
  Box3 bounds;
  uint32_t first = 0;  // inner: left child index; leaf: first position in `order`
  uint32_t count = 0;  // 0 for an inner node, else the number of objects in the leaf
  bool leaf() const { return count > 0; }
};

struct Bvh {
  std::vector<BvhNode> nodes;   // nodes[0] is the root (absent when there are no boxes)
  std::vector<uint32_t> order;  // leaf order: indices into the input boxes
  int depth = 0;                // levels below the root, for the kernel's traversal stack
};

// Leaves hold at most this many objects, unless their boxes cannot be told apart.
constexpr uint32_t kBvhLeafSize = 4;
// The traversal stack the GLSL reserves; the builder never goes deeper.
constexpr int kBvhMaxDepth = 60;

Bvh build_bvh(std::span<const Box3> boxes);

}  // namespace prism::gpu
