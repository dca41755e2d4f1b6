// Quadric, GPU intersector: the core module `quadric` (core/glsl/quadric.glsl),
// the GLSL port of prism/sdk/quadric_math.hpp that cylinder and cone share,
// so the three give the same t and normal on the GPU as on the CPU. Method:
// origin re-centred at the foot of the perpendicular, stable roots c/q, q/a
// with an fma discriminant, first root in (tmin, tmax] inside the clip box,
// one Newton step onto f = 0 in surface. Double: a camera 1e6 away loses
// o - c itself in float32, and tiny `a` must keep its accurate near root
// (docs/numerics.md, Quadratics). The record is the QuadricShape the
// module reads (its offsets are static_asserted in cylinder.cpp and cone.cpp
// against the one C++ struct). uv is (0, 0), as on the CPU.
//
// prism:require quadric

bool quadric_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  return prism_quadric_intersect(rec, ray, tmin, tmax, hit);
}

void quadric_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  prism_quadric_point_normal(rec, hit, s.point, s.normal);
  s.uv = dvec2(0.0LF);
}
