// Quadric primitive, written once for the CPU and the GPU (the shared
// dialect: prism/sdk/dialect.hpp): the module `quadric`
// (prism/sdk/modules/quadric.shared.glsl), which cylinder and cone run too,
// so the three give the same t and normal on both sides. Method: origin
// re-centred at the foot of the perpendicular (and at the vertex of f when
// the roots are close), stable roots c/q, q/a with an fma discriminant,
// first root in (tmin, tmax] inside the clip box, one Newton step onto
// f = 0 in surface. The record is the QuadricShape the module reads. uv is
// (0, 0).
//
// prism:require quadric

bool quadric_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  return prism_quadric_intersect(rec, ray, tmin, tmax, hit);
}

void quadric_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  prism_quadric_point_normal(rec, hit, s.point, s.normal);
  s.uv = real2(R(0.0));
}
