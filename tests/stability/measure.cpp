#include "measure.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

namespace prism::stability {

namespace {

constexpr double kInfD = std::numeric_limits<double>::infinity();
// A relative change of t beyond this is another root (another part of the
// surface), not an error in the same one.
constexpr double kRootJump = 1e-3;

// Quad-precision vector helpers (exact.cpp keeps its own to itself).
Vec add(const Vec& a, const Vec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec sub(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec scale(real s, const Vec& a) { return {s * a.x, s * a.y, s * a.z}; }
real dotq(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec crossq(const Vec& a, const Vec& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
real normq(const Vec& a) { return sqrtq(dotq(a, a)); }
Vec unitq(const Vec& a) { return scale(1 / normq(a), a); }

// The angle between two directions, accurate near 0 (no acos).
real angle(const Vec& a, const Vec& b) { return atan2q(normq(crossq(a, b)), dotq(a, b)); }

// NaN stays NaN (it reads as +inf in the percentiles).
double to_double(real v) { return isnanq(v) ? std::numeric_limits<double>::quiet_NaN() : double(v); }

// Where an object "is", for the band of a ray that misses: its centre (a
// plane's point).
Vec anchor_of(const nlohmann::json& object) {
  for (const char* key : {"center", "point"}) {
    auto it = object.find(key);
    if (it != object.end() && it->is_array() && it->size() == 3)
      return {real((*it)[0].get<double>()), real((*it)[1].get<double>()), real((*it)[2].get<double>())};
  }
  return {0, 0, 0};
}

// The ambiguity band and the conditioning of one ray.
//
// Why 1e-7 relative: a ray is only known to its producer to the precision of
// the numbers that made it (a camera basis, a hit point, a reflected
// direction), and a float32 pipeline carries ~6e-8 relative error in each of
// them. Where a nudge of that size (the origin moved 1e-7 (|o| + t*)
// sideways, or the direction turned by 1e-7 rad) changes which object is hit
// (or hit vs miss), or which part of it (t* jumps to another root: a tangent
// that touches one part of a torus and goes on to hit another), the ray lies
// on a silhouette, an edge, a rim or a tangent to that precision, and neither
// answer can be called wrong: such rays are "ambiguous" and not counted as
// misclassified (their t and normal errors are left out when the backend's
// classification differs: there is nothing to compare them with). Four
// origin nudges (± along two directions perpendicular to d) and four
// direction nudges (turned toward the same two directions) probe the
// neighbourhood. For a miss, t* is replaced by the distance to the nearest
// object's centre. The band is narrow enough that the families' deliberate
// near misses (5x the band off a tangent, 1e-5 off a ring's inner radius)
// stay outside it.
//
// The normal is undefined on a box edge or corner. Where a nudge of 1e-12
// relative keeps the object but turns the oracle's normal by more than 0.1
// rad, the ray sits on such a crease and its normal error is left out too
// (1e-12, not 1e-7: a 1e-7 rad turn of a ray from 1e6 away moves its hit
// point by 0.1, which turns a unit sphere's normal that much without any
// crease).
//
// The same probe at 2^-51 relative (about 2 ulp of a double) measures what
// input rounding alone does to the answer: t_floor and normal_floor, the
// errors a backward-stable double algorithm can show. A family whose error
// sits at its floor is ill-conditioned there rather than badly solved. Where
// those 2 ulp move t to another root, the ray is ambiguous; where they turn
// the normal by more than 1e-3 rad (a hit within rounding of a cone's apex,
// where the normal's azimuth is whatever the last bit says), its normal is.
void probe(const std::vector<ExactObject>& objects, const std::vector<Vec>& anchors, OracleRay& r) {
  const ExactRay& ray = r.ray;
  const Vec d = ray.dir;
  const Vec helper = fabsq(d.x) < real(0.5) ? Vec{1, 0, 0} : Vec{0, 1, 0};
  const Vec e1 = unitq(crossq(d, helper)), e2 = crossq(d, e1);
  real t_ref = r.hit.t;
  if (r.hit.object < 0) {
    t_ref = -1;
    for (const Vec& a : anchors) {
      const real dist = normq(sub(a, ray.origin));
      if (t_ref < 0 || dist < t_ref) t_ref = dist;
    }
    if (t_ref < 0) t_ref = 0;
  }
  const real reach = normq(ray.origin) + t_ref;

  enum Kind { kBand, kCrease, kFloor };
  const std::pair<real, Kind> levels[] = {{real(1e-7), kBand}, {real(1e-12), kCrease}, {ldexpq(1, -51), kFloor}};
  for (const auto& [relative, kind] : levels) {
    const real shift = relative * reach, c = cosq(relative), s = sinq(relative);
    for (int k = 0; k < 8; ++k) {
      const Vec e = scale(k % 2 ? -1 : 1, k / 2 % 2 ? e2 : e1);
      ExactRay nudged = ray;
      if (k < 4)
        nudged.origin = add(ray.origin, scale(shift, e));
      else
        nudged.dir = add(scale(c, d), scale(s, e));
      const ExactSceneHit h = closest_hit(objects, nudged);
      if (h.object != r.hit.object) {
        r.ambiguous = true;
        continue;
      }
      if (h.object < 0) continue;
      const double t_change = to_double(fabsq(h.t - r.hit.t) / r.hit.t);
      const double turn = to_double(angle(h.normal, r.hit.normal));
      if (kind == kBand && t_change > kRootJump) r.ambiguous = true;
      if (kind == kCrease && turn > 0.1) r.normal_ambiguous = true;
      if (kind == kFloor) {
        // Another root, or a normal turned by more than 1e-3 rad, for 2 ulp of
        // input: the answer is not defined in double (a tangent, the apex of a
        // cone); the ray is ambiguous, or its normal is.
        if (t_change > kRootJump)
          r.ambiguous = true;
        else
          r.t_floor = std::max(r.t_floor, t_change);
        if (turn > 1e-3)
          r.normal_ambiguous = true;
        else
          r.normal_floor = std::max(r.normal_floor, turn);
      }
    }
  }
}

std::string format_vec(const double v[3]) {
  char text[128];
  std::snprintf(text, sizeof text, "(%.17g, %.17g, %.17g)", v[0], v[1], v[2]);
  return text;
}

std::string describe_oracle(const ExactSceneHit& h) {
  if (h.object < 0) return "miss";
  return "object " + std::to_string(h.object) + " t=" + to_string(h.t, 20) + " n=(" + to_string(h.normal.x, 17) + ", " +
         to_string(h.normal.y, 17) + ", " + to_string(h.normal.z, 17) + ")";
}

std::string describe_answer(const Answer& a) {
  if (a.object < 0) return "miss";
  char text[64];
  std::snprintf(text, sizeof text, "object %d t=%.17g n=", a.object, a.t);
  return text + format_vec(a.normal);
}

// Keeps the `keep` examples of highest severity.
void keep_worst(std::vector<Example>& list, Example e, size_t keep) {
  list.push_back(std::move(e));
  std::stable_sort(list.begin(), list.end(),
                   [](const Example& a, const Example& b) { return a.severity > b.severity; });
  if (list.size() > keep) list.resize(keep);
}

}  // namespace

CaseOracle solve_case(const Case& c) {
  CaseOracle out;
  std::vector<Vec> anchors;
  for (const auto& object : c.objects) {
    out.objects.emplace_back(object);
    anchors.push_back(anchor_of(object));
  }
  out.rays.resize(c.rays.size());
  // The rays are independent: solve them on every core.
  const unsigned threads = std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0};
  std::vector<std::string> errors(threads);
  auto work = [&](unsigned id) {
    try {
      for (size_t i; (i = next.fetch_add(1)) < c.rays.size();) {
        const Ray& ray = c.rays[i];
        OracleRay& r = out.rays[i];
        r.ray = make_ray(ray.origin, ray.dir, ray.tmin);
        r.hit = closest_hit(out.objects, r.ray);
        probe(out.objects, anchors, r);
      }
    } catch (const std::exception& e) {
      errors[id] = e.what();
      next = c.rays.size();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned id = 1; id < threads; ++id) pool.emplace_back(work, id);
  work(0);
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (!e.empty()) throw std::runtime_error("oracle: " + e);
  return out;
}

std::vector<Answer> parse_answers(const std::string& text) {
  std::vector<Answer> answers;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    Answer a;
    double v[5];
    const char* p = line.c_str();
    for (int i = 0; i < 5; ++i) {
      char* end = nullptr;
      v[i] = std::strtod(p, &end);
      if (end == p || (i < 4 && *end != ',') || (i == 4 && *end != '\0' && *end != '\r'))
        throw std::runtime_error("trace output line " + std::to_string(number) + ": cannot read '" + line + "'");
      p = end + 1;
    }
    a.t = v[0];
    a.object = int(v[1]);
    for (int i = 0; i < 3; ++i) a.normal[i] = v[2 + i];
    answers.push_back(a);
  }
  return answers;
}

void compare(const std::string& family, const Case& c, const CaseOracle& oracle, const std::vector<Answer>& answers,
             const std::string& backend, Tally& tally) {
  if (answers.size() != oracle.rays.size())
    throw std::runtime_error(family + " " + c.param + ": " + std::to_string(answers.size()) + " answers for " +
                             std::to_string(oracle.rays.size()) + " rays");
  constexpr size_t kKeep = 3;
  for (size_t i = 0; i < answers.size(); ++i) {
    const OracleRay& o = oracle.rays[i];
    const Answer& a = answers[i];
    tally.rays++;
    if (o.hit.object >= 0) tally.hits++;
    if (o.ambiguous) tally.ambiguous++;
    Example example{family, c.param, backend, "", c.rays[i], describe_oracle(o.hit), describe_answer(a), 0};

    // An ambiguous ray may also be answered with another part of the same
    // object: another root (t off by more than kRootJump) or another face
    // (the normal off by more than 0.1 rad, as at a box corner the ray only
    // touches). That is a classification that differs, not an error.
    if (o.ambiguous && a.object == o.hit.object && a.object >= 0) {
      const Vec n{a.normal[0], a.normal[1], a.normal[2]};
      const bool other_root = !(std::fabs(a.t - double(o.hit.t)) <= kRootJump * double(o.hit.t));
      const bool other_face = !(to_double(angle(n, o.hit.normal)) <= 0.1);
      if (other_root || other_face) {
        tally.ambiguous_disagree++;
        continue;
      }
    }
    if (a.object != o.hit.object) {
      if (o.ambiguous) {
        tally.ambiguous_disagree++;
        continue;
      }
      tally.misclassified++;
      if (a.object < 0)
        tally.false_miss++, example.what = "false miss";
      else if (o.hit.object < 0)
        tally.false_hit++, example.what = "false hit";
      else
        tally.wrong_object++, example.what = "wrong object";
      example.severity = kInfD;
      keep_worst(tally.worst_misclassified, example, kKeep);
      continue;
    }
    if (o.hit.object < 0) continue;  // both miss

    const real t_rel = fabsq(real(a.t) - o.hit.t) / o.hit.t;
    const double t_err = std::isnan(a.t) ? kInfD : to_double(t_rel);
    tally.t_rel.push_back(t_err);
    tally.t_floor.push_back(o.t_floor);
    char what[96];
    std::snprintf(what, sizeof what, "relative t error %.3g (floor %.3g)", t_err, o.t_floor);
    example.what = what;
    example.severity = t_err;
    keep_worst(tally.worst_t, example, kKeep);

    const Vec n{a.normal[0], a.normal[1], a.normal[2]};
    if (!o.normal_ambiguous) {
      double turn = to_double(angle(n, o.hit.normal));
      if (std::isnan(turn) || !(normq(n) > 0)) turn = kInfD;
      tally.normal_angle.push_back(turn);
      tally.normal_floor.push_back(o.normal_floor);
      std::snprintf(what, sizeof what, "normal off by %.3g rad (floor %.3g)", turn, o.normal_floor);
      example.what = what;
      example.severity = turn;
      keep_worst(tally.worst_normal, example, kKeep);
    }

    const ExactObject& object = oracle.objects[size_t(o.hit.object)];
    const Vec point = add(o.ray.origin, scale(real(a.t), o.ray.dir));
    double off = to_double(object.distance_to_surface(point) / object.size());
    if (std::isnan(a.t) || std::isnan(off)) off = kInfD;
    tally.point_distance.push_back(off);
    std::snprintf(what, sizeof what, "point %.3g (of the size) off the surface", off);
    example.what = what;
    example.severity = off;
    keep_worst(tally.worst_point, example, kKeep);
  }
}

Percentiles percentiles(std::vector<double> values) {
  Percentiles p;
  p.n = int64_t(values.size());
  if (values.empty()) return p;
  for (double& v : values)
    if (std::isnan(v)) v = kInfD;
  std::sort(values.begin(), values.end());
  auto rank = [&](double q) {
    const size_t k = size_t(std::ceil(q * double(values.size())));
    return values[std::min(values.size() - 1, k == 0 ? 0 : k - 1)];
  };
  p.p50 = rank(0.5);
  p.p99 = rank(0.99);
  p.max = values.back();
  return p;
}

Summary summarize(const std::string& family, const std::string& param, const std::string& primitive,
                  const std::string& backend, const std::string& precision, const Tally& tally,
                  bool double_only) {
  Summary s;
  s.double_only = double_only;
  s.family = family;
  s.param = param;
  s.primitive = primitive;
  s.backend = backend;
  s.precision = precision;
  s.rays = tally.rays;
  s.hits = tally.hits;
  s.ambiguous = tally.ambiguous;
  s.misclassified = tally.misclassified;
  s.false_miss = tally.false_miss;
  s.false_hit = tally.false_hit;
  s.wrong_object = tally.wrong_object;
  s.ambiguous_disagree = tally.ambiguous_disagree;
  s.t_rel = percentiles(tally.t_rel);
  s.normal_angle = percentiles(tally.normal_angle);
  s.point_distance = percentiles(tally.point_distance);
  s.t_floor = percentiles(tally.t_floor);
  s.normal_floor = percentiles(tally.normal_floor);
  s.render_ms = tally.render_ms;
  s.ns_per_ray = tally.rays > 0 ? tally.render_ms * 1e6 / double(tally.rays) : 0;
  for (const auto* list : {&tally.worst_misclassified, &tally.worst_t, &tally.worst_normal, &tally.worst_point})
    s.worst.insert(s.worst.end(), list->begin(), list->end());
  apply_caps(s);
  return s;
}

Caps caps_for(const std::string& precision) {
  if (precision == "double") return {0.0, 1e-10, 1e-6, 1e-9};
  return {0.01, 1e-4, -1, -1};
}

void apply_caps(Summary& s) {
  const Caps caps = caps_for(s.precision);
  char text[256];
  s.failures.clear();
  if (double(s.misclassified) > caps.misclassified_fraction * double(s.rays)) {
    std::snprintf(text, sizeof text,
                  "misclassified %lld of %lld rays outside the band (false miss %lld, false hit %lld, wrong object "
                  "%lld); cap %g %%",
                  (long long)s.misclassified, (long long)s.rays, (long long)s.false_miss, (long long)s.false_hit,
                  (long long)s.wrong_object, caps.misclassified_fraction * 100);
    s.failures.push_back(text);
  }
  if (s.t_rel.n > 0 && !(s.t_rel.p99 <= caps.t_rel_p99)) {
    std::snprintf(text, sizeof text, "relative t error p99 %.3g > %g (max %.3g; input-rounding floor p99 %.3g)",
                  s.t_rel.p99, caps.t_rel_p99, s.t_rel.max, s.t_floor.p99);
    s.failures.push_back(text);
  }
  if (caps.normal_p99 >= 0 && s.normal_angle.n > 0 && !(s.normal_angle.p99 <= caps.normal_p99)) {
    std::snprintf(text, sizeof text, "normal angle p99 %.3g rad > %g (max %.3g; floor p99 %.3g)", s.normal_angle.p99,
                  caps.normal_p99, s.normal_angle.max, s.normal_floor.p99);
    s.failures.push_back(text);
  }
  if (caps.point_p99 >= 0 && s.point_distance.n > 0 && !(s.point_distance.p99 <= caps.point_p99)) {
    std::snprintf(text, sizeof text, "point off the surface p99 %.3g > %g of the size (max %.3g)", s.point_distance.p99,
                  caps.point_p99, s.point_distance.max);
    s.failures.push_back(text);
  }
  if (s.double_only && s.precision == "float") s.beyond_float = std::exchange(s.failures, {});
}

const char* verdict_word(const Summary& s) {
  if (!s.failures.empty()) return "FAIL";
  return s.beyond_float.empty() ? "pass" : "double-only";
}

}  // namespace prism::stability
