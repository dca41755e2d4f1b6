#include "prism/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/registry.hpp"
#include "prism/sdk/sphere_math.hpp"

namespace prism {

namespace {

glm::dvec3 load(const double v[3]) { return {v[0], v[1], v[2]}; }

double max_abs(const glm::dvec3& v) { return std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z)); }

// The local ray again in long double, from the rotation before rounding and
// with the direction normalised in long double (as the exact answer has it).
PrismRayExt to_local_ext(const Object& object, const Ray& ray) {
  using real = long double;
  const real o[3] = {real(ray.origin.x) - object.center.x, real(ray.origin.y) - object.center.y,
                     real(ray.origin.z) - object.center.z};
  const real d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
  PrismRayExt local;
  for (int i = 0; i < 3; ++i) {
    local.origin[i] = o[i];
    local.dir[i] = d[i];
  }
  if (object.rotation_ext) {
    const RotationExt& m = *object.rotation_ext;  // local = m^T world
    for (int i = 0; i < 3; ++i) {
      local.origin[i] = m[size_t(i)] * o[0] + m[size_t(3 + i)] * o[1] + m[size_t(6 + i)] * o[2];
      local.dir[i] = m[size_t(i)] * d[0] + m[size_t(3 + i)] * d[1] + m[size_t(6 + i)] * d[2];
    }
  }
  const real length = std::sqrt(local.dir[0] * local.dir[0] + local.dir[1] * local.dir[1] + local.dir[2] * local.dir[2]);
  for (real& c : local.dir) c /= length;
  return local;
}

// "primitive plugin 'torus' (FILE) ... for its object at (x, y, z)": the
// object has no index here, its type and centre name it.
std::string fault_message(const Object& object, const std::string& what) {
  char centre[96];
  std::snprintf(centre, sizeof centre, "(%g, %g, %g)", object.center.x, object.center.y, object.center.z);
  const std::string file = object.plugin ? " (" + object.plugin->path().string() + ")" : "";
  return "primitive plugin '" + std::string(object.desc->type_name) + "'" + file + " " + what + " for its object at " +
         centre;
}

std::string triple(const double v[3]) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", v[0], v[1], v[2]);
  return text;
}

bool finite3(const double v[3]) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

void check_surface(const Object& object, const PrismSurface& s) {
  // The usual case in one test: a sum is finite only if every term is (a
  // NaN or an infinity carries through; finite terms that overflow it take
  // the checks below, which pass them).
  const double sum = s.point[0] + s.point[1] + s.point[2] + s.normal[0] + s.normal[1] + s.normal[2] + s.uv[0] + s.uv[1];
  if (std::isfinite(sum)) return;
  if (!finite3(s.point))
    throw RuntimeError(fault_message(object, "returned a non-finite surface point " + triple(s.point)));
  if (!finite3(s.normal))
    throw RuntimeError(fault_message(object, "returned a non-finite surface normal " + triple(s.normal)));
  if (!std::isfinite(s.uv[0]) || !std::isfinite(s.uv[1])) {
    char uv[64];
    std::snprintf(uv, sizeof uv, "(%g, %g)", s.uv[0], s.uv[1]);
    throw RuntimeError(fault_message(object, std::string("returned a non-finite uv ") + uv));
  }
}

// Written in place: returned and copied, the surface was read back in
// 16-byte pieces across the plugin's 8-byte stores, which waited for them
// to retire (a store-forwarding stall).
void plugin_surface(const Object& object, const PrismRay& local, const PrismHit& found, bool want_uv, PrismSurface& s) {
  PrismHit hit = found;
  hit.flags = want_uv ? 0u : PRISM_HIT_SKIP_UV;  // whatever `intersect` left there
  s = PrismSurface{};
  object.desc->surface(object.record(), &local, &hit, &s);
  check_surface(object, s);
}

// The ulps of input error the double path may carry into the local ray (the
// subtraction of the centre, the rotation, the re-centring): generous, so
// that a hit is polished before its error could reach 1e-11.
constexpr double kInputUlps = 8.0;
constexpr double kPolishBelow = 1e-11;

}  // namespace

bool ill_conditioned(const PrismRay& local, double t, const PrismSurface& s) {
  // One ulp on the local ray moves the point by eps * (|o| + |p|); along the
  // ray that is that over the cosine between the ray and the surface.
  const glm::dvec3 n = load(s.normal), d = load(local.dir);
  // Nearly every hit is far from the threshold: settle those with bounds
  // (|v| <= 2 max|v_i|, and a factor 2 more for rounding) before three roots.
  const double reach_bound = 2.0 * (max_abs(load(local.origin)) + max_abs(load(s.point)));
  const double slope = std::abs(glm::dot(n, d)) * t;
  if (2.0 * kInputUlps * std::numeric_limits<double>::epsilon() * reach_bound * (2.0 * max_abs(n)) <= kPolishBelow * slope)
    return false;
  const double n_length = glm::length(n);
  if (!(n_length > 0.0) || !std::isfinite(n_length)) return false;  // undefined normal: nothing to polish against
  const double cosine = std::abs(glm::dot(n, d)) / n_length;
  const double reach = glm::length(load(local.origin)) + glm::length(load(s.point));
  return kInputUlps * std::numeric_limits<double>::epsilon() * reach > kPolishBelow * cosine * t;
}

