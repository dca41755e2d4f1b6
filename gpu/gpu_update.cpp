#include "gpu_update.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>

#include "gpu_pack.hpp"

namespace prism::gpu {

namespace {

// `now` replaces `packed`; the writes are the elements that differ (all of
// them when the count changed).
template <class T>
void replace(std::vector<T>& packed, std::vector<T> now, BufferWrites& writes) {
  if (now.size() != packed.size()) {
    writes.whole = true;
  } else {
    std::vector<size_t> differ;
    for (size_t i = 0; i < now.size(); ++i)
      if (std::memcmp(&now[i], &packed[i], sizeof(T)) != 0) differ.push_back(i);
    writes.runs = runs_of(std::move(differ));
  }
  packed = std::move(now);
}

bool finite_box(const Box3& box) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a]) || box.lo[a] > box.hi[a]) return false;
  return true;
}

bool same_box(const Box3& a, const Box3& b) { return a.lo == b.lo && a.hi == b.hi; }

// Whether object `id` can be rewritten where it is: same plugin (so the same
// record size and kernel type), still bounded or still unbounded, finite bounds.
bool fits_in_place(const PackedScene& p, const Scene& scene, uint32_t id) {
  if (id >= scene.objects.size()) return false;
  const Object& object = scene.objects[id];
  const uint32_t slot = p.slot_of[id];
  const bool was_bounded = slot < uint32_t(p.bounded_objects);
  return object.desc == p.types[p.objects[slot].type] && object.bounded == was_bounded &&
         (!object.bounded || finite_box(object.world_bounds));
}

// Refits the tree to the moved boxes; false when its SAH cost says rebuild.
bool refit(PackedScene& p, std::span<const uint32_t> moved, PackedUpdate& u) {
  const std::vector<uint32_t> changed = refit_bvh(p.bvh, p.boxes, moved);
  if (sah_cost(p.bvh) > kBvhRefitMaxCostRatio * p.bvh.built_cost) return false;
  std::vector<size_t> nodes;  // only nodes whose float bounds changed are sent
  for (uint32_t n : changed) {
    const GpuNode node = detail::node_entry(p.bvh.nodes[n]);
    if (std::memcmp(&node, &p.nodes[n], sizeof node) == 0) continue;
    p.nodes[n] = node;
    nodes.push_back(n);
  }
  u.buffers[kBindNodes].runs = runs_of(std::move(nodes));
  u.bvh_refitted = true;
  return true;
}

// Rewrites the objects `ids` where they are; false when one of them cannot
// be, or the refitted BVH is too costly (then the caller packs every object again).
bool update_in_place(PackedScene& p, const Scene& scene, std::span<const uint32_t> ids, PackedUpdate& u) {
  if (p.slot_of.size() != scene.objects.size()) return false;
  for (uint32_t id : ids)
    if (!fits_in_place(p, scene, id)) return false;
  std::vector<size_t> slots, doubles;
  std::vector<uint32_t> moved;  // BVH input indices
  for (uint32_t id : ids) {
    const Object& object = scene.objects[id];
    const uint32_t slot = p.slot_of[id];
    GpuObject& entry = p.objects[slot];
    entry = detail::object_entry(object, id, entry.type, entry.record);
    const size_t n = object.desc->record_size / sizeof(double);
    std::memcpy(p.records.data() + entry.record, object.record(), n * sizeof(double));
    slots.push_back(slot);
    for (size_t i = 0; i < n; ++i) doubles.push_back(entry.record + i);
    if (!object.bounded) continue;
    const uint32_t box = p.bvh.order[slot];
    if (same_box(p.boxes[box], object.world_bounds)) continue;
    p.boxes[box] = object.world_bounds;
    moved.push_back(box);
  }
  if (!moved.empty() && !refit(p, moved, u)) return false;
  u.buffers[kBindObjects].runs = runs_of(std::move(slots));
  u.buffers[kBindRecords].runs = runs_of(std::move(doubles));
  u.objects_written = ids.size();
  return true;
}

