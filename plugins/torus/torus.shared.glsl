// Torus primitive, written once for the CPU and the GPU (the shared
// dialect: prism/sdk/dialect.hpp): (|p|^2 + R^2 - r^2)^2 = 4 R^2 (p.x^2 +
// p.z^2), axis local y, 0 < r < R. The Newton-bisection steps are the shared
// module `roots`, the critical points' quadratic the library's.
//
// Numerics (why not a closed-form quartic: see docs/numerics.md, Torus;
// closed forms lose everything for far origins, thin tubes and grazing rays)
// 1. Bounding sphere: the ray is clipped to the sphere of radius
//    (R + r)(1 + 1e-3) with the robust discriminant, and the origin is moved
//    to the chord's midpoint (the foot of the perpendicular), in double. A
//    camera 1e4 or 1e6 away then loses nothing, and the quartic is built from
//    numbers of the torus's size.
// 2. Scale by 1/R: in s = (t - t_f)/R the quartic f(s) is monic with O(1)
//    coefficients. Its roots are isolated on the chord [-H, H] by the
//    derivative sequence: roots of the quadratic f'' split the cubic f' into
//    monotone pieces, each sign change of f' is solved by safeguarded
//    Newton-bisection, and those critical points split f into monotone
//    pieces, each holding at most one root. Critical points are well
//    conditioned (f'' = O(1) there) even where f itself is not.
// 3. Signs and roots come from the signed distance to the tube,
//    g(s) = sqrt((sqrt(x^2 + z^2) - 1)^2 + y^2) - r/R, not from the expanded
//    quartic: g
//    has the same sign as f everywhere (f = A*B with A = dist^2 - (r/R)^2 and
//    B > 0 for r < R), but no cancellation: for r/R = 1e-3 the quartic loses
//    ~6 digits near the tube while g keeps full precision, and |g'| <= 1.
//    Each bracketed sign change of g is solved by safeguarded
//    Newton-bisection on g itself, which doubles as the final polish.
// 4. Pieces are visited in order and only as far as needed: the first root
//    with tmin < t <= tmax wins, tested on t itself (not on a rounded s).
//    A grazing touch (g == 0 at a critical point) counts as a hit. The
//    occlusion test (torus_occluded) stops at the first piece whose sign
//    change lies, ends and all, inside (tmin, tmax): the root the solver
//    would find there stays in the piece, and t = t_f + R s rounds
//    monotonically in s, so its t lies inside too.
// 5. surface: the stored point is re-projected onto the tube (nearest point
//    of the core circle plus r along the radial direction) and the normal is
//    that radial direction, which is parallel to the spec's gradient.
// 6. Most scans find nothing (shadow rays past the tube, windows that end
//    before it): before the scan, the part of the chord inside the window
//    is shown clear of the tube when f's Bernstein coefficients there stay
//    above a margin far beyond rounding (torus_clear_in_window). It settles
//    99.6 % of the showcase's empty scans with multiplications and
//    additions only, where the scan spends square roots and divisions.
//
// prism:require roots
//
// Record (doubles; torus.cpp static_asserts its struct against these):
#define TORUS_MAJOR 0
#define TORUS_MINOR 1

// Newton stops once a step is below these (in units of R); the step just
// taken leaves an error ~K * step^2, far below double resolution. A critical
// point off by 1e-9 changes f's extremum by ~1e-18, so it still separates
// any root pair that double precision can tell apart. In float neither can
// be reached (g and f' are known to a few ulps), so there the tolerance is
// 8 ulps at 1: without that floor the float steps wander at ulp level until
// the bracket closes, several times the double step count (on the GPU, each
// step costs every lane of the group). In double the floor never binds.
const real TORUS_FLOOR_TOL = R(8.0) * PRISM_REAL_EPSILON;
const real TORUS_CRITICAL_TOL = max(R(1.0) / R(1000000000.0), TORUS_FLOOR_TOL);  // 1e-9, a quotient of float-exact literals
const real TORUS_ROOT_TOL = max(R(1.0) / (R(1000000.0) * R(1000000.0)), TORUS_FLOOR_TOL);  // 1e-12, likewise

