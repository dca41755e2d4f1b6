#include "plugin_packets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "prism/geometry.hpp"

namespace prism::cli {

namespace {

constexpr unsigned kLanes = PRISM_PACKET_SIZE;

// Beside each ray that hits: one starting just inside the surface along the
// same direction, and one skimming the surface at the hit point.
std::vector<Ray> rays_with_stiff_cases(const Object& object, std::span<const TraceQuery> given) {
  const double size = object.bounded ? glm::length(object.world_bounds.hi - object.world_bounds.lo) : 4.0;
  std::vector<Ray> rays;
  for (const TraceQuery& q : given) {
    const Ray ray{q.origin, q.dir};
    rays.push_back(ray);
    PrismHit hit;
    if (!intersect_object(object, ray, 0.0, kInfinity, hit)) continue;
    const SurfacePoint s = surface_of(object, ray, hit);
    rays.push_back(Ray{s.position + 1e-3 * size * ray.dir, ray.dir});
    const glm::dvec3 across = glm::cross(s.normal, ray.dir);
    if (glm::length(across) > 1e-9) {
      const glm::dvec3 tangent = glm::normalize(glm::cross(across, s.normal));
      rays.push_back(Ray{s.position - size * tangent, tangent});
    }
  }
  return rays;
}

std::string describe(const char* what, const Ray& ray, double tmin, double tmax) {
  char text[512];
  std::snprintf(text, sizeof text, "%s differs for the ray from (%.17g, %.17g, %.17g) along (%.17g, %.17g, %.17g), "
                "t in (%.17g, %.17g]", what, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y,
                ray.dir.z, tmin, tmax);
  return text;
}

struct PacketBounds {
  uint32_t active = 0;
  double tmin[kLanes] = {};
  double tmax[kLanes] = {};
};

// Random lanes, and bounds that cut some hits: tmax at, just below, just
// above, or past a scalar hit, tmin 0 or a little more.
PacketBounds random_bounds(const Object& object, const Ray* rays, unsigned count, std::mt19937_64& rng) {
  PacketBounds b;
  const uint32_t all = count >= 32 ? ~0u : (1u << count) - 1u;
  while (b.active == 0) b.active = uint32_t(rng()) & all;
  for (unsigned i = 0; i < count; ++i) {
    b.tmin[i] = rng() % 4 == 0 ? 1e-3 : 0.0;
    PrismHit hit;
    const bool hits = intersect_object(object, rays[i], b.tmin[i], kInfinity, hit);
    switch (rng() % 4) {
      case 0: b.tmax[i] = kInfinity; break;
      case 1: b.tmax[i] = hits ? hit.t : 10.0; break;
      case 2: b.tmax[i] = hits ? std::nextafter(hit.t, kInfinity) : 0.5; break;
      default: b.tmax[i] = hits ? std::nextafter(hit.t, 0.0) : 1.0; break;
    }
  }
  return b;
}

bool same_hit(const PrismHit& a, const PrismHit& b) {
  return a.t == b.t && std::memcmp(a.data, b.data, sizeof a.data) == 0 && a.part == b.part;
}

void check_packet(const Object& object, const Ray* rays, unsigned count, std::mt19937_64& rng, PacketCheck& out) {
  const PacketBounds b = random_bounds(object, rays, count, rng);
  PrismHit hits[kLanes];
  const uint32_t found = intersect_object_packet(object, rays, b.active, b.tmin, b.tmax, hits);
  const uint32_t blocked = blocks_packet(object, rays, b.active, b.tmax);
  for (unsigned i = 0; i < count; ++i) {
    if (!(b.active >> i & 1u)) continue;
    ++out.rays;
    PrismHit hit;
    const bool scalar_found = intersect_object(object, rays[i], b.tmin[i], b.tmax[i], hit);
    const bool packet_found = (found >> i & 1u) != 0;
    const bool closest_ok = scalar_found == packet_found && (!scalar_found || same_hit(hit, hits[i]));
    // The occlusion entries against intersect's hit below tmax: `occluded`
    // with the lane's bounds, the packet's with tmin 0 (blocks_packet).
    const PrismRay local = to_local(object, rays[i]);
    const bool scalar_occluded = object.desc->occluded(object.record(), &local, b.tmin[i], b.tmax[i]) != 0;
    PrismHit from_zero;
    const bool blocked_from_zero = intersect_object(object, rays[i], 0.0, b.tmax[i], from_zero) && from_zero.t < b.tmax[i];
    const bool occluded_ok = scalar_occluded == (scalar_found && hit.t < b.tmax[i]);
    const bool packet_occluded_ok = ((blocked >> i & 1u) != 0) == blocked_from_zero;
    if (closest_ok && occluded_ok && packet_occluded_ok) continue;
    const char* which = !closest_ok ? "intersect_packet" : !occluded_ok ? "occluded" : "occluded_packet";
    if (out.mismatches++ == 0) out.first = describe(which, rays[i], b.tmin[i], b.tmax[i]);
  }
}

}  // namespace

PacketCheck check_packet_entries(const Object& object, std::span<const TraceQuery> given) {
  const std::vector<Ray> rays = rays_with_stiff_cases(object, given);
  std::mt19937_64 rng(20261202);
  PacketCheck out;
  for (size_t at = 0; at < rays.size(); at += kLanes)
    check_packet(object, &rays[at], unsigned(std::min<size_t>(kLanes, rays.size() - at)), rng, out);
  return out;
}

PacketCheck check_surface_without_uv(const Object& object, std::span<const TraceQuery> given) {
  PacketCheck out;
  for (const Ray& ray : rays_with_stiff_cases(object, given)) {
    PrismHit hit;
    if (!intersect_object(object, ray, 0.0, kInfinity, hit)) continue;
    ++out.rays;
    const SurfacePoint all = surface_of(object, ray, hit, kIntersectDouble, true);
    const SurfacePoint no_uv = surface_of(object, ray, hit, kIntersectDouble, false);
    const bool same = std::memcmp(&all.t, &no_uv.t, sizeof all.t) == 0 &&
                      std::memcmp(&all.position, &no_uv.position, sizeof all.position) == 0 &&
                      std::memcmp(&all.normal, &no_uv.normal, sizeof all.normal) == 0;
    if (!same && out.mismatches++ == 0) out.first = describe("surface without uv", ray, 0.0, kInfinity);
  }
  return out;
}

PacketCheck check_bounding_sphere(const Object& object, std::span<const TraceQuery> given) {
  PacketCheck out;
  const WorldSphere sphere = world_bounding_sphere(object);
  for (const Ray& ray : rays_with_stiff_cases(object, given)) {
    PrismHit hit;
    if (!intersect_object(object, ray, 0.0, kInfinity, hit)) continue;
    ++out.rays;
    // The plugin's own point for its hit (not the core's polish of an
    // ill-conditioned one, which may slide along a ray that runs in the surface).
    const PrismRay local = to_local(object, ray);
    PrismHit found = hit;
    found.flags = PRISM_HIT_SKIP_UV;
    PrismSurface s{};
    object.desc->surface(object.record(), &local, &found, &s);
    const glm::dvec3 point{s.point[0], s.point[1], s.point[2]};
    const glm::dvec3 position = object.center + (object.has_rotation ? rotate(object.rotation, point) : point);
    const double distance = glm::length(position - sphere.center);
    if (!(distance <= sphere.radius * (1 + 1e-9)) && out.mismatches++ == 0) {
      char text[160];
      std::snprintf(text, sizeof text, "a hit point %.17g from the centre, radius %.17g, ", distance, sphere.radius);
      out.first = text + describe("ray", ray, 0.0, kInfinity);
    }
  }
  return out;
}

namespace {

// Both entries on each ray; the relative t errors where both hit.
FloatTally tally_float_entry(const Object& object, std::span<const Ray> rays) {
  FloatTally out;
  std::vector<double> t_errors;
  for (const Ray& ray : rays) {
    ++out.rays;
    PrismHit in_double, in_float;
    const bool hit_double = intersect_object(object, ray, 0.0, kInfinity, in_double, kIntersectDouble);
    const bool hit_float = intersect_object(object, ray, 0.0, kInfinity, in_float, kIntersectFloat);
    if (hit_double != hit_float) ++out.misclassified;
    if (hit_double && hit_float) t_errors.push_back(std::abs(in_float.t - in_double.t) / in_double.t);
  }
  if (!t_errors.empty()) {
    std::sort(t_errors.begin(), t_errors.end());
    out.t_p99 = t_errors[std::min(t_errors.size() - 1, size_t(std::ceil(0.99 * double(t_errors.size()))) - 1)];
    out.t_max = t_errors.back();
  }
  return out;
}

}  // namespace

FloatCheck check_float_entry(const Object& object, std::span<const TraceQuery> given) {
  FloatCheck out;
  out.has_float = object.desc->intersect_float != object.desc->intersect;
  std::vector<Ray> random, stiff;
  for (const Ray& ray : rays_with_stiff_cases(object, given)) {
    const bool is_given = random.size() < given.size() && ray.origin == given[random.size()].origin &&
                          ray.dir == given[random.size()].dir;
    (is_given ? random : stiff).push_back(ray);
  }
  out.random = tally_float_entry(object, random);
  out.stiff = tally_float_entry(object, stiff);
  return out;
}

}  // namespace prism::cli
