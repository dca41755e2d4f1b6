// Torus, GPU intersector: the same method as torus.cpp, step for step, in
// double precision. Float32 is not enough here even re-centred: thin tubes
// (r/R = 1e-3) miss 15-20 % of true hits in float32, double stays <= 0.15 %,
// and near-axial rays give false hits inside the hole in float
// (docs/numerics.md, Torus); a far camera also loses o - c itself.
// 1. Clip the ray to the bounding sphere of radius (R + r)(1 + 1e-3) with
//    the robust discriminant and move the origin to the chord's midpoint
//    (the foot of the perpendicular); scale by 1/R.
// 2. Isolate roots of the monic quartic f(s) on the chord [-H, H] by the
//    derivative sequence: the roots of the quadratic f'' split the cubic f'
//    into monotone pieces, each sign change of f' is a critical point
//    (Newton-bisection), and the critical points split f into monotone
//    pieces with at most one root each.
// 3. Signs and roots come from the signed distance to the tube
//    g(s) = sqrt((sqrt(x^2 + z^2) - 1)^2 + y^2) - r/R (same sign as f, no
//    cancellation, |g'| <= 1), each bracketed sign change solved by
//    Newton-bisection on g (module `roots`, bounded step count).
// 4. Pieces in order, the first root with tmin < t <= tmax wins (tested on
//    t); a grazing touch (g == 0 at a critical point) is a hit.
// 5. surface: re-projection onto the tube; the radial direction is the
//    normal. Only the uv angles are float (prism_turn_fraction).
//
// prism:require roots
//
// Record (std430 doubles; offsets static_asserted in torus.cpp):
#define TORUS_MAJOR 0
#define TORUS_MINOR 1

// Newton tolerances in units of R (torus.cpp kCriticalTol, kRootTol).
const double TORUS_CRITICAL_TOL = 1e-9LF;
const double TORUS_ROOT_TOL = 1e-12LF;

// The scaled ray p(s) = u + s d against the torus R = 1, tube radius `tube`,
// and the scan over its monotone pieces (torus.cpp RootScan).
struct TorusScan {
  dvec3 u;
  dvec3 d;
  double tube;
  double tf;
  double big;
  double tmin;
  double tmax;
  double a;   // the previous break
  double ga;  // g there
  bool done;
  bool found;
  double root;
};

// Signed distance to the tube and its derivative along the scaled ray; on
// the axis d(radial)/ds is 0/0 and the NaN sends the solver to bisection.
void torus_distance(TorusScan sc, double s, out double g, out double dg) {
  dvec3 p = sc.u + s * sc.d;
  double radial = sqrt(p.x * p.x + p.z * p.z);
  double q = radial - 1.0LF;
  double dist = sqrt(q * q + p.y * p.y);
  g = dist - sc.tube;
  double dradial = (p.x * sc.d.x + p.z * sc.d.z) / radial;
  dg = (q * dradial + p.y * sc.d.y) / dist;
}

double torus_distance_at(TorusScan sc, double s) {
  double g, dg;
  torus_distance(sc, s, g, dg);
  return g;
}

// Closes the piece [sc.a, b]: at most one root, solved only where g changes
// sign and the piece reaches past tmin.
void torus_advance(inout TorusScan sc, double b) {
  if (sc.done) return;
  double a0 = sc.a, g0 = sc.ga, gb = torus_distance_at(sc, b);
  sc.a = b;
  sc.ga = gb;
  if (sc.tf + sc.big * a0 > sc.tmax) {
    sc.done = true;
    return;
  }
  if ((g0 > 0.0LF) == (gb > 0.0LF) || sc.tf + sc.big * b <= sc.tmin) return;
  PrismBracket br = prism_bracket_start(a0, b, g0, gb, TORUS_ROOT_TOL * (1.0LF + abs(b)));
  for (int i = 0; i < PRISM_BRACKET_MAX_STEPS; ++i) {
    double g, dg;
    torus_distance(sc, br.s, g, dg);
    if (prism_bracket_step(br, g, dg)) break;
  }
  double t = sc.tf + sc.big * br.s;
  if (t > sc.tmax) {
    sc.done = true;
  } else if (t > sc.tmin) {
    sc.done = true;
    sc.found = true;
    sc.root = br.s;
  }
}

// f'(s) and f''(s) of the monic quartic s^4 + c.w s^3 + c.z s^2 + c.y s + c.x.
double torus_d1(dvec4 c, double s) { return ((4.0LF * s + 3.0LF * c.w) * s + 2.0LF * c.z) * s + c.y; }
double torus_d2(dvec4 c, double s) { return (12.0LF * s + 6.0LF * c.w) * s + 2.0LF * c.z; }