// The scaled ray p(s) = u + s d against the torus R = 1, tube radius `tube`,
// and the scan over its monotone pieces.
struct TorusScan {
  real3 u;
  real3 d;
  real tube;
  real tf;
  real big;
  real tmin;
  real tmax;
  real a;   // the previous break
  real ga;  // g there
  bool done;
  bool found;
  real root;
  bool any;     // an occlusion test: a root known to lie in (tmin, tmax) is enough
  bool inside;  // found so, its root left unsolved
};

// Signed distance to the tube and its derivative along the scaled ray; on
// the axis d(radial)/ds is 0/0 and the NaN sends the solver to bisection.
void torus_distance(TorusScan sc, real s, OUT(real) g, OUT(real) dg) {
  real3 p = sc.u + s * sc.d;
  real radial = sqrt(p.x * p.x + p.z * p.z);
  real q = radial - R(1.0);
  real dist = sqrt(q * q + p.y * p.y);
  g = dist - sc.tube;
  real dradial = (p.x * sc.d.x + p.z * sc.d.z) / radial;
  dg = (q * dradial + p.y * sc.d.y) / dist;
}

real torus_distance_at(TorusScan sc, real s) {
  real g, dg;
  torus_distance(sc, s, g, dg);
  return g;
}

// Closes the piece [sc.a, b]: at most one root, solved only where g changes
// sign and the piece reaches past tmin.
void torus_advance(INOUT(TorusScan) sc, real b) {
  if (sc.done) return;
  real a0 = sc.a, g0 = sc.ga, gb = torus_distance_at(sc, b);
  sc.a = b;
  sc.ga = gb;
  if (sc.tf + sc.big * a0 > sc.tmax) {
    sc.done = true;
    return;
  }
  if ((g0 > R(0.0)) == (gb > R(0.0)) || sc.tf + sc.big * b <= sc.tmin) return;
  if (sc.any && sc.tf + sc.big * a0 > sc.tmin && sc.tf + sc.big * b < sc.tmax) {
    sc.done = true;
    sc.found = true;
    sc.inside = true;
    return;
  }
  PrismBracket br = prism_bracket_start(a0, b, g0, gb, TORUS_ROOT_TOL * (R(1.0) + abs(b)));
  for (int i = 0; i < PRISM_BRACKET_MAX_STEPS; ++i) {
    real g, dg;
    torus_distance(sc, br.s, g, dg);
    if (prism_bracket_step(br, g, dg)) break;
  }
  real t = sc.tf + sc.big * br.s;
  if (t > sc.tmax) {
    sc.done = true;
  } else if (t > sc.tmin) {
    sc.done = true;
    sc.found = true;
    sc.root = br.s;
  }
}

// f'(s) and f''(s) of the monic quartic s^4 + c.w s^3 + c.z s^2 + c.y s + c.x.
real torus_d1(real4 c, real s) { return ((R(4.0) * s + R(3.0) * c.w) * s + R(2.0) * c.z) * s + c.y; }
real torus_d2(real4 c, real s) { return (R(12.0) * s + R(6.0) * c.w) * s + R(2.0) * c.z; }

// The quartic along the scaled ray:
// (s^2 + 2es + k)^2 - 4 (dxz s^2 + 2 exz s + gxz), d unit.
real4 torus_quartic(TorusScan sc) {
  real3 u = sc.u, d = sc.d;
  real e = dot(u, d);
  real k = dot(u, u) + R(1.0) - sc.tube * sc.tube;
  real dxz = d.x * d.x + d.z * d.z, exz = u.x * d.x + u.z * d.z, gxz = u.x * u.x + u.z * u.z;
  return real4(k * k - R(4.0) * gxz, R(4.0) * e * k - R(8.0) * exz, R(4.0) * e * e + R(2.0) * k - R(4.0) * dxz, R(4.0) * e);
}

