// Cylinder primitive, written once for the CPU and the GPU (the shared dialect:
// prism/sdk/dialect.hpp): the quadric [1,0,1,0,0,0,0,0,0,-radius^2]
// clipped to 0 <= y <= height, an open tube around local y.
//
// It has no numerics of its own: intersect and surface are the module
// `quadric` (prism/sdk/modules/quadric.shared.glsl), which the quadric and
// the other axial plugin run too, so t and the normal are bit-identical to
// those of the equivalent `quadric` object, on the CPU as on the GPU. The
// record is the AxialQuadricRecord of prism/sdk/axial_quadric.hpp, whose
// offsets the module defines.
//
// prism:require quadric

bool cylinder_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  return prism_quadric_intersect(rec, ray, tmin, tmax, hit);
}

// u = 0.5 + atan2(z, x)/2pi, v = y/height.
void cylinder_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  prism_axial_quadric_surface(rec, hit, s);
}
