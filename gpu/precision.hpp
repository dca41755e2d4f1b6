// Which world precision a GPU kernel computes in (gpu/scene.glsl): float,
// with every position relative to an anchor, or double. The rule is
// docs/numerics.md, "Float or double on the GPU".
#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prism/backend.hpp"
#include "prism/scene.hpp"

namespace prism::gpu {

// What the rule found for one object.
struct ObjectPrecision {
  bool needs_double = false;
  std::string reason;  // why, with the figures; empty when float suffices
};

struct WorldChoice {
  bool float_world = false;
  glm::dvec3 anchor{0};
  std::string description;                // what --stats info.precision says
  std::string objects;                    // what --stats info.precision_objects says
  std::string warning;                    // non-empty when float is forced where double was needed
  std::vector<ObjectPrecision> per_object;
};

// The rule's estimate of a float world's error at a hit on a bounded object
// whose box lies `far` (its farthest corner) from the anchor: a few roundings
// of numbers that large.
double float_point_error(double far);

// What float would do to `object` in a world anchored at `anchor`.
ObjectPrecision object_precision(const Object& object, const glm::dvec3& anchor);

// The world a backend renders `scene` in when asked for `requested`; for
// `trace` (arbitrary rays, not the camera's) automatic means double. On a
// device without double (`device_has_double` false) every world is float,
// and `warning` names the objects the rule wanted in double, with the
// errors it expects there.
WorldChoice choose_world(const Scene& scene, Precision requested, bool trace = false, bool device_has_double = true);

// Where a float world answering `rays` is anchored: the mean of their
// origins, so that positions near them keep float's resolution (a ray
// query's origins need not be near the scene's camera).
glm::dvec3 trace_anchor(std::span<const TraceQuery> rays);

}  // namespace prism::gpu
