#include "bvh.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <stdexcept>

namespace prism::gpu {

namespace {

constexpr int kBins = 16;

Box3 empty_box() {
  const double inf = std::numeric_limits<double>::infinity();
  return {glm::dvec3(inf), glm::dvec3(-inf)};
}

void grow(Box3& box, const Box3& other) {
  box.lo = glm::min(box.lo, other.lo);
  box.hi = glm::max(box.hi, other.hi);
}

void grow(Box3& box, const glm::dvec3& p) {
  box.lo = glm::min(box.lo, p);
  box.hi = glm::max(box.hi, p);
}

double half_area(const Box3& box) {
  glm::dvec3 e = box.hi - box.lo;
  if (e.x < 0) return 0.0;  // empty
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

glm::dvec3 centroid(const Box3& box) { return 0.5 * (box.lo + box.hi); }

struct Builder {
  std::span<const Box3> boxes;
  Bvh bvh;

  struct Split {
    int axis = -1;
    double position = 0.0;
    double cost = std::numeric_limits<double>::infinity();
  };

  // The cheapest of the (kBins - 1) planes per axis between the centroid bounds.
  Split best_split(uint32_t begin, uint32_t end, const Box3& centroids) const {
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      double lo = centroids.lo[axis], extent = centroids.hi[axis] - lo;
      if (!(extent > 0.0)) continue;
      std::array<Box3, kBins> bin_box;
      std::array<uint32_t, kBins> bin_count{};
      bin_box.fill(empty_box());
      for (uint32_t i = begin; i < end; ++i) {
        const Box3& b = boxes[bvh.order[i]];
        int bin = std::min(kBins - 1, int((centroid(b)[axis] - lo) / extent * kBins));
        grow(bin_box[size_t(bin)], b);
        ++bin_count[size_t(bin)];
      }
      std::array<double, kBins> right_cost{};
      Box3 right = empty_box();
      uint32_t right_n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        grow(right, bin_box[size_t(b)]);
        right_n += bin_count[size_t(b)];
        right_cost[size_t(b)] = half_area(right) * right_n;
      }
      Box3 left = empty_box();
      uint32_t left_n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        grow(left, bin_box[size_t(b)]);
        left_n += bin_count[size_t(b)];
        double cost = half_area(left) * left_n + right_cost[size_t(b) + 1];
        if (left_n > 0 && left_n < end - begin && cost < best.cost)
          best = {axis, lo + extent * (b + 1) / kBins, cost};
      }
    }
    return best;
  }