// The quartic along the scaled ray (torus.cpp torus_quartic):
// (s^2 + 2es + k)^2 - 4 (dxz s^2 + 2 exz s + gxz), d unit.
dvec4 torus_quartic(TorusScan sc) {
  dvec3 u = sc.u, d = sc.d;
  double e = dot(u, d);
  double k = dot(u, u) + 1.0LF - sc.tube * sc.tube;
  double dxz = d.x * d.x + d.z * d.z, exz = u.x * d.x + u.z * d.z, gxz = u.x * u.x + u.z * u.z;
  return dvec4(k * k - 4.0LF * gxz, 4.0LF * e * k - 8.0LF * exz, 4.0LF * e * e + 2.0LF * k - 4.0LF * dxz, 4.0LF * e);
}

// Feeds the scan the critical points of f in [-h, h] in order, then h.
void torus_scan_pieces(inout TorusScan sc, double h) {
  dvec4 c = torus_quartic(sc);
  double r[2];
  int n = prism_solve_quadratic(12.0LF, 6.0LF * c.w, 2.0LF * c.z, r[0], r[1]);
  double ends[4] = double[4](-h, 0.0LF, 0.0LF, 0.0LF);
  int count = 1;
  for (int i = 0; i < n; ++i)
    if (r[i] > -h && r[i] < h) ends[count++] = r[i];
  ends[count++] = h;
  sc.a = -h;
  sc.ga = torus_distance_at(sc, -h);
  for (int i = 0; i + 1 < count && !sc.done; ++i) {
    double a = ends[i], b = ends[i + 1], fa = torus_d1(c, a), fb = torus_d1(c, b);
    if ((fa > 0.0LF) == (fb > 0.0LF)) continue;
    PrismBracket br = prism_bracket_start(a, b, fa, fb, TORUS_CRITICAL_TOL * (1.0LF + abs(a)));
    for (int k = 0; k < PRISM_BRACKET_MAX_STEPS; ++k)
      if (prism_bracket_step(br, torus_d1(c, br.s), torus_d2(c, br.s))) break;
    torus_advance(sc, br.s);
  }
  torus_advance(sc, h);
}

bool torus_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit) {
  hit.t = 0.0LF;
  hit.data = dvec3(0.0LF);
  hit.part = 0u;
  double big = prism_record(rec, TORUS_MAJOR), minor = prism_record(rec, TORUS_MINOR);
  dvec3 d = ray.dir;
  double tf = prism_foot_parameter(ray.origin, d);
  dvec3 foot = ray.origin + tf * d;
  dvec3 perp = foot - dot(foot, d) * d;
  double bound = (big + minor) * (1.0LF + 1e-3LF);  // slack: the outer equator touches R + r
  double half2 = bound * bound - dot(perp, perp);
  if (!(half2 >= 0.0LF)) return false;
  double h = sqrt(half2) / big;
  if (tf + big * h <= tmin || tf - big * h > tmax) return false;

  TorusScan sc;
  sc.u = foot / big;
  sc.d = d;
  sc.tube = minor / big;
  sc.tf = tf;
  sc.big = big;
  sc.tmin = tmin;
  sc.tmax = tmax;
  sc.a = 0.0LF;
  sc.ga = 0.0LF;
  sc.done = false;
  sc.found = false;
  sc.root = 0.0LF;
  torus_scan_pieces(sc, h);
  if (!sc.found) return false;
  hit.t = tf + big * sc.root;
  hit.data = foot + (big * sc.root) * d;
  return true;
}

// The stored point re-projected onto the tube: nearest point of the core
// circle plus r along the radial direction, which is the normal.
void torus_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {
  double major = prism_record(rec, TORUS_MAJOR), minor = prism_record(rec, TORUS_MINOR);
  dvec3 p = hit.data;
  double radial = sqrt(p.x * p.x + p.z * p.z);
  dvec3 normal = dvec3(0.0LF);
  if (radial > 0.0LF) {
    dvec3 core = dvec3(major * p.x / radial, 0.0LF, major * p.z / radial);
    dvec3 out_dir = p - core;
    double len = length(out_dir);
    if (len > 0.0LF) {
      normal = out_dir / len;
      p = core + minor * normal;
    }
  }
  s.point = p;
  s.normal = normal;
  s.uv = dvec2(prism_turn_fraction(p.z, p.x), prism_turn_fraction(p.y, sqrt(p.x * p.x + p.z * p.z) - major));
}