// Whether f stays above rounding's reach on the part of the chord where a
// root would count, shown by Bernstein coefficients: a polynomial lies in
// the hull of its control points, so all five above the margin on an
// interval put f above it there. The interval is tried whole, then halved
// (de Casteljau) down to eighths where its hull dips but f's own values at
// its ends do not.
// Why nothing the scan would find is lost:
// - f = A B with A = dist^2 - tube^2 and 0 < B <= 9 on the chord (|p| <= 2),
//   so f >= m there gives g = dist - tube >= m / 36.
// - The margin, 1e7 ulps of 1 + the coefficients' size (2.2e-9 at least in
//   double), is far above the rounding of c, of these sums and of g itself
//   (a few ulps of |p| + 1): no g the scan computes in the interval reaches 0.
// - The interval is (tmin, tmax] in s widened by 1e-9 (1 + h), a thousand
//   times the solver's tolerance, and by 64 ulps of the t's over big, so a
//   root just outside cannot round in, nor a piece's ends.
// In float the margin would exceed every coefficient: it is not tried.
bool torus_clear_in_window(TorusScan sc, real4 c, real h) {
  if (PRISM_REAL_EPSILON > R(1.0) / R(10000000000.0)) return false;  // float: the margin is out of reach (a constant: folded away)
  real widen = R(1.0) / R(1000000000.0) * (R(1.0) + h) +
               R(64.0) * PRISM_REAL_EPSILON * (abs(sc.tf) + abs(sc.tmin) + min(abs(sc.tmax), abs(sc.tf) + sc.big * h)) / sc.big;
  real lo = max(-h, (sc.tmin - sc.tf) / sc.big - widen);
  real hi = min(h, (sc.tmax - sc.tf) / sc.big + widen);
  if (!(lo < hi)) return false;
  // The Taylor coefficients of f at lo, times w^i (P(x) = f(lo + w x)), then
  // the Bernstein coefficients of P on [0, 1].
  real w = hi - lo;
  real a0 = (((lo + c.w) * lo + c.z) * lo + c.y) * lo + c.x;
  real a1 = w * torus_d1(c, lo);
  real a2 = w * w * ((R(6.0) * lo + R(3.0) * c.w) * lo + c.z);
  real a3 = w * w * w * (R(4.0) * lo + c.w);
  real a4 = w * w * w * w;
  real margin = R(10000000.0) * PRISM_REAL_EPSILON * (R(1.0) + abs(a0) + abs(a1) + abs(a2) + abs(a3) + a4);
  real b[5];
  b[0] = a0;
  b[1] = a0 + R(0.25) * a1;
  b[2] = a0 + R(0.5) * a1 + a2 / R(6.0);
  b[3] = a0 + R(0.75) * a1 + R(0.5) * a2 + R(0.25) * a3;
  b[4] = a0 + a1 + a2 + a3 + a4;
  // Depth first, left half first; the right halves wait in `later` (one per level).
  real later[15];
  int waiting = 0, depth = 0;
  int depths[3];
  for (int step = 0; step < 15; ++step) {
    if (!(b[0] > margin) || !(b[4] > margin)) return false;  // f itself is small there: leave it to the scan
    bool above = b[1] > margin && b[2] > margin && b[3] > margin;
    if (above) {
      if (waiting == 0) return true;
      --waiting;
      for (int k = 0; k < 5; ++k) b[k] = later[5 * waiting + k];
      depth = depths[waiting];
      continue;
    }
    if (depth == 3) return false;
    real c0 = R(0.5) * (b[0] + b[1]), c1 = R(0.5) * (b[1] + b[2]), c2 = R(0.5) * (b[2] + b[3]), c3 = R(0.5) * (b[3] + b[4]);
    real d0 = R(0.5) * (c0 + c1), d1 = R(0.5) * (c1 + c2), d2 = R(0.5) * (c2 + c3);
    real e0 = R(0.5) * (d0 + d1), e1 = R(0.5) * (d1 + d2);
    real mid = R(0.5) * (e0 + e1);
    later[5 * waiting] = mid;
    later[5 * waiting + 1] = e1;
    later[5 * waiting + 2] = d2;
    later[5 * waiting + 3] = c3;
    later[5 * waiting + 4] = b[4];
    ++depth;
    depths[waiting] = depth;
    ++waiting;
    b[1] = c0;
    b[2] = d0;
    b[3] = e0;
    b[4] = mid;
  }
  return false;
}

