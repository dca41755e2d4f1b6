// Prism GLSL module `roots` (a plugin line `// prism:require roots` splices
// it after library.glsl): safeguarded Newton-bisection for a root of f in a
// bracket [a, b] with f(a), f(b) on opposite sides of zero, a port of
// prism/sdk/math.hpp solve_bracketed that takes the same steps and returns
// the same point. Double precision, as the geometry it polishes.
//
// GLSL has no lambdas or function pointers, so the solver runs by reverse
// communication: it keeps its state in a PrismBracket and the caller
// evaluates its own function at `s`, in a loop whose bound is constant:
//
//   PrismBracket br = prism_bracket_start(a, b, fa, fb, tol);
//   for (int i = 0; i < PRISM_BRACKET_MAX_STEPS; ++i) {
//     double f, df;
//     ...f and df at br.s...
//     if (prism_bracket_step(br, f, df)) break;
//   }
//   ...the root is br.s...
//
// Start at the secant point; bisect whenever a Newton step would leave the
// current bracket (or the derivative is 0 or NaN), so br.s always lies in
// [a, b]; stop after a Newton step shorter than `tol` (leaving an error
// ~tol^2) or once the bracket is narrower than `tol`. A NaN f only shrinks
// the bracket, and the step count is bounded, so NaN rays end.
#define PRISM_BRACKET_MAX_STEPS 128

struct PrismBracket {
  double lo;  // the end on f(a)'s side
  double hi;  // the other end
  double s;   // where to evaluate next; the root once a step says done
  double tol;
  bool a_positive;
};

PrismBracket prism_bracket_start(double a, double b, double fa, double fb, double tol) {
  PrismBracket br;
  br.a_positive = fa > 0.0LF;
  br.lo = a;
  br.hi = b;
  br.tol = tol;
  double s = a - fa * (b - a) / (fb - fa);
  if (!(s > a && s < b)) s = 0.5LF * (a + b);
  br.s = s;
  return br;
}

// Takes f and f' at br.s; returns true when br.s is the root.
bool prism_bracket_step(inout PrismBracket br, double f, double df) {
  if (f == 0.0LF) return true;
  if ((f > 0.0LF) == br.a_positive) {
    br.lo = br.s;
  } else {
    br.hi = br.s;
  }
  // std::min / std::max order, not GLSL min/max (undefined for NaN).
  double mn = br.hi < br.lo ? br.hi : br.lo;
  double mx = br.lo < br.hi ? br.hi : br.lo;
  double next = br.s - f / df;
  bool done = false;
  if (next >= mn && next <= mx) {
    done = abs(next - br.s) <= br.tol;
  } else {
    next = 0.5LF * (br.lo + br.hi);
    done = mx - mn <= br.tol || next == mn || next == mx;
  }
  br.s = next;
  return done;
}