  // Partitions [begin, end) and returns the split point; falls back to the
  // median along the widest centroid axis (or the index middle when every
  // centroid coincides), so the depth stays logarithmic.
  uint32_t partition(uint32_t begin, uint32_t end, const Box3& bounds, const Box3& centroids) {
    Split split = best_split(begin, end, centroids);
    const uint32_t n = end - begin;
    const bool worth_it = split.axis >= 0 && split.cost < half_area(bounds) * double(n);
    if (worth_it) {
      auto mid = std::partition(bvh.order.begin() + begin, bvh.order.begin() + end, [&](uint32_t i) {
        return centroid(boxes[i])[split.axis] < split.position;
      });
      return uint32_t(mid - bvh.order.begin());
    }
    glm::dvec3 extent = centroids.hi - centroids.lo;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    uint32_t mid = begin + n / 2;
    std::nth_element(bvh.order.begin() + begin, bvh.order.begin() + mid, bvh.order.begin() + end,
                     [&](uint32_t a, uint32_t b) {
                       double ca = centroid(boxes[a])[axis], cb = centroid(boxes[b])[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    return mid;
  }

  void build(uint32_t node, uint32_t begin, uint32_t end, int depth) {
    Box3 bounds = empty_box(), centroids = empty_box();
    for (uint32_t i = begin; i < end; ++i) {
      grow(bounds, boxes[bvh.order[i]]);
      grow(centroids, centroid(boxes[bvh.order[i]]));
    }
    bvh.nodes[node].bounds = bounds;
    bvh.depth = std::max(bvh.depth, depth);
    const uint32_t n = end - begin;
    if (n <= kBvhLeafSize || depth >= kBvhMaxDepth) {
      bvh.nodes[node].first = begin;
      bvh.nodes[node].count = n;
      return;
    }
    uint32_t mid = partition(begin, end, bounds, centroids);
    uint32_t left = uint32_t(bvh.nodes.size());
    bvh.nodes.resize(bvh.nodes.size() + 2);
    bvh.nodes[node].first = left;
    bvh.nodes[node].count = 0;
    build(left, begin, mid, depth + 1);
    build(left + 1, mid, end, depth + 1);
  }
};

// Links every node to its parent and every box to its leaf.
void link(Bvh& bvh) {
  bvh.parent.assign(bvh.nodes.size(), 0);
  bvh.leaf_of.assign(bvh.order.size(), 0);
  for (uint32_t n = 0; n < bvh.nodes.size(); ++n) {
    const BvhNode& node = bvh.nodes[n];
    if (!node.leaf()) {
      bvh.parent[node.first] = bvh.parent[node.first + 1] = n;
      continue;
    }
    for (uint32_t i = node.first; i < node.first + node.count; ++i) bvh.leaf_of[bvh.order[i]] = n;
  }
}

bool same_box(const Box3& a, const Box3& b) { return a.lo == b.lo && a.hi == b.hi; }

// Recomputes one node from its children (or its objects); true when its bounds changed.
bool refit_node(Bvh& bvh, std::span<const Box3> boxes, uint32_t n) {
  BvhNode& node = bvh.nodes[n];
  Box3 bounds = empty_box();
  if (node.leaf()) {
    for (uint32_t i = node.first; i < node.first + node.count; ++i) grow(bounds, boxes[bvh.order[i]]);
  } else {
    grow(bounds, bvh.nodes[node.first].bounds);
    grow(bounds, bvh.nodes[node.first + 1].bounds);
  }
  if (same_box(bounds, node.bounds)) return false;
  node.bounds = bounds;
  return true;
}

void check_refit_input(const Bvh& bvh, std::span<const Box3> boxes) {
  if (boxes.size() != bvh.order.size() || bvh.parent.size() != bvh.nodes.size())
    throw std::invalid_argument("refit_bvh: the boxes are not the ones the tree was built from");
}

}  // namespace

Bvh build_bvh(std::span<const Box3> boxes) {
  Builder builder{boxes, {}};
  if (boxes.empty()) return {};
  builder.bvh.order.resize(boxes.size());
  for (uint32_t i = 0; i < boxes.size(); ++i) builder.bvh.order[i] = i;
  builder.bvh.nodes.reserve(2 * boxes.size());
  builder.bvh.nodes.resize(1);
  builder.build(0, 0, uint32_t(boxes.size()), 0);
  link(builder.bvh);
  builder.bvh.built_cost = sah_cost(builder.bvh);
  return std::move(builder.bvh);
}

double sah_cost(const Bvh& bvh) {
  double cost = 0.0;
  for (const BvhNode& node : bvh.nodes) cost += half_area(node.bounds) * (node.leaf() ? double(node.count) : 1.0);
  return cost;
}

std::vector<uint32_t> refit_bvh(Bvh& bvh, std::span<const Box3> boxes, std::span<const uint32_t> moved) {
  check_refit_input(bvh, boxes);
  // The moved boxes' leaves and every ancestor; children have higher indices
  // than their parent, so descending order is bottom-up.
  std::vector<uint32_t> todo;
  for (uint32_t box : moved) {
    if (box >= boxes.size()) throw std::invalid_argument("refit_bvh: a moved box is out of range");
    for (uint32_t n = bvh.leaf_of[box];; n = bvh.parent[n]) {
      todo.push_back(n);
      if (n == 0) break;
    }
  }
  std::sort(todo.begin(), todo.end(), std::greater<>());
  todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  std::vector<uint32_t> changed;
  for (uint32_t n : todo)
    if (refit_node(bvh, boxes, n)) changed.push_back(n);
  std::reverse(changed.begin(), changed.end());
  return changed;
}

std::vector<uint32_t> refit_bvh(Bvh& bvh, std::span<const Box3> boxes) {
  check_refit_input(bvh, boxes);
  std::vector<uint32_t> changed;
  for (size_t n = bvh.nodes.size(); n-- > 0;)
    if (refit_node(bvh, boxes, uint32_t(n))) changed.push_back(uint32_t(n));
  std::reverse(changed.begin(), changed.end());
  return changed;
}

}  // namespace prism::gpu