void repack_objects(PackedScene& p, const Scene& scene, PackedUpdate& u) {
  const std::vector<const PrismPrimitiveDesc*> before = p.types;
  detail::pack_objects(scene, before, p);
  for (uint32_t b : {kBindRecords, kBindObjects, kBindNodes}) u.buffers[b] = {true, {}};
  u.kernel = u.kernel || p.types != before;
  u.objects_written = scene.objects.size();
  u.bvh_built = !p.bvh.nodes.empty();
  u.bvh_refitted = false;
}

// A float world's copies made again; its nodes are rounded from their own
// relative bounds, so the nodes sent are the float ones that changed.
void refresh_float_nodes(PackedScene& p, BufferWrites& nodes) {
  if (!p.float_world) return;
  const std::vector<GpuNode> before = p.nodes_f;
  refresh_float_world(p);
  if (nodes.whole) return;
  if (before.size() != p.nodes_f.size()) {
    nodes.whole = true;
    return;
  }
  std::vector<size_t> differ;
  for (size_t n = 0; n < before.size(); ++n)
    if (std::memcmp(&before[n], &p.nodes_f[n], sizeof(GpuNode)) != 0) differ.push_back(n);
  nodes.runs = runs_of(std::move(differ));
}

}  // namespace

std::vector<Range> runs_of(std::vector<size_t> indices) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::vector<Range> runs;
  for (size_t i : indices) {
    if (!runs.empty() && runs.back().first + runs.back().count == i) ++runs.back().count;
    else runs.push_back({i, 1});
  }
  return runs;
}

std::vector<ByteRange> byte_ranges(const SceneBuffer& source, const BufferWrites& writes) {
  const auto* bytes = static_cast<const unsigned char*>(source.data);
  if (writes.whole) return {{0, bytes, source.bytes()}};
  std::vector<ByteRange> out;
  for (const Range& r : writes.runs)
    out.push_back({r.first * source.element_bytes, bytes + r.first * source.element_bytes, r.count * source.element_bytes});
  return out;
}

void start_counters(BackendStats& stats) {
  for (const char* name : {counter::kPrepares, counter::kUpdates, counter::kObjectsUploaded, counter::kBvhBuilds,
                           counter::kBvhRefits, counter::kKernelBuilds})
    stats.counters[name] = 0;
}

void count_prepare(BackendStats& stats, const PackedScene& packed) {
  stats.counters[counter::kPrepares] += 1;
  stats.counters[counter::kObjectsUploaded] += double(packed.slot_of.size());
  stats.counters[counter::kBvhBuilds] += packed.bvh.nodes.empty() ? 0 : 1;
}

void count_update(BackendStats& stats, const PackedUpdate& update) {
  stats.counters[counter::kUpdates] += 1;
  stats.counters[counter::kObjectsUploaded] += double(update.objects_written);
  stats.counters[counter::kBvhBuilds] += update.bvh_built ? 1 : 0;
  stats.counters[counter::kBvhRefits] += update.bvh_refitted ? 1 : 0;
}

PackedUpdate update_packed_scene(PackedScene& p, const Scene& scene, const SceneChanges& changes) {
  PackedUpdate u;
  const std::vector<uint32_t> layout_before = kernel_layout(p);
  if (changes.textures) {
    detail::pack_textures(scene, p);
    u.buffers[kBindTexels].whole = true;
  }
  if (changes.materials || changes.textures)
    replace(p.materials, detail::pack_materials(scene, p), u.buffers[kBindMaterials]);
  if (changes.lights) replace(p.lights, detail::pack_lights(scene), u.buffers[kBindLights]);
  if (changes.environment || changes.textures) detail::pack_environment(scene, p);
  if (changes.objects_added_or_removed || !update_in_place(p, scene, changes.objects, u)) repack_objects(p, scene, u);
  detail::set_counts(p);
  std::set<Feature> features = detail::scene_features(scene, p);
  u.kernel = u.kernel || features != p.features || kernel_layout(p) != layout_before;
  p.features = std::move(features);
  refresh_float_nodes(p, u.buffers[kBindNodes]);
  return u;
}

}  // namespace prism::gpu
