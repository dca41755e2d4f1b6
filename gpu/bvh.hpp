// A bounding volume hierarchy for the GPU kernels: built on the host with a
// binned surface-area heuristic, flattened depth-first so that an inner
// node's two children are adjacent (`first`, `first + 1`) and a leaf's
// objects are a contiguous run of `order`. A live update refits it (new
// bounds, same topology) until its SAH cost says a rebuild pays.
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
  std::vector<uint32_t> parent;   // per node: its parent (the root's is 0)
  std::vector<uint32_t> leaf_of;  // per input box: the leaf that holds it
  int depth = 0;                // levels below the root, for the kernel's traversal stack
  double built_cost = 0.0;      // sah_cost() when it was built
};

// Leaves hold at most this many objects, unless their boxes cannot be told apart.
constexpr uint32_t kBvhLeafSize = 4;
// The traversal stack the GLSL reserves; the builder never goes deeper.
constexpr int kBvhMaxDepth = 60;

// A refitted tree is kept while its SAH cost stays within this factor of
// its cost when built. With 10,000 spheres on llvmpipe and lavapipe a
// rebuild (repack, build, send every node, object and record: ~7 ms) costs
// about one 64x48 frame (~5 ms) and ~70 refits (~0.1 ms). SAH cost tracks
// traversal work, so a tree 1.5x as costly makes the traversal part of every
// later frame up to 1.5x as slow: past that, a rebuild pays for itself within
// a few frames, while objects moving about in place (a few per cent of cost)
// never trigger one.
constexpr double kBvhRefitMaxCostRatio = 1.5;

Bvh build_bvh(std::span<const Box3> boxes);

// The tree's surface-area-heuristic cost: the half areas of the inner nodes
// (one traversal step each) plus those of the leaves times their object
// counts (one intersection each). Not divided by the root's area: by
// Crofton's formula the area is proportional to how many lines of a fixed,
// uniform ray distribution cross a box, so costs before and after a refit
// that grew the root still compare the same rays.
double sah_cost(const Bvh& bvh);

// Refits the tree to `boxes` (the same boxes it was built from, some of them
// changed), keeping its topology: each node's bounds become the union of its
// children's, a leaf's the union of its objects' boxes, bottom-up. Only the
// leaves holding the `moved` boxes and their ancestors are recomputed.
// Returns the nodes whose bounds changed, ascending.
std::vector<uint32_t> refit_bvh(Bvh& bvh, std::span<const Box3> boxes, std::span<const uint32_t> moved);
// The same with every node recomputed.
std::vector<uint32_t> refit_bvh(Bvh& bvh, std::span<const Box3> boxes);

}  // namespace prism::gpu
