// Prism module `quadric`, in the shared dialect (prism/sdk/dialect.hpp):
// the clipped general quadric
//   f(p) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz + G x + H y + I z + J = 0,
//   clip_min <= p <= clip_max,
// for every record that begins with a QuadricShape (quadric, cylinder,
// cone), and the axial-quadric uv of cylinder and cone. Written once: C++
// instantiates it through prism/sdk/quadric_math.hpp, and a plugin line
// `// prism:require quadric` splices it into the GPU kernel after the
// library. So the three plugins share one code path on both sides, and the
// re-centring below exists once.
//
// Method (docs/numerics.md, Quadratics and Re-centring): origin moved to the
// foot of the perpendicular from the local origin before b and c are formed
// (Wald, Ray Tracing Gems II ch. 34), and again to the vertex of f along the
// ray when the roots are close together (4ac >= b^2 / 2); roots by the
// stable pair c/q, q/a with the fma discriminant (prism_solve_quadratic);
// `a == 0` exactly is linear and nothing else; non-finite roots rejected;
// clip test on the point formed in the re-centred frame; one Newton step
// onto f = 0 in surface. Double in the renderer: a camera 1e6 away from a
// small quadric loses o - c itself in float32 (docs/numerics.md, Float and
// double); only the uv azimuth is float on the GPU (prism_turn_fraction).
//
// QuadricShape at the record start (doubles): coef[12] (A..J, two unused),
// lo[4], hi[4] (clip box; IEEE -inf / +inf where unbounded, which the plain
// comparisons below handle). The AxialQuadricRecord of cylinder and cone
// continues with radius, height. prism/sdk/quadric_math.hpp and
// axial_quadric.hpp static_assert their structs against these offsets.
#define PRISM_QUADRIC_COEF 0
#define PRISM_QUADRIC_LO 12
#define PRISM_QUADRIC_HI 16
#define PRISM_AXIAL_QUADRIC_HEIGHT 21

// A record's QuadricShape: coefficients A..J and the clip box.
struct PrismQuadric {
  real c[10];
  real3 lo;
  real3 hi;
};

PrismQuadric prism_quadric_load(PrismRecord rec) {
  PrismQuadric q;
  for (uint i = 0u; i < 10u; ++i) q.c[i] = prism_record(rec, PRISM_QUADRIC_COEF + i);
  q.lo = prism_record3(rec, PRISM_QUADRIC_LO);
  q.hi = prism_record3(rec, PRISM_QUADRIC_HI);
  return q;
}

real prism_quadric_value(PrismQuadric q, real3 p) {
  return p.x * (q.c[0] * p.x + q.c[3] * p.y + q.c[5] * p.z + q.c[6]) + p.y * (q.c[1] * p.y + q.c[4] * p.z + q.c[7]) +
         p.z * (q.c[2] * p.z + q.c[8]) + q.c[9];
}

real3 prism_quadric_gradient(PrismQuadric q, real3 p) {
  return real3(R(2.0) * q.c[0] * p.x + q.c[3] * p.y + q.c[5] * p.z + q.c[6],
               R(2.0) * q.c[1] * p.y + q.c[3] * p.x + q.c[4] * p.z + q.c[7],
               R(2.0) * q.c[2] * p.z + q.c[4] * p.y + q.c[5] * p.x + q.c[8]);
}

// d^T M d: the coefficient of t^2 along direction d.
real prism_quadric_quadratic_term(PrismQuadric q, real3 d) {
  return d.x * (q.c[0] * d.x + q.c[3] * d.y + q.c[5] * d.z) + d.y * (q.c[1] * d.y + q.c[4] * d.z) +
         d.z * q.c[2] * d.z;
}

bool prism_quadric_in_clip(PrismQuadric q, real3 p) {
  return p.x >= q.lo.x && p.x <= q.hi.x && p.y >= q.lo.y && p.y <= q.hi.y && p.z >= q.lo.z && p.z <= q.hi.z;
}

