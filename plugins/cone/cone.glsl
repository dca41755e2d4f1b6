// Cone, GPU intersector: the quadric [1,-(radius/height)^2,1,0,0,0,0,0,0,0]
// clipped to 0 <= y <= height (apex at the origin, where the gradient and so
// the normal are all zeros), run by the core module `quadric`
// (core/glsl/quadric.glsl), the GLSL port of prism/sdk/quadric_math.hpp and
// axial_quadric.hpp that the quadric plugin runs too: t and the normal are
// those of the equivalent `quadric` object, on the GPU as on the CPU.
// Method: origin re-centred at the foot of the perpendicular, stable roots,
// clip test on the point formed in that frame, one Newton step onto the
// surface. Double: a camera 1e6 away loses o - c itself in float32
// (docs/numerics.md, Quadratics / Float and double); only the uv
// azimuth is float. The record is the AxialQuadricRecord whose offsets the
// module defines and cone.cpp static_asserts.
//
// prism:require quadric

bool cone_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  return prism_quadric_intersect(rec, ray, tmin, tmax, hit);
}

// u = 0.5 + atan2(z, x)/2pi, v = y/height.
void cone_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  prism_axial_quadric_surface(rec, hit, s);
}