// Feeds the scan the critical points of f in [-h, h] in order, then h.
// The breaks of f' are -h, the roots of f'' inside (-h, h) and h; step i < 3
// closes the piece of f' that ends at break i + 1 (r0, r1, h) and advances to
// its critical point, if f' changes sign there; step 3 advances to h. One
// loop with one advance: a GPU compiler inlines every call, and a CPU
// driver runs each copy for all lanes of a group, even when none needs it.
void torus_scan_pieces(INOUT(TorusScan) sc, real h) {
  real4 c = torus_quartic(sc);
  if (torus_clear_in_window(sc, c, h)) {  // no sign change of g for the scan to find
    sc.done = true;
    return;
  }
  real r0, r1;
  int n = prism_solve_quadratic(R(12.0), R(6.0) * c.w, R(2.0) * c.z, r0, r1);
  sc.a = -h;
  sc.ga = torus_distance_at(sc, -h);
  real a = -h;  // the last break of f' passed
  for (int i = 0; i < 4 && !sc.done; ++i) {
    real b = i == 0 ? r0 : (i == 1 ? r1 : h);
    bool piece = i == 2 || (i < n && b > -h && b < h);
    real stop = h;
    bool advance = i == 3;
    if (piece) {
      real fa = torus_d1(c, a), fb = torus_d1(c, b);
      if ((fa > R(0.0)) != (fb > R(0.0))) {
        PrismBracket br = prism_bracket_start(a, b, fa, fb, TORUS_CRITICAL_TOL * (R(1.0) + abs(a)));
        for (int k = 0; k < PRISM_BRACKET_MAX_STEPS; ++k)
          if (prism_bracket_step(br, torus_d1(c, br.s), torus_d2(c, br.s))) break;
        stop = br.s;
        advance = true;
      }
      a = b;
    }
    if (advance) torus_advance(sc, stop);
  }
}

// Scans the ray's monotone pieces (see the top) for the first root with
// tmin < t <= tmax; `any`: for an occlusion test. False where the ray misses
// the bounding sphere's part inside the bounds.
bool torus_scan(PrismRecord rec, PrismRay ray, real tmin, real tmax, bool any, OUT(TorusScan) sc, OUT(real3) foot) {
  real big = prism_record(rec, TORUS_MAJOR), minor = prism_record(rec, TORUS_MINOR);
  real3 d = ray.dir;
  real tf = prism_foot_parameter(ray.origin, d);
  foot = ray.origin + tf * d;
  real3 perp = foot - dot(foot, d) * d;
  real bound = (big + minor) * (R(1.0) + R(1.0) / R(1000.0));  // slack: the outer equator touches R + r
  real half2 = bound * bound - dot(perp, perp);
  sc.found = false;
  if (!(half2 >= R(0.0))) return false;
  real h = sqrt(half2) / big;
  if (tf + big * h <= tmin || tf - big * h > tmax) return false;
  sc.u = foot / big;
  sc.d = d;
  sc.tube = minor / big;
  sc.tf = tf;
  sc.big = big;
  sc.tmin = tmin;
  sc.tmax = tmax;
  sc.a = R(0.0);
  sc.ga = R(0.0);
  sc.done = false;
  sc.root = R(0.0);
  sc.any = any;
  sc.inside = false;
  torus_scan_pieces(sc, h);
  return sc.found;
}

bool torus_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit) {
  prism_clear_hit(hit);
  TorusScan sc;
  real3 foot;
  if (!torus_scan(rec, ray, tmin, tmax, false, sc, foot)) return false;
  hit.t = sc.tf + sc.big * sc.root;
  hit.data = foot + (sc.big * sc.root) * ray.dir;
  return true;
}

// Whether torus_intersect finds a hit with t < tmax.
bool torus_occluded(PrismRecord rec, PrismRay ray, real tmin, real tmax) {
  TorusScan sc;
  real3 foot;
  if (!torus_scan(rec, ray, tmin, tmax, true, sc, foot)) return false;
  return sc.inside || sc.tf + sc.big * sc.root < tmax;
}

// The stored point re-projected onto the tube: nearest point of the core
// circle plus r along the radial direction, which is the normal.
void torus_surface(PrismRecord rec, PrismRay ray, PrismHit hit, OUT(PrismSurface) s) {
  real major = prism_record(rec, TORUS_MAJOR), minor = prism_record(rec, TORUS_MINOR);
  real3 p = hit.data;
  real radial = sqrt(p.x * p.x + p.z * p.z);
  real3 normal = real3(R(0.0));
  if (radial > R(0.0)) {
    real3 core = real3(major * p.x / radial, R(0.0), major * p.z / radial);
    real3 out_dir = p - core;
    real len = length(out_dir);
    if (len > R(0.0)) {
      normal = out_dir / len;
      p = core + minor * normal;
    }
  }
  s.point = p;
  s.normal = normal;
  s.uv = real2(prism_turn_fraction(p.z, p.x), prism_turn_fraction(p.y, sqrt(p.x * p.x + p.z * p.z) - major));
}
