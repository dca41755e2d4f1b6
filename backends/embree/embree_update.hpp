// Updates of an EmbreeQuery's BVH after objects were edited in place
// (Backend::update), without a build from scratch.
//
// WHY NOT EMBREE'S REFIT
//
// Embree 3 refits a scene of quality RTC_BUILD_QUALITY_LOW (two-level)
// whose geometries have quality RTC_BUILD_QUALITY_REFIT, but not user
// geometry: Embree 3.13.5 (Debian 12; BVH8 on AVX-512, and BVH4 with
// max_isa=SSE4.2 alike) builds a REFIT user geometry's tree again on every
// commit. Measured on 10,000 spheres: after half of them were scattered, the
// "refitted" tree's SAH cost (verbose=3) equals a fresh build's to the last
// digit, and a one-object update costs about a build (6-8 ms against 6-10).
// That mode also renders the showcase ~9% slower (154 against 141 ms a
// frame). Chunks of 256 objects, each an instanced scene, so that an update
// rebuilds one chunk, update in 0.13 ms but trace 10,000 spheres ~70% slower
// (106 against 63 ms for 200,000 rays): rays enter several chunks.
//
// LAYERS
//
// So the main tree is never touched after its build. The first update that
// moves BVH objects makes a top-level scene holding an instance of the main
// scene (identity transform) and a user geometry of the moved objects. A
// moved object is skipped in the main tree (its callbacks return at once;
// its stale box stays there) and lives in the top level, which each update
// builds again: O(m log m) for m moved objects. Rays pay ~0.02-0.05 us each
// for the instance step and the moved objects' boxes (+8-28% on 100,000
// rays; the most on small scenes, whose rays are cheapest); when that beats
// a build is the backend's policy (embree_backend.cpp).
//
// THE COST LIMIT
//
// Embree's trees are opaque, so what the layers cost is estimated from the
// objects' boxes, as the surface-area heuristic would: the chance that a
// ray meets a box is its surface area. A ray meets every box of the main
// tree, stale ones included, and every box of the moved tree; a fresh build
// would give it only the boxes now. So
//     layered_cost = (Σ area(boxes when built) + Σ area(moved boxes now))
//                    / Σ area(boxes now)
// is 1 after a build and grows by about each moved object's share of the
// area, however often it moves. Past kMaxLayeredCost the backend builds a
// new query, which also bounds the top level's rebuilds.
#pragma once

#include "prism/scene.hpp"

namespace prism::embree {

// A rebuild is due once the layers' boxes cost this much more than a fresh
// build's: about a tenth of the objects moved. Each update then rebuilds at
// most about a tenth of a build in its top level, and tracing pays at most
// ~35% (10,000 spheres: +10% with 10 scattered, +36% with 1,000, +51% with
// 2,000, all against a fresh build).
constexpr double kMaxLayeredCost = 1.1;
// The frame's box B is the BVH objects' union box grown on every side by
// this much of its largest extent: an object may move that far out of the
// others' box (off a flat field of spheres, say) before an update needs a
// new build. A larger B only makes the padding (4e-6 of it) and the clipped
// rays a little longer (embree_query.cpp).
constexpr double kFrameSlack = 0.25;

// Half the surface area of a box (xy + yz + zx); 0 for an empty one.
double half_area(const Box3& box);
Box3 box_union(const Box3& a, const Box3& b);
bool box_contains(const Box3& outer, const Box3& inner);
// The box that contains nothing (the identity of box_union).
Box3 empty_box();

}  // namespace prism::embree
