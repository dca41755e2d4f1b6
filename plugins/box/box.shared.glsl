// Box primitive, written once for the CPU and the GPU (the shared dialect:
// prism/sdk/dialect.hpp): |p.x| <= hx, |p.y| <= hy, |p.z| <= hz in the local
// frame.
//
// - intersect: the slab method in a frame re-centred at the foot of the
//   perpendicular from the box centre, so each slab distance (+-h - o_i)/d_i
//   is formed from numbers of the box's size even for a camera 1e6 away
//   (double: float32 loses o - c itself there; docs/numerics.md, Float and
//   double; Box). An axis with d_i == 0 exactly is either always inside its
//   slab or a miss (no 0 * inf NaNs). Hit: the entry distance if it is in
//   (tmin, tmax], else the exit distance (ray starting inside); hit.part is
//   the axis of that face.
// - surface: the hit point (stored from the re-centred frame, error ~eps*h)
//   is snapped onto the hit face and clamped into the face rectangle; the
//   normal and uv then follow the spec's argmax rule on that point (ties
//   x < y < z), so an edge hit gives the same answer in every backend.
//
// Record (doubles; box.cpp static_asserts its struct against these):
#define BOX_HALF 0

bool box_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  real3 h = prism_record3(rec, BOX_HALF);
  real3 d = ray.dir;
  precise real tf = prism_foot_parameter(ray.origin, d);
  precise real3 of = ray.origin + tf * d;
  // The parameter span [t_in, t_out] of the ray inside the box, relative to
  // `of`, with the axis that bounds each end.
  real t_in = -prism_inf();
  real t_out = prism_inf();
  uint in_axis = 0u;
  uint out_axis = 0u;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == R(0.0)) {
      if (!(abs(of[i]) <= h[i])) return false;
      continue;
    }
    precise real t0 = (-h[i] - of[i]) / d[i];
    precise real t1 = (h[i] - of[i]) / d[i];
    if (t0 > t1) {
      real swap = t0;
      t0 = t1;
      t1 = swap;
    }
    if (t0 > t_in) {
      t_in = t0;
      in_axis = uint(i);
    }
    if (t1 < t_out) {
      t_out = t1;
      out_axis = uint(i);
    }
  }
  if (!(t_in <= t_out)) return false;  // NaN rays too
  precise real t = tf + t_in;
  if (t > tmin && t <= tmax) {
    hit.t = t;
    hit.data = of + t_in * d;
    hit.part = in_axis;
    return true;
  }
  t = tf + t_out;
  if (t > tmin && t <= tmax) {
    hit.t = t;
    hit.data = of + t_out * d;
    hit.part = out_axis;
    return true;
  }
  return false;
}

void box_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  real3 h = prism_record3(rec, BOX_HALF);
  // Components are written by name, never at a computed index: NVIDIA's
  // OpenGL compiler cannot link a dynamically indexed write into a dvec3.
  real3 q = hit.data;
  real3 p = real3(hit.part == 0u ? prism_copysign(h.x, q.x) : clamp(q.x, -h.x, h.x),
                  hit.part == 1u ? prism_copysign(h.y, q.y) : clamp(q.y, -h.y, h.y),
                  hit.part == 2u ? prism_copysign(h.z, q.z) : clamp(q.z, -h.z, h.z));
  // The spec's face: argmax |p_i| / h_i, ties going to the lower axis.
  int a = 0;
  for (int i = 1; i < 3; ++i)
    if (abs(p[i]) / h[i] > abs(p[a]) / h[a]) a = i;
  real sign = prism_copysign(R(1.0), p[a]);
  real3 n = real3(a == 0 ? sign : R(0.0), a == 1 ? sign : R(0.0), a == 2 ? sign : R(0.0));
  // Spec uv: +-x (z, -y), +-y (x, z), +-z (x, -y), each mapped to [0, 1].
  real from_x = (p.x + h.x) / (R(2.0) * h.x);
  real from_z = (p.z + h.z) / (R(2.0) * h.z);
  real down_y = (h.y - p.y) / (R(2.0) * h.y);
  s.point = p;
  s.normal = n;
  s.uv = a == 0 ? real2(from_z, down_y) : (a == 1 ? real2(from_x, from_z) : real2(from_x, down_y));
}
