#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "prism/csv.hpp"
#include "process.hpp"

namespace prism::stability {

namespace fs = std::filesystem;

namespace {

std::string g3(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

std::string g17(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string xml(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

nlohmann::ordered_json number_json(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}

nlohmann::ordered_json percentiles_json(const Percentiles& p) {
  nlohmann::ordered_json j;
  j["n"] = p.n;
  if (p.n == 0) {
    j["p50"] = nullptr;
    j["p99"] = nullptr;
    j["max"] = nullptr;
  } else {
    j["p50"] = number_json(p.p50);
    j["p99"] = number_json(p.p99);
    j["max"] = number_json(p.max);
  }
  return j;
}

// The table's precision: what the backend's --stats said ("double",
// "float", ...), cut to the column; "?" when it said nothing.
std::string precision_column(const Summary& s) {
  if (s.precision.empty()) return "?";
  return s.precision.size() <= 9 ? s.precision : s.precision.substr(0, 8) + "~";
}

// One series of the chart: a backend in one precision.
std::string series(const Summary& s) { return s.precision.empty() ? s.backend : s.backend + " (" + s.precision + ")"; }

}  // namespace

std::string format_error(const Percentiles& p, double Percentiles::*field) {
  if (p.n == 0) return "-";
  return g3(p.*field);
}

void print_table(std::FILE* out, const std::vector<Summary>& rows) {
  std::fprintf(out, "%-26s %-16s %-9s %-9s %5s %5s %4s %5s  %-9s %-9s %-9s %-9s  %-9s %-9s  %-9s %8s  %s\n",
               "family", "param", "backend", "precision", "rays", "hits", "amb", "miscl", "t p50", "t p99", "t max", "t floor", "n p99",
               "n max", "pt p99", "ns/ray", "verdict");
  for (const Summary& s : rows) {
    std::fprintf(
        out, "%-26s %-16s %-9s %-9s %5lld %5lld %4lld %5lld  %-9s %-9s %-9s %-9s  %-9s %-9s  %-9s %8.0f  %s\n",
        s.family.c_str(), s.param.c_str(), s.backend.c_str(), precision_column(s).c_str(), (long long)s.rays, (long long)s.hits,
        (long long)s.ambiguous, (long long)s.misclassified, format_error(s.t_rel, &Percentiles::p50).c_str(),
        format_error(s.t_rel, &Percentiles::p99).c_str(), format_error(s.t_rel, &Percentiles::max).c_str(),
        format_error(s.t_floor, &Percentiles::p99).c_str(), format_error(s.normal_angle, &Percentiles::p99).c_str(),
        format_error(s.normal_angle, &Percentiles::max).c_str(),
        format_error(s.point_distance, &Percentiles::p99).c_str(), s.ns_per_ray, verdict_word(s));
  }
}

void write_csv(const fs::path& file, const std::vector<Summary>& rows) {
  std::string text =
      "family,param,primitive,backend,precision,rays,hits,ambiguous,misclassified,false_miss,false_hit,wrong_object,"
      "ambiguous_disagree,t_rel_n,t_rel_p50,t_rel_p99,t_rel_max,t_floor_p50,t_floor_p99,t_floor_max,normal_n,"
      "normal_p50,normal_p99,normal_max,normal_floor_p99,point_n,point_p50,point_p99,point_max,render_ms,ns_per_ray,"
      "verdict,failures,double_only,beyond_float\n";
  auto pct = [](const Percentiles& p) {
    if (p.n == 0) return std::string(",,");
    return g17(p.p50) + "," + g17(p.p99) + "," + g17(p.max);
  };
  for (const Summary& s : rows) {
    std::string failures;
    for (const auto& f : s.failures) failures += (failures.empty() ? "" : "; ") + f;
    std::string beyond;
    for (const auto& f : s.beyond_float) beyond += (beyond.empty() ? "" : "; ") + f;
    text += csv_field(s.family) + "," + csv_field(s.param) + "," + s.primitive + "," + s.backend + "," +
            csv_field(s.precision) + "," + std::to_string(s.rays) + "," + std::to_string(s.hits) + "," +
            std::to_string(s.ambiguous) + "," + std::to_string(s.misclassified) + "," + std::to_string(s.false_miss) +
            "," + std::to_string(s.false_hit) + "," + std::to_string(s.wrong_object) + "," +
            std::to_string(s.ambiguous_disagree) + "," + std::to_string(s.t_rel.n) + "," + pct(s.t_rel) + "," +
            pct(s.t_floor) + "," + std::to_string(s.normal_angle.n) + "," + pct(s.normal_angle) + "," +
            (s.normal_floor.n ? g17(s.normal_floor.p99) : "") + "," + std::to_string(s.point_distance.n) + "," +
            pct(s.point_distance) + "," + g17(s.render_ms) + "," + g17(s.ns_per_ray) + "," +
            (s.failures.empty() ? "pass" : "fail") + "," + csv_field(failures) + "," +
            (s.double_only ? "yes" : "no") + "," + csv_field(beyond) + "\n";
  }
  write_text(file, text);
}

nlohmann::ordered_json summary_json(const Summary& s) {
  nlohmann::ordered_json j;
  j["family"] = s.family;
  j["param"] = s.param;
  j["primitive"] = s.primitive;
  j["backend"] = s.backend;
  j["precision"] = s.precision;
  j["rays"] = s.rays;
  j["hits"] = s.hits;
  j["ambiguous"] = s.ambiguous;
  j["misclassified"] = s.misclassified;
  j["false_miss"] = s.false_miss;
  j["false_hit"] = s.false_hit;
  j["wrong_object"] = s.wrong_object;
  j["ambiguous_disagree"] = s.ambiguous_disagree;
  j["t_rel"] = percentiles_json(s.t_rel);
  j["t_floor"] = percentiles_json(s.t_floor);
  j["normal_angle"] = percentiles_json(s.normal_angle);
  j["normal_floor"] = percentiles_json(s.normal_floor);
  j["point_distance"] = percentiles_json(s.point_distance);
  j["render_ms"] = s.render_ms;
  j["ns_per_ray"] = s.ns_per_ray;
  j["verdict"] = s.failures.empty() ? "pass" : "fail";
  j["failures"] = s.failures;
  j["double_only"] = s.double_only;
  j["beyond_float"] = s.beyond_float;
  // The worst rays, for a failing row only (they are what a reader needs to
  // reproduce the failure; a passing row's would only bloat the file).
  nlohmann::ordered_json worst = nlohmann::ordered_json::array();
  for (const Example& e : s.failures.empty() ? std::vector<Example>{} : s.worst) {
    nlohmann::ordered_json w;
    w["param"] = e.param;
    w["what"] = e.what;
    w["origin"] = {e.ray.origin[0], e.ray.origin[1], e.ray.origin[2]};
    w["dir"] = {e.ray.dir[0], e.ray.dir[1], e.ray.dir[2]};
    w["tmin"] = e.ray.tmin;
    w["oracle"] = e.oracle;
    w["backend"] = e.backend_answer;
    worst.push_back(w);
  }
  j["worst_rays"] = worst;
  return j;
}

void write_json(const fs::path& file, const nlohmann::ordered_json& meta, const std::vector<Summary>& rows,
                const std::vector<Summary>& sweep) {
  nlohmann::ordered_json j = meta;
  j["rows"] = nlohmann::ordered_json::array();
  for (const Summary& s : rows) j["rows"].push_back(summary_json(s));
  if (!sweep.empty()) {
    j["sweep"] = nlohmann::ordered_json::array();
    for (const Summary& s : sweep) j["sweep"].push_back(summary_json(s));
  }
  write_text(file, j.dump(2) + "\n");
}

void write_svg(const fs::path& file, const std::vector<Summary>& rows, const std::string& title) {
  const double W = 960, H = 640, left = 90, right = 190, top = 60, bottom = 70;
  const double pw = W - left - right, ph = H - top - bottom;
  const double kZero = 1e-18;  // where an exact (0) error is drawn

  std::vector<std::string> backends;
  double xmin = 1e300, xmax = 0, ymax = 1e-3;
  for (const Summary& s : rows) {
    if (std::find(backends.begin(), backends.end(), series(s)) == backends.end()) backends.push_back(series(s));
    if (s.t_rel.n == 0 || !(s.ns_per_ray > 0)) continue;
    xmin = std::min(xmin, s.ns_per_ray);
    xmax = std::max(xmax, s.ns_per_ray);
    if (std::isfinite(s.t_rel.p99)) ymax = std::max(ymax, s.t_rel.p99);
  }
  if (xmax == 0) xmin = 1, xmax = 10;
  const double lx0 = std::floor(std::log10(xmin)), lx1 = std::max(lx0 + 1, std::ceil(std::log10(xmax)));
  const double ly0 = std::log10(kZero), ly1 = std::ceil(std::log10(ymax)) + 0.5;
  auto X = [&](double v) { return left + (std::log10(v) - lx0) / (lx1 - lx0) * pw; };
  auto Y = [&](double v) {
    const double l = std::clamp(std::log10(std::max(v, kZero)), ly0, ly1);
    return top + (ly1 - l) / (ly1 - ly0) * ph;
  };
  static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"};

  std::string svg;
  char buf[1024];
  std::snprintf(
      buf, sizeof buf,
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
      "font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
      W, H, W, H);
  svg += buf;
  std::snprintf(buf, sizeof buf, "<text x=\"%.0f\" y=\"30\" text-anchor=\"middle\" font-size=\"17\">%s</text>\n",
                left + pw / 2, xml(title).c_str());
  svg += buf;
  // Grid and ticks: every power of ten.
  for (double l = lx0; l <= lx1 + 1e-9; l += 1) {
    const double x = left + (l - lx0) / (lx1 - lx0) * pw;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n<text x=\"%.1f\" "
                  "y=\"%.1f\" text-anchor=\"middle\">1e%d</text>\n",
                  x, top, x, top + ph, x, top + ph + 18, int(l));
    svg += buf;
  }
  for (double l = std::ceil(ly0); l <= ly1 + 1e-9; l += 1) {
    const double y = top + (ly1 - l) / (ly1 - ly0) * ph;
    const bool label = int(l) % 2 == 0 || l == ly0;
    std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", left, y,
                  left + pw, y);
    svg += buf;
    if (label) {
      std::snprintf(buf, sizeof buf, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%s</text>\n", left - 6, y + 4,
                    l == ly0 ? "0 (exact)" : ("1e" + std::to_string(int(l))).c_str());
      svg += buf;
    }
  }
  // The caps.
  const double double_cap = caps_for("double").t_rel_p99, gpu_cap = caps_for("float").t_rel_p99;
  char double_label[32], gpu_label[32];
  std::snprintf(double_label, sizeof double_label, "double cap %g", double_cap);
  std::snprintf(gpu_label, sizeof gpu_label, "GPU cap %g", gpu_cap);
  for (const auto& [cap, label] : {std::pair<double, const char*>{double_cap, double_label}, {gpu_cap, gpu_label}}) {
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\" stroke-dasharray=\"6 4\"/>\n"
                  "<text x=\"%.1f\" y=\"%.1f\" fill=\"#555\" text-anchor=\"end\">%s</text>\n",
                  left, Y(cap), left + pw, Y(cap), left + pw - 4, Y(cap) - 4, label);
    svg += buf;
  }
  std::snprintf(buf, sizeof buf,
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#333\"/>\n", left,
                top, pw, ph);
  svg += buf;
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">time per ray (ns, log; the trace's ms.render / "
                "rays)</text>\n<text transform=\"translate(22 %.1f) rotate(-90)\" text-anchor=\"middle\">p99 relative "
                "t error |t - t*| / t* (log)</text>\n",
                left + pw / 2, H - 25, top + ph / 2);
  svg += buf;
  // Points: one per row; a failing row gets a black ring.
  for (const Summary& s : rows) {
    if (s.t_rel.n == 0 || !(s.ns_per_ray > 0)) continue;
    const size_t b = size_t(std::find(backends.begin(), backends.end(), series(s)) - backends.begin());
    const double x = X(s.ns_per_ray), y = Y(std::isfinite(s.t_rel.p99) ? s.t_rel.p99 : 1e300);
    std::snprintf(buf, sizeof buf,
                  "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" fill=\"%s\" fill-opacity=\"0.75\" stroke=\"%s\" "
                  "stroke-width=\"%s\"><title>%s %s on %s: p99 %s, %.0f ns/ray%s</title></circle>\n",
                  x, y, palette[b % 7], s.failures.empty() ? "none" : "black", s.failures.empty() ? "0" : "1.5",
                  xml(s.family).c_str(), xml(s.param).c_str(), xml(series(s)).c_str(), g3(s.t_rel.p99).c_str(),
                  s.ns_per_ray, s.failures.empty() ? (s.beyond_float.empty() ? "" : " (double-only)") : " (FAIL)");
    svg += buf;
  }
  // Legend.
  double ly = top + 10;
  for (size_t b = 0; b < backends.size(); ++b, ly += 22) {
    std::snprintf(buf, sizeof buf,
                  "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"6\" fill=\"%s\"/><text x=\"%.1f\" y=\"%.1f\">%s</text>\n",
                  left + pw + 20, ly, palette[b % 7], left + pw + 32, ly + 4, xml(backends[b]).c_str());
    svg += buf;
  }
  std::snprintf(buf, sizeof buf,
                "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"/>"
                "<text x=\"%.1f\" y=\"%.1f\">fails a cap</text>\n<text x=\"%.1f\" y=\"%.1f\" fill=\"#555\">one point "
                "per family</text>\n",
                left + pw + 20, ly + 6, left + pw + 32, ly + 10, left + pw + 14, ly + 34);
  svg += buf;
  svg += "</svg>\n";
  write_text(file, svg);
}

}  // namespace prism::stability
