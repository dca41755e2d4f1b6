#include "prism/geometry.hpp"

#include "prism/sdk/sphere_math.hpp"

namespace prism {

namespace {

void store(const glm::dvec3& v, double out[3]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

glm::dvec3 load(const double v[3]) { return {v[0], v[1], v[2]}; }

}  // namespace

PrismRay to_local(const Object& object, const Ray& ray) {
  PrismRay local;
  glm::dvec3 origin = ray.origin - object.center;
  glm::dvec3 dir = ray.dir;
  if (object.has_rotation) {
    // R is orthonormal: its inverse is its transpose, and t is unchanged.
    glm::dmat3 inverse = glm::transpose(object.rotation);
    origin = inverse * origin;
    dir = inverse * dir;
  }
  store(origin, local.origin);
  store(dir, local.dir);
  return local;
}

bool intersect_object(const Object& object, const Ray& ray, double tmin, double tmax, PrismHit& hit) {
  PrismRay local = to_local(object, ray);
  return object.desc->intersect(object.record(), &local, tmin, tmax, &hit) != 0;
}

SurfacePoint surface_of(const Object& object, const Ray& ray, const PrismHit& hit) {
  PrismRay local = to_local(object, ray);
  PrismSurface s{};
  object.desc->surface(object.record(), &local, &hit, &s);
  glm::dvec3 point = load(s.point);
  glm::dvec3 normal = load(s.normal);
  if (object.has_rotation) {
    point = object.rotation * point;
    normal = object.rotation * normal;
  }
  SurfacePoint out;
  out.position = object.center + point;
  double length = glm::length(normal);
  // Where the normal is undefined (a quadric's singular point) the format says N = -dir.
  out.normal = (length > 0 && std::isfinite(length)) ? normal / length : -ray.dir;
  out.uv = {s.uv[0], s.uv[1]};
  return out;
}

Hit intersect_light_spheres(const Scene& scene, const Ray& ray, double tmin, double tmax) {
  Hit best;
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    const Light& light = scene.lights[k];
    if (!light.visible_sphere()) continue;
    double t;
    if (sdk::intersect_sphere(ray.origin - light.position, ray.dir, light.radius, tmin, tmax, t) && t < best.t) {
      best.t = t;
      best.id = light_sphere_id(static_cast<int>(k));
    }
  }
  return best;
}

}  // namespace prism