// Smallest root t with tmin < t <= tmax whose point lies in the clip box
// (the far root when the near one is clipped away); fills t and the local
// hit point p, formed in the re-centred frame (its error ~eps * |object|
// rather than eps * |origin|). Leaves t and p alone on a miss.
bool prism_quadric_hit(PrismQuadric q, real3 o, real3 d, real tmin, real tmax, INOUT(real) t, INOUT(real3) p) {
  precise real tf = prism_foot_parameter(o, d);
  precise real3 of = o + tf * d;
  precise real a = prism_quadric_quadratic_term(q, d);
  precise real b = dot(prism_quadric_gradient(q, of), d);
  precise real c = prism_quadric_value(q, of);
  // When both roots lie near the vertex of f along the ray (4ac >= b^2 / 2:
  // they are within 0.71 of its distance from it, or there are none), b^2
  // and 4ac nearly cancel and the discriminant drowns in their rounding: a
  // spheroid x^2 + 1e12 y^2 + z^2 = 1 lost hits that way. Re-centred at the
  // vertex, b is ~0 and c is f's extreme value, formed directly.
  if (a != R(0.0) && R(4.0) * a * c >= R(0.5) * b * b) {
    precise real tv = -b / (R(2.0) * a);
    if (prism_is_finite(tv)) {
      of += tv * d;
      tf += tv;
      b = dot(prism_quadric_gradient(q, of), d);
      c = prism_quadric_value(q, of);
    }
  }
  real s[2];
  int n = prism_solve_quadratic(a, b, c, s[0], s[1]);
  for (int i = 0; i < n; ++i) {
    precise real ti = tf + s[i];
    if (!(ti > tmin && ti <= tmax) || !prism_is_finite(ti)) continue;
    precise real3 pi = of + s[i] * d;
    if (!prism_quadric_in_clip(q, pi)) continue;
    t = ti;
    p = pi;
    return true;
  }
  return false;
}

// The intersect of any plugin whose record begins with a QuadricShape;
// hit.data is the local point.
bool prism_quadric_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  return prism_quadric_hit(prism_quadric_load(rec), ray.origin, ray.dir, tmin, tmax, hit.t, hit.data);
}

// Re-projects a hit point onto f = 0 with one Newton step along the gradient
// (the hit is already within rounding of the surface, so one step squares
// that error) and returns the gradient there as the outward normal, scaled
// so its largest component is 1 (tiny coefficients must not underflow it).
// Where the gradient vanishes (a cone's apex) the normal is all zeros and
// the core falls back to -dir, as the spec says.
void prism_quadric_project(PrismQuadric q, real3 p, OUT(real3) point, OUT(real3) normal) {
  real3 g = prism_quadric_gradient(q, p);
  real m = prism_max_abs_component(g);
  if (m > R(0.0) && prism_is_finite(m)) {
    real3 gs = g / m;
    precise real3 step = (prism_quadric_value(q, p) / m / dot(gs, gs)) * gs;
    if (prism_is_finite(step.x) && prism_is_finite(step.y) && prism_is_finite(step.z)) p -= step;
    g = prism_quadric_gradient(q, p);
    m = prism_max_abs_component(g);
  }
  point = p;
  normal = (m > R(0.0) && prism_is_finite(m)) ? g / m : real3(R(0.0));
}

// Point and normal of a hit from prism_quadric_intersect.
void prism_quadric_point_normal(PrismRecord rec, PrismHit hit, OUT(real3) point, OUT(real3) normal) {
  prism_quadric_project(prism_quadric_load(rec), hit.data, point, normal);
}

// The surface of cylinder and cone (AxialQuadricRecord): the quadric's point
// and normal, u = 0.5 + atan2(z, x)/2pi, v = y/height.
void prism_axial_quadric_surface(PrismRecord rec, PrismHit hit, OUT(PrismSurface) s) {
  prism_quadric_point_normal(rec, hit, s.point, s.normal);
  real height = prism_record(rec, PRISM_AXIAL_QUADRIC_HEIGHT);
  s.uv = real2(prism_turn_fraction(s.point.z, s.point.x), s.point.y / height);
}
