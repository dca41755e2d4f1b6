// World-space rays and hits, and the per-object transform into a plugin's
// local frame. Shared by every CPU backend.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "prism/scene.hpp"

namespace prism {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Ray {
  glm::dvec3 origin{0};
  glm::dvec3 dir{0, 0, 1};  // unit length
};

// Id of light k's visible sphere, as the spec numbers it.
constexpr int32_t light_sphere_id(int k) { return -2 - k; }
constexpr int32_t kMissId = -1;

struct Hit {
  double t = kInfinity;
  int32_t id = kMissId;  // object id, light_sphere_id(k), or kMissId
  PrismHit prim{};       // plugin data for Object::surface (objects only)
  bool found() const { return id != kMissId; }
};

struct SurfacePoint {
  double t = 0;            // the hit's t, polished where the double t was ill-conditioned
  glm::dvec3 position{0};  // world P
  glm::dvec3 normal{0};    // world outward unit N (-dir where undefined)
  glm::dvec2 uv{0};
};

// R v and R^T v with glm's operations in glm's order (glm::dmat3 * dvec3,
// and that of glm::transpose(R)), so every bit is the same, written out:
// the compiler left glm's product out of line in the hot loops, and built
// the transposed copy for every ray and object.
inline glm::dvec3 rotate(const glm::dmat3& r, const glm::dvec3& v) {
  return {r[0][0] * v.x + r[1][0] * v.y + r[2][0] * v.z, r[0][1] * v.x + r[1][1] * v.y + r[2][1] * v.z,
          r[0][2] * v.x + r[1][2] * v.y + r[2][2] * v.z};
}
inline glm::dvec3 rotate_back(const glm::dmat3& r, const glm::dvec3& v) {
  return {r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z, r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
          r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z};
}

// Ray in the object's local frame (t is preserved: rotations are orthonormal).
// Inline, with intersect_object: every candidate object of every ray passes here.
// Two returns, each from values in registers: one local `dir`, copied
// from the ray and overwritten under the rotation, was kept in memory by
// GCC, stored as 16 + 8 bytes and read back as 8 + 16, and the read waited
// for the stores to retire (a store-forwarding stall, ~1.6 % of a showcase
// frame in surface_of alone, by perf).
inline PrismRay to_local(const Object& object, const Ray& ray) {
  const glm::dvec3 origin = ray.origin - object.center;
  if (!object.has_rotation) return PrismRay{{origin.x, origin.y, origin.z}, {ray.dir.x, ray.dir.y, ray.dir.z}};
  // R is orthonormal: its inverse is its transpose, and t is unchanged.
  const glm::dvec3 o = rotate_back(object.rotation, origin), d = rotate_back(object.rotation, ray.dir);
  return PrismRay{{o.x, o.y, o.z}, {d.x, d.y, d.z}};
}

// A hit a plugin returned outside (tmin, tmax] or at a NaN or infinite t:
// stops the run with an error naming the plugin and the object
// (request_stop_for_fault: this may run inside Embree, which swallows
// exceptions) and drops the hit. Returns false. Never reached by a sound plugin.
bool reject_hit(const Object& object, double t, double tmin, double tmax);

// Which of a plugin's intersectors a CPU query calls: `intersect` (double),
// or `intersect_float` (--precision float on the reference backend).
using IntersectEntry = int (*PrismPrimitiveDesc::*)(const void*, const PrismRay*, double, double, PrismHit*);
inline constexpr IntersectEntry kIntersectDouble = &PrismPrimitiveDesc::intersect;
inline constexpr IntersectEntry kIntersectFloat = &PrismPrimitiveDesc::intersect_float;

// Closest hit on one object with tmin < t <= tmax.
inline bool intersect_object(const Object& object, const Ray& ray, double tmin, double tmax, PrismHit& hit,
                             IntersectEntry entry = kIntersectDouble) {
  const PrismRay local = to_local(object, ray);
  if ((object.desc->*entry)(object.record(), &local, tmin, tmax, &hit) == 0) return false;
  // The plugin's word is checked, not trusted (a NaN fails the first test).
  if (!(hit.t > tmin && hit.t <= tmax) || hit.t == kInfinity) [[unlikely]]
    return reject_hit(object, hit.t, tmin, tmax);
  return true;
}

// Lanes of a packet of world rays (lane i is rays[i]) in the object's local
// frame, each exactly as to_local moves it.
inline void to_local_packet(const Object& object, const Ray* rays, uint32_t active, PrismRayPacket& out) {
  for (uint32_t lanes = active; lanes != 0; lanes &= lanes - 1) {
    const unsigned i = unsigned(__builtin_ctz(lanes));
    const PrismRay local = to_local(object, rays[i]);
    for (int a = 0; a < 3; ++a) {
      out.origin[a][i] = local.origin[a];
      out.dir[a][i] = local.dir[a];
    }
  }
}

// intersect_object for the lanes of a packet, tmin[i] < t <= tmax[i]; the
// mask of lanes hit. One call into the plugin for the whole packet.
inline uint32_t intersect_object_packet(const Object& object, const Ray* rays, uint32_t active, const double* tmin,
                                        const double* tmax, PrismHit* hits) {
  PrismRayPacket packet;
  to_local_packet(object, rays, active, packet);
  for (uint32_t lanes = active; lanes != 0; lanes &= lanes - 1) {
    const unsigned i = unsigned(__builtin_ctz(lanes));
    packet.tmin[i] = tmin[i];
    packet.tmax[i] = tmax[i];
  }
  return object.desc->intersect_packet(object.record(), &packet, active, hits);
}

// blocks() for the lanes of a packet: the mask of lanes hit with 0 < t < tmax[i].
inline uint32_t blocks_packet(const Object& object, const Ray* rays, uint32_t active, const double* tmax) {
  PrismRayPacket packet;
  to_local_packet(object, rays, active, packet);
  for (uint32_t lanes = active; lanes != 0; lanes &= lanes - 1) {
    const unsigned i = unsigned(__builtin_ctz(lanes));
    packet.tmin[i] = 0.0;
    packet.tmax[i] = tmax[i];
  }
  return object.desc->occluded_packet(object.record(), &packet, active);
}

// Whether one object is hit with 0 < t < tmax: the occlusion test. Inline
// like intersect_object: a backend's shadow-ray loop calls it per candidate.
// In double the plugin's `occluded` answers (the same answer, sometimes
// without solving for t); in float, `intersect_float`'s hit below tmax.
inline bool blocks(const Object& object, const Ray& ray, double tmax, IntersectEntry entry = kIntersectDouble) {
  if (entry == kIntersectDouble) {
    const PrismRay local = to_local(object, ray);
    return object.desc->occluded(object.record(), &local, 0.0, tmax) != 0;
  }
  PrismHit hit;
  return intersect_object(object, ray, 0.0, tmax, hit, entry) && hit.t < tmax;
}

// World-space point, outward normal and uv of a hit found by intersect_object.
// A plugin's surface with a non-finite point, normal or uv (or a polish to a
// non-finite t) throws RuntimeError naming the plugin and the object.
// Where one ulp of input rounding could move the hit's t by more than ~1e-11
// relative (a grazing ray, a hit far from the object's origin), the plugin's
// `refine` first polishes t in long double; `t` is the result. A hit found
// by `intersect_float` is not polished: the float path models a GPU kernel,
// which has no wider type to polish in.
// `want_uv` false: the caller will not read `uv` (PRISM_HIT_SKIP_UV; it
// may then be 0), and point, normal and t are the same bits.
SurfacePoint surface_of(const Object& object, const Ray& ray, const PrismHit& hit,
                        IntersectEntry found_by = kIntersectDouble, bool want_uv = true);

// surface_of in two halves, for callers that work out many surfaces: the
// plugin's answer in the object's frame (checked, and polished where
// ill-conditioned), then the world-space point and unit normal from it.
// world_surface(object, ray, local_surface(object, ray, hit, ...)) is
// surface_of(object, ray, hit, ...), bit for bit.
struct LocalSurface {
  PrismSurface s;
  double t;
};
void local_surface(const Object& object, const Ray& ray, const PrismHit& hit, IntersectEntry found_by, bool want_uv,
                   LocalSurface& out);
SurfacePoint world_surface(const Object& object, const Ray& ray, const LocalSurface& local);

// Whether a hit at `t` on the local ray, with local surface point and
// normal `s`, is that ill-conditioned (exposed for tests).
bool ill_conditioned(const PrismRay& local, double t, const PrismSurface& s);

// The lights of `scene` whose sphere is visible, ascending.
std::vector<uint32_t> lights_with_spheres(const Scene& scene);

// A world-space sphere that holds a bounded object: the smaller of its
// plugin's bounding_sphere (ABI 5, optional) and the sphere around its
// local box, moved by the object's frame (a rotation keeps the radius:
// tighter than a sphere around the world box of a rotated object), grown
// by 1e-12 relative and 1e-15 of the coordinates for the rounding of the
// centre. Throws RuntimeError naming the plugin when the plugin's sphere is
// not finite or has a negative radius.
struct WorldSphere {
  glm::dvec3 center{0};
  double radius = 0;
};
WorldSphere world_bounding_sphere(const Object& object);
// Closest sphere of `lights` (from lights_with_spheres) with tmin < t <= tmax
// (ties: lower light index).
Hit intersect_light_spheres(const Scene& scene, std::span<const uint32_t> lights, const Ray& ray, double tmin,
                            double tmax);

// The outward unit normal of the light sphere that `hit` (found by
// intersect_light_spheres for `ray`) lies on.
inline glm::dvec3 light_sphere_normal(const Scene& scene, const Ray& ray, const Hit& hit) {
  const Light& light = scene.lights[size_t(-2 - hit.id)];
  return glm::normalize(ray.origin + hit.t * ray.dir - light.position);
}

}  // namespace prism
