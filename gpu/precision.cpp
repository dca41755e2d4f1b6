#include "precision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace prism::gpu {

namespace {

constexpr double kFloatUnit = 0x1p-24;  // float's unit roundoff
// Roundings a hit point collects in the float world: the ray moved into the
// object's frame (subtract, rotate), o + t d, and back (rotate, add).
constexpr double kRoundings = 4;
// The hit point's error may be at most this part of the spec's secondary-ray
// offset 1e-4 (1 + max|P_i|): a spawned ray must never find its own surface.
constexpr double kOffsetShare = 0.1;
// ... at most this part of the object's smallest feature (normals and
// silhouettes move by about the ratio, in radians: 1e-3 rad moves a Phong
// highlight of exponent 100 by well under the conformance threshold 0.016)...
constexpr double kFeatureShare = 1e-3;
// ... and at most this part of the distance from the camera to the object
// (a camera ray's relative t error: the GPU cap is 1e-4 at the 99th
// percentile; this keeps a 10x margin).
constexpr double kDistanceShare = 1e-5;

double max_abs(const glm::dvec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// The farthest corner of `box` from `p`, and the nearest point's distance.
double farthest(const Box3& box, const glm::dvec3& p) {
  glm::dvec3 d;
  for (int a = 0; a < 3; ++a) d[a] = std::max(std::fabs(box.lo[a] - p[a]), std::fabs(box.hi[a] - p[a]));
  return glm::length(d);
}
double nearest(const Box3& box, const glm::dvec3& p) {
  return glm::length(glm::max(glm::max(box.lo - p, p - box.hi), glm::dvec3(0)));
}

// The smallest non-zero half extent of the object's local box: a torus's
// tube, a thin slab's thickness, a small sphere's radius (flat objects,
// with a zero extent, are judged by their other two).
double smallest_feature(const Object& object) {
  double lo[3], hi[3];
  if (!object.desc->bounds || !object.desc->bounds(object.record(), lo, hi)) return 0;
  double feature = INFINITY;
  for (int a = 0; a < 3; ++a)
    if (double half = 0.5 * (hi[a] - lo[a]); half > 0) feature = std::min(feature, half);
  return std::isfinite(feature) ? feature : 0;
}

std::string figures(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

}  // namespace

double float_point_error(double far) { return kRoundings * kFloatUnit * far; }

ObjectPrecision object_precision(const Object& object, const glm::dvec3& anchor) {
  ObjectPrecision result;
  // A plugin whose GLSL is not in the shared dialect has no float version
  // (ABI 4 marks it by an intersect_float that is its double intersect).
  if (object.desc->intersect_float == object.desc->intersect) {
    result.needs_double = true;
    result.reason = "its plugin has no float instantiation";
    return result;
  }
  // An unbounded object (a plane) is exact to float's resolution everywhere
  // a camera ray meets it: its error grows with t, as the offset does.
  if (!object.bounded) return result;
  const Box3& box = object.world_bounds;
  const double error = float_point_error(farthest(box, anchor));
  glm::dvec3 nearest_point;
  for (int a = 0; a < 3; ++a) nearest_point[a] = std::clamp(0.0, box.lo[a], box.hi[a]);
  const double offset = 1e-4 * (1 + max_abs(nearest_point));
  const double feature = smallest_feature(object);
  const double distance = nearest(box, anchor);
  if (error > kOffsetShare * offset) {
    result.reason = figures("hit-point error ~%.2g in float over the secondary-ray offset's share %.2g", error,
                            kOffsetShare * offset);
  } else if (feature > 0 && error > kFeatureShare * feature) {
    result.reason = figures("hit-point error ~%.2g in float against its smallest feature %.2g", error, feature);
  } else if (error > kDistanceShare * distance) {
    result.reason = figures("hit-point error ~%.2g in float against its distance %.2g from the camera", error,
                            distance);
  }
  result.needs_double = !result.reason.empty();
  return result;
}

WorldChoice choose_world(const Scene& scene, Precision requested, bool trace, bool device_has_double) {
  WorldChoice choice;
  choice.anchor = scene.camera.position;
  size_t doubles = 0;
  std::string reasons;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    choice.per_object.push_back(object_precision(scene.objects[i], choice.anchor));
    const ObjectPrecision& p = choice.per_object.back();
    if (!p.needs_double) continue;
    ++doubles;
    if (doubles <= 4)
      reasons += (reasons.empty() ? "" : "; ") + std::string("object ") + std::to_string(i) + " (" +
                 scene.objects[i].desc->type_name + "): " + p.reason;
  }
  if (!device_has_double) choice.float_world = true;
  else if (requested == Precision::automatic) choice.float_world = !trace && doubles == 0;
  else choice.float_world = requested == Precision::float32;
  if (!choice.float_world) choice.anchor = glm::dvec3(0);
  choice.description = choice.float_world ? "float" : "double geometry, float32 shading";
  const std::string counts = std::to_string(scene.objects.size() - doubles) + " of " +
                             std::to_string(scene.objects.size()) + " objects float-safe";
  if (doubles == 0) choice.objects = counts;
  else choice.objects = counts + "; double needed for " + reasons + (doubles > 4 ? "; ..." : "");
  if (requested == Precision::automatic && trace && device_has_double)
    choice.objects += " (prism trace: double for arbitrary rays)";
  if (!device_has_double && (doubles > 0 || requested == Precision::float64))
    choice.warning = "the device has no double precision (shaderFloat64), so this scene runs in float" +
                     std::string(requested == Precision::float64 ? " although double was asked for" : "") +
                     (doubles > 0 ? "; expect errors beyond the GPU bounds at " + reasons + (doubles > 4 ? "; ..." : "")
                                  : std::string());
  return choice;
}

glm::dvec3 trace_anchor(std::span<const TraceQuery> rays) {
  glm::dvec3 sum{0};
  for (const TraceQuery& ray : rays) sum += ray.origin;
  return rays.empty() ? sum : sum / double(rays.size());
}

}  // namespace prism::gpu
