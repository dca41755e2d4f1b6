// Prism GLSL module `quadric` (a plugin line `// prism:require quadric`
// splices it after library.glsl): the clipped general quadric
//   f(p) = A x^2 + B y^2 + C z^2 + D xy + E yz + F xz + G x + H y + I z + J = 0,
//   clip_min <= p <= clip_max,
// for every record that begins with a QuadricShape (quadric, cylinder,
// cone), and the axial-quadric uv of cylinder and cone. A line-for-line port
// of prism/sdk/quadric_math.hpp and prism/sdk/axial_quadric.hpp, so the three
// plugins share one GPU code path as they share one CPU code path, and the
// GPU makes the CPU's choices.
//
// Method (docs/numerics.md, Quadratics and Re-centring): origin moved to the foot of
// the perpendicular from the local origin before b and c are formed (Wald,
// Ray Tracing Gems II ch. 34), and again to the vertex of f along the ray
// when the roots are close together (4ac >= b^2 / 2), roots by the stable pair c/q, q/a with the
// fma discriminant (prism_solve_quadratic), `a == 0` exactly is linear and
// nothing else, non-finite roots rejected, clip test on the point formed in
// the re-centred frame, one Newton step onto f = 0 in surface. Double
// precision: a camera 1e6 away from a small quadric loses o - c itself in
// float32, which no formula recovers (docs/numerics.md, Float and double); only the
// uv azimuth is float (prism_turn_fraction).
//
// QuadricShape at the record start (std430 doubles): coef[12] (A..J, two
// unused), lo[4], hi[4] (clip box; IEEE -inf / +inf where unbounded, which
// the plain comparisons below handle). The AxialQuadricRecord of cylinder
// and cone continues with radius, height. Offsets are static_asserted
// against the C++ structs in plugins/cylinder and plugins/cone.
#define PRISM_QUADRIC_COEF 0
#define PRISM_QUADRIC_LO 12
#define PRISM_QUADRIC_HI 16
#define PRISM_AXIAL_QUADRIC_HEIGHT 21

// A record's QuadricShape: coefficients A..J and the clip box.
struct PrismQuadric {
  double c[10];
  dvec3 lo;
  dvec3 hi;
};

PrismQuadric prism_quadric_load(uint rec) {
  PrismQuadric q;
  for (uint i = 0u; i < 10u; ++i) q.c[i] = prism_record(rec, PRISM_QUADRIC_COEF + i);
  q.lo = prism_record3(rec, PRISM_QUADRIC_LO);
  q.hi = prism_record3(rec, PRISM_QUADRIC_HI);
  return q;
}

double prism_quadric_value(PrismQuadric q, dvec3 p) {
  return p.x * (q.c[0] * p.x + q.c[3] * p.y + q.c[5] * p.z + q.c[6]) + p.y * (q.c[1] * p.y + q.c[4] * p.z + q.c[7]) +
         p.z * (q.c[2] * p.z + q.c[8]) + q.c[9];
}

dvec3 prism_quadric_gradient(PrismQuadric q, dvec3 p) {
  return dvec3(2.0LF * q.c[0] * p.x + q.c[3] * p.y + q.c[5] * p.z + q.c[6],
               2.0LF * q.c[1] * p.y + q.c[3] * p.x + q.c[4] * p.z + q.c[7],
               2.0LF * q.c[2] * p.z + q.c[4] * p.y + q.c[5] * p.x + q.c[8]);
}

// d^T M d: the coefficient of t^2 along direction d.
double prism_quadric_quadratic_term(PrismQuadric q, dvec3 d) {
  return d.x * (q.c[0] * d.x + q.c[3] * d.y + q.c[5] * d.z) + d.y * (q.c[1] * d.y + q.c[4] * d.z) +
         d.z * q.c[2] * d.z;
}

bool prism_quadric_in_clip(PrismQuadric q, dvec3 p) {
  return p.x >= q.lo.x && p.x <= q.hi.x && p.y >= q.lo.y && p.y <= q.hi.y && p.z >= q.lo.z && p.z <= q.hi.z;
}

// Smallest root tmin < t <= tmax whose point lies in the clip box (the far
// root when the near one is clipped away); hit.data is the local point,
// formed in the re-centred frame. Any plugin whose record begins with a
// QuadricShape calls this as its <prefix>_intersect.
bool prism_quadric_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  PrismQuadric q = prism_quadric_load(rec);
  dvec3 d = ray.dir;
  double tf = prism_foot_parameter(ray.origin, d);
  dvec3 of = ray.origin + tf * d;
  double a = prism_quadric_quadratic_term(q, d);
  double b = dot(prism_quadric_gradient(q, of), d);
  double c = prism_quadric_value(q, of);
  // Roots near the vertex of f along the ray (4ac >= b^2 / 2): b^2 and 4ac
  // nearly cancel, so re-centre at the vertex, where b is ~0 and c is formed
  // directly (quadric_math.hpp says why).
  if (a != 0.0LF && 4.0LF * a * c >= 0.5LF * b * b) {
    double tv = -b / (2.0LF * a);
    if (prism_is_finite(tv)) {
      of += tv * d;
      tf += tv;
      b = dot(prism_quadric_gradient(q, of), d);
      c = prism_quadric_value(q, of);
    }
  }
  double s[2];
  int n = prism_solve_quadratic(a, b, c, s[0], s[1]);
  for (int i = 0; i < n; ++i) {
    double ti = tf + s[i];
    if (!(ti > tmin && ti <= tmax) || !prism_is_finite(ti)) continue;
    dvec3 pi = of + s[i] * d;
    if (!prism_quadric_in_clip(q, pi)) continue;
    hit.t = ti;
    hit.data = pi;
    return true;
  }
  return false;
}

// Point and normal of a hit from prism_quadric_intersect: one Newton step
// along the gradient pulls the point onto f = 0 (it is within rounding of
// the surface, so one step squares that error); the normal is the gradient
// there scaled so its largest component is 1, all zeros where it vanishes
// (a cone's apex: the core then uses -dir).
void prism_quadric_point_normal(uint rec, PrismHit hit, out dvec3 point, out dvec3 normal) {
  PrismQuadric q = prism_quadric_load(rec);
  dvec3 p = hit.data;
  dvec3 g = prism_quadric_gradient(q, p);
  double m = prism_max_abs_component(g);
  if (m > 0.0LF && prism_is_finite(m)) {
    dvec3 gs = g / m;
    dvec3 step = (prism_quadric_value(q, p) / m / dot(gs, gs)) * gs;
    if (prism_is_finite(step.x) && prism_is_finite(step.y) && prism_is_finite(step.z)) p -= step;
    g = prism_quadric_gradient(q, p);
    m = prism_max_abs_component(g);
  }
  point = p;
  normal = (m > 0.0LF && prism_is_finite(m)) ? g / m : dvec3(0.0LF);
}

// The surface of cylinder and cone (AxialQuadricRecord): the quadric's point
// and normal, u = 0.5 + atan2(z, x)/2pi, v = y/height.
void prism_axial_quadric_surface(uint rec, PrismHit hit, out PrismSurface s) {
  prism_quadric_point_normal(rec, hit, s.point, s.normal);
  double height = prism_record(rec, PRISM_AXIAL_QUADRIC_HEIGHT);
  s.uv = dvec2(prism_turn_fraction(s.point.z, s.point.x), s.point.y / height);
}
