// Box, GPU intersector: the same method as box.cpp, in double. The slab
// method runs in a frame re-centred at the foot of the perpendicular from
// the box centre, so each slab distance (+-h - o_i)/d_i is formed from
// numbers of the box's size; double because a camera 1e6 away from a small
// box loses o - c itself in float32 (docs/numerics.md, Float and
// double; Box). An axis with d_i == 0 exactly is inside its slab or a miss (no
// 0 * inf NaNs); the hit is the entry distance if it lies in (tmin, tmax],
// else the exit distance. surface snaps the stored point onto the hit face,
// clamps it into the face and applies the spec's argmax rule (ties
// x < y < z), so edge hits agree with every backend.
//
// Record (std430 doubles; offsets static_asserted in box.cpp):
#define BOX_HALF 0

bool box_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  dvec3 h = prism_record3(rec, BOX_HALF), d = ray.dir;
  double tf = prism_foot_parameter(ray.origin, d);
  dvec3 of = ray.origin + tf * d;
  // The parameter span [t_in, t_out] of the ray inside the box, relative to
  // `of`, with the axis that bounds each end (box.cpp slab_span).
  double t_in = -prism_inf(), t_out = prism_inf();
  uint in_axis = 0u, out_axis = 0u;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0LF) {
      if (!(abs(of[i]) <= h[i])) return false;
      continue;
    }
    double t0 = (-h[i] - of[i]) / d[i], t1 = (h[i] - of[i]) / d[i];
    if (t0 > t1) {
      double swap = t0;
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
  double t = tf + t_in;
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

void box_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  dvec3 h = prism_record3(rec, BOX_HALF);
  dvec3 p = hit.data;
  for (int i = 0; i < 3; ++i)
    p[i] = uint(i) == hit.part ? prism_copysign(h[i], p[i]) : clamp(p[i], -h[i], h[i]);
  // The spec's face: argmax |p_i| / h_i, ties going to the lower axis.
  int a = 0;
  for (int i = 1; i < 3; ++i)
    if (abs(p[i]) / h[i] > abs(p[a]) / h[a]) a = i;
  dvec3 n = dvec3(0.0LF);
  n[a] = prism_copysign(1.0LF, p[a]);
  // Spec uv: +-x (z, -y), +-y (x, z), +-z (x, -y), each mapped to [0, 1].
  double from_x = (p.x + h.x) / (2.0LF * h.x), from_z = (p.z + h.z) / (2.0LF * h.z);
  double down_y = (h.y - p.y) / (2.0LF * h.y);
  s.point = p;
  s.normal = n;
  s.uv = a == 0 ? dvec2(from_z, down_y) : (a == 1 ? dvec2(from_x, from_z) : dvec2(from_x, down_y));
}
