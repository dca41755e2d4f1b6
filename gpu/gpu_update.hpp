// Live updates of a packed scene (Backend::update): the packing is changed
// in place to match the edited Scene, and what changed comes back as runs of
// elements per buffer, so each backend sends only those. Shared by both GPU
// backends; only the API calls that send the bytes differ.
//
// Objects changed in place have their entry and record rewritten and the BVH
// refitted (bvh.hpp); the BVH is built again, and every object sent again,
// when objects were added or removed, when one changed type, turned bounded
// or unbounded or got non-finite bounds, or when the refitted tree's SAH cost
// passed kBvhRefitMaxCostRatio times its cost when built. Materials, lights,
// texels and the frame's scene constants are packed again only when their
// flag says so, and only the elements that differ are sent.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "gpu_scene.hpp"
#include "prism/backend.hpp"

namespace prism::gpu {

// Elements [first, first + count) of a buffer.
struct Range {
  size_t first = 0;
  size_t count = 0;
  friend bool operator==(const Range&, const Range&) = default;
};

struct BufferWrites {
  bool whole = false;     // send all of it (a buffer it no longer fits is made again)
  std::vector<Range> runs;  // otherwise only these, ascending; none: unchanged
  bool any() const { return whole || !runs.empty(); }
};

struct PackedUpdate {
  std::array<BufferWrites, kSceneBufferCount> buffers;  // by binding (kBindRecords ... kBindTexels)
  bool kernel = false;         // the primitive types or the features changed: generate and build again
  size_t objects_written = 0;  // objects whose entry and record are sent again
  bool bvh_built = false;
  bool bvh_refitted = false;
};

// A piece of a scene buffer to send: where it goes and its bytes.
struct ByteRange {
  size_t offset;
  const void* data;
  size_t size;
};
// The pieces of `source` that `writes` names (all of it when whole). When
// whole and larger than the buffer on the device, make that buffer again instead.
std::vector<ByteRange> byte_ranges(const SceneBuffer& source, const BufferWrites& writes);

// Brings `packed` (pack_scene of `scene` before the edit) up to date with
// `scene` after `changes`. Throws RuntimeError as pack_scene does.
PackedUpdate update_packed_scene(PackedScene& packed, const Scene& scene, const SceneChanges& changes);

// The cumulative counters of prism::counter in `stats`: all zero from the
// backend's creation on, then what a prepare (of `packed`) or an update did.
void start_counters(BackendStats& stats);
void count_prepare(BackendStats& stats, const PackedScene& packed);
void count_update(BackendStats& stats, const PackedUpdate& update);

// Runs of consecutive indices, ascending (input in any order, repeats allowed).
std::vector<Range> runs_of(std::vector<size_t> indices);

}  // namespace prism::gpu
