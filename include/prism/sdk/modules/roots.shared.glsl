// Prism module `roots`, in the shared dialect (prism/sdk/dialect.hpp):
// safeguarded Newton-bisection for a root of f in a bracket [a, b] with
// f(a), f(b) on opposite sides of zero. Written once: C++'s
// prism::sdk::solve_bracketed (prism/sdk/math.hpp) runs these steps, and a
// plugin line `// prism:require roots` splices them into the GPU kernel, so
// both take the same steps and return the same point.
//
// GLSL has no lambdas or function pointers, so the solver runs by reverse
// communication: it keeps its state in a PrismBracket and the caller
// evaluates its own function at `s`, in a loop whose bound is constant:
//
//   PrismBracket br = prism_bracket_start(a, b, fa, fb, tol);
//   for (int i = 0; i < PRISM_BRACKET_MAX_STEPS; ++i) {
//     real f, df;
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
  real lo;  // the end on f(a)'s side
  real hi;  // the other end
  real s;   // where to evaluate next; the root once a step says done
  real tol;
  bool a_positive;
};

PrismBracket prism_bracket_start(real a, real b, real fa, real fb, real tol) {
  PrismBracket br;
  br.a_positive = fa > R(0.0);
  br.lo = a;
  br.hi = b;
  br.tol = tol;
  precise real s = a - fa * (b - a) / (fb - fa);
  if (!(s > a && s < b)) s = R(0.5) * (a + b);
  br.s = s;
  return br;
}

// Takes f and f' at br.s; returns true when br.s is the root.
bool prism_bracket_step(INOUT(PrismBracket) br, real f, real df) {
  if (f == R(0.0)) return true;
  if ((f > R(0.0)) == br.a_positive) {
    br.lo = br.s;
  } else {
    br.hi = br.s;
  }
  // std::min / std::max order, not GLSL min/max (undefined for NaN).
  real mn = br.hi < br.lo ? br.hi : br.lo;
  real mx = br.lo < br.hi ? br.hi : br.lo;
  precise real next = br.s - f / df;
  bool done = false;
  if (next >= mn && next <= mx) {
    done = abs(next - br.s) <= br.tol;
  } else {
    next = R(0.5) * (br.lo + br.hi);
    done = mx - mn <= br.tol || next == mn || next == mx;
  }
  br.s = next;
  return done;
}