bool reject_hit(const Object& object, double t, double tmin, double tmax) {
  if (cancel_requested()) return false;  // the run is stopping already: the first fault is the one named
  char text[128];
  std::snprintf(text, sizeof text, "returned a hit at t = %g, outside (tmin, tmax] = (%g, %g]", t, tmin, tmax);
  request_stop_for_fault(fault_message(object, text));
  return false;
}

void local_surface(const Object& object, const Ray& ray, const PrismHit& hit, IntersectEntry found_by, bool want_uv,
                   LocalSurface& out) {
  const PrismRay local = to_local(object, ray);
  plugin_surface(object, local, hit, want_uv, out.s);
  out.t = hit.t;
  if (object.desc->refine && found_by == kIntersectDouble && ill_conditioned(local, hit.t, out.s)) {
    const PrismRayExt ext = to_local_ext(object, ray);
    PrismHit polished = hit;
    object.desc->refine(object.record(), &ext, &polished);
    if (!std::isfinite(polished.t))
      throw RuntimeError(fault_message(object, "refined a hit to t = " + std::to_string(polished.t)));
    if (polished.t != hit.t) {
      plugin_surface(object, local, polished, want_uv, out.s);
      out.t = polished.t;
    }
  }
}

SurfacePoint world_surface(const Object& object, const Ray& ray, const LocalSurface& local) {
  glm::dvec3 point = load(local.s.point);
  glm::dvec3 normal = load(local.s.normal);
  if (object.has_rotation) {
    point = rotate(object.rotation, point);
    normal = rotate(object.rotation, normal);
  }
  SurfacePoint out;
  out.t = local.t;
  out.position = object.center + point;
  double length = glm::length(normal);
  // Where the normal is undefined (a quadric's singular point) the format says N = -dir.
  out.normal = (length > 0 && std::isfinite(length)) ? normal / length : -ray.dir;
  out.uv = {local.s.uv[0], local.s.uv[1]};
  return out;
}

SurfacePoint surface_of(const Object& object, const Ray& ray, const PrismHit& hit, IntersectEntry found_by,
                        bool want_uv) {
  LocalSurface local;
  local_surface(object, ray, hit, found_by, want_uv, local);
  return world_surface(object, ray, local);
}

WorldSphere world_bounding_sphere(const Object& object) {
  double lo[3], hi[3];
  object.desc->bounds(object.record(), lo, hi);
  glm::dvec3 local_center = 0.5 * (load(lo) + load(hi));
  double radius = 0.5 * glm::length(load(hi) - load(lo));
  double center[3], own_radius = 0;
  if (object.desc->bounding_sphere && object.desc->bounding_sphere(object.record(), center, &own_radius)) {
    if (!finite3(center) || !std::isfinite(own_radius) || own_radius < 0) {
      char text[160];
      std::snprintf(text, sizeof text, "returned a bounding sphere of centre (%g, %g, %g) and radius %g", center[0],
                    center[1], center[2], own_radius);
      throw RuntimeError(fault_message(object, text));
    }
    if (own_radius < radius) {
      local_center = load(center);
      radius = own_radius;
    }
  }
  const glm::dvec3 world_center = object.center + (object.has_rotation ? rotate(object.rotation, local_center) : local_center);
  const double rounding = 1e-15 * (max_abs(world_center) + max_abs(local_center) + max_abs(object.center));
  return {world_center, radius * (1 + 1e-12) + rounding};
}

std::vector<uint32_t> lights_with_spheres(const Scene& scene) {
  std::vector<uint32_t> lights;
  for (size_t k = 0; k < scene.lights.size(); ++k)
    if (scene.lights[k].visible_sphere()) lights.push_back(uint32_t(k));
  return lights;
}

Hit intersect_light_spheres(const Scene& scene, std::span<const uint32_t> lights, const Ray& ray, double tmin,
                            double tmax) {
  Hit best;
  for (const uint32_t k : lights) {
    const Light& light = scene.lights[k];
    const glm::dvec3 o = ray.origin - light.position;
    // Most rays pass a light sphere by far. Their squared distance from its
    // centre, |o|^2 - (o.d)^2, is off by at most ~12 eps |o|^2 here (and
    // intersect_sphere's own by less), so where it exceeds r^2 by 1e-12 |o|^2
    // intersect_sphere finds no root either, and the rest pay for it.
    const double oo = glm::dot(o, o), od = glm::dot(o, ray.dir);
    if (oo - od * od > light.radius * light.radius + 1e-12 * oo) continue;
    double t;
    if (sdk::intersect_sphere(o, ray.dir, light.radius, tmin, tmax, t) && t < best.t) {
      best.t = t;
      best.id = light_sphere_id(static_cast<int>(k));
    }
  }
  return best;
}

}  // namespace prism
