// What the stability suite measures: the oracle's answer for every ray of a
// case (with its ambiguity band and conditioning), a backend's answers
// compared with it, and the per family x backend summary and caps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "exact.hpp"
#include "families.hpp"

namespace prism::stability {

// ---------------------------------------------------------------- the oracle side

struct OracleRay {
  ExactRay ray;
  ExactSceneHit hit;
  // The oracle's classification (object id or miss, or the root: t jumps by
  // more than 1e-3 relative) changes under a nudge of 1e-7 relative (see
  // measure.cpp): misclassifying such a ray is not counted.
  bool ambiguous = false;
  // The oracle's normal jumps (by > 0.1 rad) under a nudge of 1e-12 relative
  // while the object stays: an edge or a corner, where the normal is undefined.
  bool normal_ambiguous = false;
  // What ~2 ulp of input error alone does to the answer (nudges of 2^-51
  // relative): the relative t change and the normal change, the error floor
  // of a backward-stable double algorithm. 0 on a miss.
  double t_floor = 0;
  double normal_floor = 0;
};

struct CaseOracle {
  std::vector<ExactObject> objects;
  std::vector<OracleRay> rays;
};

// Solves every ray of the case in quad precision, with its nudges.
CaseOracle solve_case(const Case& c);

// ---------------------------------------------------------------- the backend side

struct Answer {  // one line of `prism trace -o` output
  double t = 0;
  int object = -1;
  double normal[3] = {0, 0, 0};
};

// Parses `prism trace` output (t,object,nx,ny,nz per line). Throws
// std::runtime_error on a malformed line.
std::vector<Answer> parse_answers(const std::string& text);

// A ray worth showing in a report: the ray, the oracle's and the backend's answer.
struct Example {
  std::string family, param, backend, what;  // what: "false miss", "t error 3e-7", ...
  Ray ray;
  std::string oracle;  // "object 0 t=... n=(...)" or "miss"
  std::string backend_answer;
  double severity = 0;  // for picking the worst ones
};

// Errors of one backend on one or more cases (accumulates).
struct Tally {
  int64_t rays = 0, hits = 0, ambiguous = 0, misclassified = 0;
  int64_t false_miss = 0, false_hit = 0, wrong_object = 0, ambiguous_disagree = 0;
  std::vector<double> t_rel, normal_angle, point_distance, t_floor, normal_floor;
  double render_ms = 0;
  // The worst few rays of each kind.
  std::vector<Example> worst_misclassified, worst_t, worst_normal, worst_point;
};

void compare(const std::string& family, const Case& c, const CaseOracle& oracle, const std::vector<Answer>& answers,
             const std::string& backend, Tally& tally);

// ---------------------------------------------------------------- summaries and caps

struct Percentiles {
  int64_t n = 0;
  double p50 = 0, p99 = 0, max = 0;  // nearest rank; NaN reads as +inf
};
Percentiles percentiles(std::vector<double> values);

struct Summary {
  std::string family, param, primitive, backend, precision;
  int64_t rays = 0, hits = 0, ambiguous = 0, misclassified = 0;
  int64_t false_miss = 0, false_hit = 0, wrong_object = 0, ambiguous_disagree = 0;
  Percentiles t_rel, normal_angle, point_distance, t_floor, normal_floor;
  double render_ms = 0, ns_per_ray = 0;
  // The family is one float cannot do (Family::double_only): a float row's
  // caps are measured and reported (beyond_float), never failed.
  bool double_only = false;
  std::vector<std::string> failures;      // caps that fail; empty: pass
  std::vector<std::string> beyond_float;  // the caps a double-only family's float row exceeds
  std::vector<Example> worst;
};

// "pass", "FAIL", or "double-only" (a float row of a double-only family over its caps).
const char* verdict_word(const Summary& s);

Summary summarize(const std::string& family, const std::string& param, const std::string& primitive,
                  const std::string& backend, const std::string& precision, const Tally& tally,
                  bool double_only = false);

// The caps (they may be tightened, never loosened):
// - double-precision backends (`--stats` info.precision == "double": reference,
//   embree): no misclassification outside the ambiguity band, relative t error
//   p99 <= 1e-10 (the 1e-9, tightened once ill-conditioned hits were
//   polished in long double), and also normal angle p99 <= 1e-6 rad (the
//   cone apex's input-rounding floor is 1.4e-5) and reported point off the
//   surface p99 <= 1e-9 (relative to the object's size);
// - every other backend (the GPU ones: "double geometry, float32 shading";
//   "float", `--precision float`: the plugins' float instantiations):
//   misclassification <= 1 % of the family's rays, relative t error p99 <= 1e-4.
//   A "float" row of a double-only family is reported against these caps,
//   not failed (docs/numerics.md, "What float cannot do").
struct Caps {
  double misclassified_fraction;  // 0 for double
  double t_rel_p99;
  double normal_p99;  // < 0: no cap
  double point_p99;   // < 0: no cap
};
Caps caps_for(const std::string& precision);
void apply_caps(Summary& s);

}  // namespace prism::stability
