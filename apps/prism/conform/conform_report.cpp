// The report of `prism conform`: results.json and results.csv for tools,
// index.html for people. The page is one self-contained file (images as PNG
// data URIs, charts as inline SVG, no scripts or styles from elsewhere) so
// that it can be attached to a CI run or mailed and still open anywhere.
#include "conform/conform.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "prism/csv.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/texture.hpp"

namespace fs = std::filesystem;

namespace prism::conform {

namespace {

// ---------------------------------------------------------------------------
// Shared helpers

template <typename... Args>
std::string formatted(const char* pattern, Args... args) {
  const int size = std::snprintf(nullptr, 0, pattern, args...);
  std::string text(size_t(std::max(size, 0)), '\0');
  std::snprintf(text.data(), text.size() + 1, pattern, args...);
  return text;
}

// The shortest decimal that reads back as the same float, so that a cap of
// 0.016f is written as 0.016 and not as its double expansion 0.0160000008.
double float_as_decimal(float value) {
  for (int digits = 6; digits < 9; ++digits) {
    const double decimal = std::strtod(formatted("%.*g", digits, double(value)).c_str(), nullptr);
    if (float(decimal) == value) return decimal;
  }
  return double(value);
}

// Every backend name in the run, in the order first met, so that columns and
// chart colours are the same in every scene.
std::vector<std::string> backend_names(const RunResult& run) {
  std::vector<std::string> names;
  for (const SceneResult& scene : run.scenes)
    for (const BackendResult& backend : scene.backends)
      if (std::find(names.begin(), names.end(), backend.backend) == names.end()) names.push_back(backend.backend);
  return names;
}

bool has_pixels(const Image& image) {
  return image.width > 0 && image.height > 0 && image.rgb.size() == size_t(image.width) * image.height * 3;
}

bool same_size(const Image& a, const Image& b) { return a.width == b.width && a.height == b.height; }

std::string percent_text(double fraction) {
  const double percent = 100.0 * fraction;
  if (!std::isfinite(percent)) return "—";
  if (percent == 0) return "0 %";
  if (percent >= 10) return formatted("%.0f %%", percent);
  if (percent >= 1) return formatted("%.1f %%", percent);
  return formatted("%.2f %%", percent);
}

// "torus (object 3): 92 %": how the report and the CSV name an attribution.
std::string attribution_text(const Attribution& attribution) {
  return attribution.label + ": " + percent_text(attribution.fraction);
}

// ---------------------------------------------------------------------------
// Heat map

struct Rgb {
  double r = 0, g = 0, b = 0;
};

// The heat map's scale, in multiples of the threshold: logarithmic from
// kFloorScale (black) up to the threshold, then on to white at kWhiteScale,
// yellow halfway there on the log scale.
constexpr double kFloorScale = 1e-3;
constexpr double kWhiteScale = 8;
const double kYellowScale = std::sqrt(kWhiteScale);
// Below the threshold: black to this blue, a third of the way per factor of 10.
constexpr Rgb kBelowThreshold{0, 0.6, 1};

// Where a multiple of the threshold sits on the legend's bar, 0 to 1.
double legend_position(double scale) {
  return std::log(scale / kFloorScale) / std::log(kWhiteScale / kFloorScale);
}

// The colour a difference should have on screen (sRGB-encoded). Blue below
// the threshold, so that errors too small to fail still show, each decade
// brighter; red at the threshold and above it towards yellow and white, so
// that pixels just over and wildly wrong ones still look different.
Rgb heat_colour(double difference, double threshold) {
  if (!std::isfinite(difference)) return {1, 0, 1};
  if (difference <= 0) return {0, 0, 0};
  const double scale = threshold > 0 ? difference / threshold : std::numeric_limits<double>::infinity();
  if (scale < 1) {
    // 0 at the floor, 1 at the threshold.
    const double below = std::max(0.0, std::log(scale / kFloorScale) / std::log(1 / kFloorScale));
    return {below * kBelowThreshold.r, below * kBelowThreshold.g, below * kBelowThreshold.b};
  }
  const double above = std::min(std::log(scale) / std::log(kWhiteScale), 1.0);  // 0 at 1x, 1 at 8x
  if (above <= 0.5) return {1, 2 * above, 0};
  return {1, 1, 2 * (above - 0.5)};
}

// Max over channels of |a - b|; NaN when either pixel holds a NaN or Inf.
double pixel_difference(const float* a, const float* b) {
  double difference = 0;
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(a[c]) || !std::isfinite(b[c])) return std::numeric_limits<double>::quiet_NaN();
    difference = std::max(difference, std::abs(double(a[c]) - double(b[c])));
  }
  return difference;
}

// ---------------------------------------------------------------------------
// JSON

using Json = nlohmann::ordered_json;

// JSON has no NaN or Infinity: a non-finite value (PSNR of identical images)
// is written as null rather than as text no parser accepts.
Json number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json to_json(const Caps& caps) {
  return {{"threshold", float_as_decimal(caps.threshold)},
          {"stable_over_gpu", number(caps.stable_over_gpu)},
          {"stable_over_double", number(caps.stable_over_double)},
          {"all_over", number(caps.all_over)}};
}

Json to_json(const ImageSettings& settings) {
  return {
      {"width", settings.width}, {"height", settings.height}, {"spp", settings.spp}, {"max_depth", settings.max_depth}};
}

Json to_json(const Metrics& m) {
  return {{"mean_error", number(m.mean_error)},
          {"rms_error", number(m.rms_error)},
          {"psnr", number(m.psnr)},
          {"max_error", number(m.max_error)},
          {"pixels", m.pixels},
          {"pixels_over", m.pixels_over},
          {"stable_pixels", m.stable_pixels},
          {"stable_over", m.stable_over},
          {"edge_pixels", m.edge_pixels},
          {"edge_over", m.edge_over},
          {"nonfinite", m.nonfinite}};
}

Json to_json(const Attribution& a) {
  return {{"object_id", a.object_id}, {"label", a.label}, {"pixels", a.pixels}, {"fraction", number(a.fraction)}};
}

Json to_json(const SweepPoint& p) {
  return {{"spp", p.spp},
          {"render_ms", number(p.render_ms)},
          {"rms_error", number(p.rms_error)},
          {"mean_error", number(p.mean_error)}};
}

// Declared before to_json_array, whose calls see only the overloads above it.
Json to_json(const BackendResult& b);

template <typename T>
Json to_json_array(const std::vector<T>& items) {
  Json array = Json::array();
  for (const T& item : items) array.push_back(to_json(item));
  return array;
}

Json to_json(const BackendResult& b) {
  return {{"backend", b.backend},
          {"status", b.status},
          {"reason", b.reason},
          {"device", b.device},
          {"precision", b.precision},
          {"render_ms", number(b.render_ms)},
          {"compile_ms", number(b.compile_ms)},
          {"prepare_ms", number(b.prepare_ms)},
          {"first_frame_ms", number(b.first_frame_ms())},
          {"metrics", to_json(b.metrics)},
          {"attribution", to_json_array(b.attribution)},
          {"sweep", to_json_array(b.sweep)}};
}

Json to_json(const BackendSummary& s) {
  return {{"backend", s.backend},
          {"passed", s.passed},
          {"failed", s.failed},
          {"errors", s.errors},
          {"skipped", s.skipped},
          {"speedup", number(s.speedup)},
          {"worst_max_error", number(s.worst_max_error)},
          {"worst_rms_error", number(s.worst_rms_error)},
          {"compile_ms", number(s.compile_ms)},
          {"first_frame_ms", number(s.first_frame_ms)},
          {"passes", s.passes()}};
}

Json to_json(const SceneResult& s) {
  return {{"name", s.name},
          {"file", s.file.string()},
          {"settings", to_json(s.image)},
          {"reference_backend", s.reference_backend},
          {"reference_ms", number(s.reference_ms)},
          {"sweep_reference", s.sweep_reference},
          {"reference_sweep", to_json_array(s.reference_sweep)},
          {"backends", to_json_array(s.backends)}};
}

// ---------------------------------------------------------------------------
// CSV

std::string csv_row(const std::vector<std::string>& fields) {
  std::string row;
  for (const std::string& field : fields) row += (row.empty() ? "" : ",") + csv_field(field);
  return row + "\n";
}

// Full precision; non-finite values as inf / nan, which spreadsheets and
// float() parsers read back.
std::string csv_number(double value) { return formatted("%.9g", value); }

std::vector<std::string> backend_row(const SceneResult& scene, const BackendResult& b) {
  const Metrics& m = b.metrics;
  const std::string top = b.attribution.empty() ? "" : attribution_text(b.attribution.front());
  return {scene.name,
          b.backend,
          b.status,
          std::to_string(scene.image.width),
          std::to_string(scene.image.height),
          std::to_string(scene.image.spp),
          csv_number(b.render_ms),
          csv_number(b.compile_ms),
          csv_number(m.mean_error),
          csv_number(m.rms_error),
          csv_number(m.psnr),
          csv_number(m.max_error),
          std::to_string(m.pixels),
          std::to_string(m.pixels_over),
          std::to_string(m.stable_pixels),
          std::to_string(m.stable_over),
          std::to_string(m.edge_pixels),
          std::to_string(m.edge_over),
          std::to_string(m.nonfinite),
          top};
}

std::string sweep_rows(const std::string& scene, const std::string& backend, const std::vector<SweepPoint>& sweep) {
  std::string rows;
  for (const SweepPoint& p : sweep)
    rows += csv_row({scene, backend, std::to_string(p.spp), csv_number(p.render_ms), csv_number(p.rms_error),
                     csv_number(p.mean_error)});
  return rows;
}

// ---------------------------------------------------------------------------
// HTML: text and numbers

std::string html(std::string_view text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&#39;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string non_finite_text(double value) {
  if (std::isnan(value)) return "NaN";
  return value > 0 ? "∞" : "−∞";
}

std::string ms_text(double ms) {
  if (!std::isfinite(ms)) return non_finite_text(ms);
  if (ms >= 10000) return formatted("%.1f s", ms / 1000);
  if (ms >= 100) return formatted("%.0f ms", ms);
  if (ms >= 10) return formatted("%.1f ms", ms);
  return formatted("%.2f ms", ms);
}

std::string error_text(double error) {
  return std::isfinite(error) ? formatted("%.3g", error) : non_finite_text(error);
}

std::string psnr_text(double psnr) {
  return std::isfinite(psnr) ? formatted("%.1f dB", psnr) : non_finite_text(psnr) + " dB";
}

std::string share_text(long part, long whole) { return whole > 0 ? percent_text(double(part) / double(whole)) : "—"; }

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return text;
}

// The status as a coloured label; its class picks the colour in the style sheet.
std::string status_badge(const std::string& status) {
  return "<span class=\"status " + html(status) + "\">" + html(upper(status)) + "</span>";
}

// ---------------------------------------------------------------------------
// HTML: images

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string encoded;
  encoded.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t count = std::min<size_t>(3, bytes.size() - i);
    uint32_t group = 0;
    for (size_t k = 0; k < 3; ++k) group = group << 8 | (k < count ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) encoded += k <= count ? kDigits[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return encoded;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw RuntimeError("cannot read " + file.string());
  return bytes;
}

// Removes a temporary file however the scope is left.
struct TemporaryFile {
  fs::path path;
  ~TemporaryFile() {
    std::error_code ignored;
    fs::remove(path, ignored);
  }
};

fs::path temporary_png() {
  static std::atomic<unsigned> counter{0};
  return fs::temp_directory_path() /
         ("prism-report-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".png");
}

// The image as a PNG data URI, encoded by the same writer as `prism render`
// so the report shows exactly what a PNG output would.
std::string png_data_uri(const Image& image) {
  const TemporaryFile png{temporary_png()};
  write_image(image, png.path);
  return "data:image/png;base64," + base64(read_bytes(png.path));
}

// Small images are blown up further so that single pixels can be told apart;
// integer factors keep every pixel the same size.
int display_scale(const ImageSettings& settings) { return std::max(2, 320 / std::max(1, settings.width)); }

struct DisplaySize {
  int width = 0, height = 0;
};

DisplaySize display_size(const ImageSettings& settings) {
  const int scale = display_scale(settings);
  return {settings.width * scale, settings.height * scale};
}

// Backends without an image get a narrow card, so that they do not push the
// images of the others onto another row.
constexpr int kCardWidth = 180;

std::string image_tag(const Image& image, const ImageSettings& settings, const std::string& alt) {
  const DisplaySize size = display_size(settings);
  return "<img src=\"" + png_data_uri(image) + "\"" +
         formatted(" width=\"%d\" height=\"%d\"", size.width, size.height) + " alt=\"" + html(alt) + "\">";
}

// A box of the given size in place of an image, so the gallery's rows stay aligned.
std::string box(const std::string& css_class, DisplaySize size, const std::string& content) {
  return formatted("<div class=\"%s\" style=\"width:%dpx;height:%dpx\">", css_class.c_str(), size.width, size.height) +
         content + "</div>";
}

std::string placeholder(DisplaySize size, const std::string& text) { return box("placeholder", size, html(text)); }

std::string figure(const std::string& content, const std::string& caption) {
  return "<figure>" + content + "<figcaption>" + caption + "</figcaption></figure>\n";
}

// ---------------------------------------------------------------------------
// HTML: the page

constexpr const char* kStyle = R"(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: #1f2328; background: #fff;
       margin: 0 auto; padding: 20px 24px; max-width: 1800px; }
h1 { font-size: 24px; margin: 0 0 8px; }
h2 { font-size: 19px; margin: 0 0 6px; }
h3 { font-size: 15px; margin: 18px 0 6px; }
header, section { border-bottom: 1px solid #d0d7de; padding-bottom: 20px; margin-bottom: 24px; }
.meta { color: #57606a; margin: 2px 0; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; margin: 8px 0; }
th, td { border: 1px solid #d0d7de; padding: 4px 8px; text-align: right; white-space: nowrap; }
th { background: #f6f8fa; font-weight: 600; }
td:first-child, th.text, td.text, td.device { text-align: left; }
td.device { white-space: normal; min-width: 120px; max-width: 240px; }
tr:nth-child(even) td { background: #fbfcfd; }
.detail { color: #57606a; font-size: 12px; }
td.over { color: #cf222e; font-weight: 600; }
.status { display: inline-block; min-width: 58px; padding: 1px 6px; border-radius: 4px; color: #fff;
          font-weight: 700; font-size: 12px; text-align: center; letter-spacing: 0.03em; }
.status.pass { background: #1a7f37; }
.status.fail { background: #d1001f; }
.status.error { background: #bc4c00; }
.status.skipped { background: #6e7781; }
.status.reference { background: #0969da; }
h1 .status { font-size: 18px; padding: 2px 10px; vertical-align: 2px; }
.gallery { display: flex; flex-wrap: wrap; gap: 18px; margin: 12px 0; }
.column figure + figure { margin-top: 10px; }
figure { margin: 0; }
figure img, .placeholder, .legend { display: block; border: 1px solid #d0d7de; box-sizing: border-box; }
img { image-rendering: pixelated; }
figcaption { margin-top: 4px; font-size: 13px; }
.placeholder { display: flex; align-items: center; justify-content: center; text-align: center; padding: 0 12px;
               background: repeating-linear-gradient(45deg, #f6f8fa 0 10px, #eef1f4 10px 20px); color: #57606a; }
.legend { display: flex; flex-direction: column; justify-content: center; gap: 10px; padding: 12px 16px;
          font-size: 13px; color: #57606a; background: #f6f8fa; }
.legend b { color: #1f2328; }
.legend-bar { height: 14px; border: 1px solid #d0d7de;
              background: linear-gradient(to right, #000 0%, #09f 76.9%, #f00 76.9%, #ff0 88.4%, #fff 100%); }
.legend-stops { position: relative; height: 3em; margin: -6px 8px 0; font-size: 11px; }
.legend-stops span { position: absolute; transform: translateX(-50%); text-align: center; white-space: nowrap; }
details > summary { cursor: pointer; list-style-position: outside; }
details > summary h2 { display: inline; }
p.fastest { font-size: 16px; margin: 10px 0; }
.swatch { display: inline-block; width: 12px; height: 12px; vertical-align: -2px; border: 1px solid #d0d7de; }
ul { margin: 4px 0; padding-left: 20px; }
li { margin: 3px 0; }
svg.chart { display: block; background: #fff; border: 1px solid #d0d7de; margin: 8px 0; }
svg.chart text { font: 12px system-ui, sans-serif; fill: #1f2328; }
svg.chart .grid { stroke: #eaeef2; }
svg.chart .axis { stroke: #57606a; }
svg.chart text.spp { font-size: 10px; fill: #57606a; }
)";

// Tells a browser test (chromium --dump-dom) that the inline images decoded
// and the charts are there.
constexpr const char* kScript = R"(
<script>
window.addEventListener('load', () => {
  document.body.dataset.imagesLoaded = Array.from(document.images).filter(i => i.naturalWidth > 0).length;
  document.body.dataset.charts = document.querySelectorAll('svg.chart').length;
  const fastest = document.getElementById('fastest');
  document.body.dataset.fastest = fastest ? fastest.innerText : '';
});
</script>
)";

constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
constexpr const char* kReferenceColour = "#24292f";

// One colour per backend name, the same in every scene's chart.
class Palette {
 public:
  explicit Palette(std::vector<std::string> names) : names_(std::move(names)) {}
  std::string colour(const std::string& backend) const {
    const auto found = std::find(names_.begin(), names_.end(), backend);
    const size_t index = size_t(found - names_.begin());
    return found == names_.end() ? kReferenceColour : kPalette[index % std::size(kPalette)];
  }

 private:
  std::vector<std::string> names_;
};

std::string caps_text(const Caps& caps) {
  return formatted("a pixel is over when any channel differs by more than %g; at most ",
                   float_as_decimal(caps.threshold)) +
         percent_text(caps.stable_over_gpu) + " of stable pixels over (float backends), " +
         percent_text(caps.stable_over_double) + " (double-precision backends); at most " +
         percent_text(caps.all_over) + " of all pixels over";
}

std::string page_header(const RunResult& run, size_t backend_count) {
  return "<header><h1>Prism conformance " + status_badge(run.passed() ? "pass" : "fail") + "</h1>\n" +
         "<p class=\"meta\">Started " + html(run.started) + " · wall time " + ms_text(run.wall_ms) + " · " +
         std::to_string(run.scenes.size()) + " scenes × " + std::to_string(backend_count) +
         " backends</p>\n<p class=\"meta\">Caps: " + html(caps_text(run.caps)) + "</p></header>\n";
}

const BackendResult* find_backend(const SceneResult& scene, const std::string& name) {
  for (const BackendResult& backend : scene.backends)
    if (backend.backend == name) return &backend;
  return nullptr;
}

// A scene's heading and link text; a nameless scene still gets a visible link.
std::string scene_title(const SceneResult& scene) { return scene.name.empty() ? "(unnamed scene)" : scene.name; }

std::string scene_anchor(size_t index) { return "scene-" + std::to_string(index); }

// Only "pass" and "fail" were compared with the reference; the metrics of a
// skipped or errored backend are empty, not zero.
bool compared(const BackendResult& b) { return b.status == "pass" || b.status == "fail"; }

std::string error_and_time(const BackendResult& b) {
  return "RMS " + error_text(b.metrics.rms_error) + " · " + ms_text(b.render_ms);
}

std::string summary_cell(const BackendResult* b) {
  if (!b) return "<td class=\"text\">—</td>";
  return "<td class=\"text\" title=\"" + html(b->reason) + "\">" + status_badge(b->status) +
         (compared(*b) ? " <span class=\"detail\">" + error_and_time(*b) + "</span>" : "") + "</td>";
}

std::string summary_table(const RunResult& run, const std::vector<std::string>& names) {
  std::string table =
      "<section><h2>Summary</h2>\n<div class=\"scroll\"><table><tr><th class=\"text\">scene</th>"
      "<th>reference time</th>";
  for (const std::string& name : names) table += "<th class=\"text\">" + html(name) + "</th>";
  table += "</tr>\n";
  for (size_t i = 0; i < run.scenes.size(); ++i) {
    const SceneResult& scene = run.scenes[i];
    table += "<tr><td><a href=\"#" + scene_anchor(i) + "\">" + html(scene_title(scene)) + "</a></td><td>" +
             ms_text(scene.reference_ms) + "</td>";
    for (const std::string& name : names) table += summary_cell(find_backend(scene, name));
    table += "</tr>\n";
  }
  return table + "</table></div></section>\n";
}

std::string speedup_text(double speedup) {
  if (!(speedup > 0)) return "—";
  return formatted(speedup >= 10 ? "%.0f×" : "%.2g×", speedup);
}

std::string scene_counts_text(const BackendSummary& s) {
  std::string text = std::to_string(s.passed) + " pass";
  if (s.failed) text += ", " + std::to_string(s.failed) + " fail";
  if (s.errors) text += ", " + std::to_string(s.errors) + " error";
  if (s.skipped) text += ", " + std::to_string(s.skipped) + " skipped";
  return text;
}

std::string backend_summary_row(const BackendSummary& s) {
  const bool measured = s.compared > 0;
  const std::string status = s.passes() ? "pass" : measured ? "fail" : "skipped";
  auto cell = [&](const std::string& text) { return "<td>" + (measured ? text : "—") + "</td>"; };
  return "<tr><td>" + html(s.backend) + "</td><td class=\"text\">" + status_badge(status) + " " +
         html(scene_counts_text(s)) + "</td><td>" + speedup_text(s.speedup) + "</td>" +
         cell(error_text(s.worst_max_error)) + cell(error_text(s.worst_rms_error)) + cell(ms_text(s.compile_ms)) +
         cell(ms_text(s.first_frame_ms)) + "</tr>\n";
}

// Per backend over every scene, and the fastest one that passed them all.
std::string backend_summary(const RunResult& run) {
  const std::vector<BackendSummary> summaries = summarize(run);
  std::string table =
      "<section><h2>Backends</h2>\n<p class=\"fastest\" id=\"fastest\">" + html(fastest_line(summaries)) +
      "</p>\n<div class=\"scroll\"><table><tr><th class=\"text\">backend</th><th class=\"text\">scenes</th>"
      "<th title=\"geometric mean over the scenes of reference time / render time\">speed vs reference</th>"
      "<th>worst max error</th><th>worst RMS error</th><th>compile (total)</th>"
      "<th title=\"prepare + compile + render, mean over the scenes\">first frame (mean)</th></tr>\n";
  for (const BackendSummary& s : summaries) table += backend_summary_row(s);
  return table + "</table></div></section>\n";
}

std::string settings_text(const ImageSettings& settings) {
  return formatted("%d×%d, %d spp, max depth %d", settings.width, settings.height, settings.spp, settings.max_depth);
}

// Where the heat maps sit in the backends' columns, the reference's column
// explains their colours.
std::string heat_map_legend(const ImageSettings& settings, float threshold) {
  const double t = float_as_decimal(threshold);
  auto stop = [&](double scale, const std::string& text) {
    return formatted("<span style=\"left:%.1f%%\">", 100 * legend_position(scale)) + text + "</span>";
  };
  const std::string stops = stop(kFloorScale, "≤ " + formatted("%.2g", t * kFloorScale)) +
                            stop(1e-2, formatted("%.2g", t * 1e-2)) + stop(1e-1, formatted("%.2g", t * 1e-1)) +
                            stop(1, formatted("%g", t) + "<br>threshold") +
                            stop(kWhiteScale, "≥ " + formatted("%.3g", t * kWhiteScale));
  return box("legend", display_size(settings),
             "<div><b>Difference heat maps</b><br>max over channels of |backend − reference|, log scale: "
             "blue below the threshold (a third brighter per factor of 10), red to white above</div>"
             "<div class=\"legend-bar\"></div><div class=\"legend-stops\">" +
                 stops + "</div><div><span class=\"swatch\" style=\"background:#f0f\"></span> NaN or Inf</div>");
}

std::string column(const std::string& figures) { return "<div class=\"column\">" + figures + "</div>\n"; }

std::string reference_column(const SceneResult& scene, float threshold) {
  const std::string caption = "<b>" + html(scene.reference_backend) + "</b> (reference)<br><span class=\"detail\">" +
                              ms_text(scene.reference_ms) + "</span>";
  const std::string picture = has_pixels(scene.reference)
                                  ? image_tag(scene.reference, scene.image, "reference")
                                  : placeholder(display_size(scene.image), "no reference image");
  return column(figure(picture, caption) + figure(heat_map_legend(scene.image, threshold), ""));
}

std::string backend_caption(const BackendResult& b) {
  return "<b>" + html(b.backend) + "</b> " + status_badge(b.status) +
         (compared(b) ? "<br><span class=\"detail\">" + error_and_time(b) + "</span>" : "");
}

std::string heat_map_picture(const SceneResult& scene, const BackendResult& b, float threshold) {
  if (!has_pixels(scene.reference) || !same_size(b.image, scene.reference))
    return placeholder(display_size(scene.image), "no difference image");
  return image_tag(heat_map(scene.reference, b.image, threshold), scene.image, b.backend + " difference");
}

// A backend's image above its difference from the reference, so the two line
// up with the reference image and the legend at the left of the gallery.
std::string backend_column(const SceneResult& scene, const BackendResult& b, float threshold) {
  if (!has_pixels(b.image)) {
    const DisplaySize card{kCardWidth, display_size(scene.image).height};
    return column(figure(placeholder(card, b.reason.empty() ? "no image" : b.reason), backend_caption(b)));
  }
  const std::string heat_caption = "difference · max " + error_text(b.metrics.max_error) + " · " +
                                   share_text(b.metrics.pixels_over, b.metrics.pixels) + " over · " +
                                   ms_text(b.render_ms);
  return column(figure(image_tag(b.image, scene.image, b.backend), backend_caption(b)) +
                figure(heat_map_picture(scene, b, threshold), heat_caption));
}

std::string gallery(const SceneResult& scene, float threshold) {
  std::string columns = reference_column(scene, threshold);
  for (const BackendResult& b : scene.backends) columns += backend_column(scene, b, threshold);
  return "<div class=\"gallery\">\n" + columns + "</div>\n";
}

// The cap on stable pixels over depends on the backend's shading precision.
double stable_cap(const Caps& caps, const BackendResult& b) {
  return b.precision == "double" ? caps.stable_over_double : caps.stable_over_gpu;
}

std::string share_cell(long part, long whole, double cap) {
  const bool over = whole > 0 && double(part) / double(whole) > cap;
  return std::string(over ? "<td class=\"over\">" : "<td>") + share_text(part, whole) + "</td>";
}

std::string device_text(const BackendResult& b) {
  return b.device + (b.precision.empty() ? "" : " (" + b.precision + ")");
}

constexpr int kMetricColumns = 9;  // compile time to NaN/Inf

// A row without metrics (the reference, a skipped backend): its time, if it
// has one, and a note across the metric columns.
std::string note_row(const std::string& name, const std::string& status, double ms, const std::string& note,
                     const std::string& device) {
  return "<tr><td>" + html(name) + "</td><td class=\"text\">" + status_badge(status) + "</td><td>" +
         (ms > 0 ? ms_text(ms) : "—") + formatted("</td><td colspan=\"%d\" class=\"text detail\">", kMetricColumns) +
         html(note) + "</td><td class=\"device\">" + html(device) + "</td></tr>\n";
}

std::string metrics_row(const BackendResult& b, const Caps& caps) {
  if (!compared(b)) return note_row(b.backend, b.status, b.render_ms, b.reason, device_text(b));
  const Metrics& m = b.metrics;
  return "<tr><td>" + html(b.backend) + "</td><td class=\"text\">" + status_badge(b.status) + "</td><td>" +
         ms_text(b.render_ms) + "</td><td>" + ms_text(b.compile_ms) + "</td><td>" + error_text(m.mean_error) +
         "</td><td>" + error_text(m.rms_error) + "</td><td>" + psnr_text(m.psnr) + "</td><td>" +
         error_text(m.max_error) + "</td>" + share_cell(m.pixels_over, m.pixels, caps.all_over) +
         share_cell(m.stable_over, m.stable_pixels, stable_cap(caps, b)) + share_cell(m.edge_over, m.edge_pixels, 1.0) +
         (m.nonfinite > 0 ? "<td class=\"over\">" : "<td>") + std::to_string(m.nonfinite) +
         "</td><td class=\"device\">" + html(device_text(b)) + "</td></tr>\n";
}

std::string metrics_table(const SceneResult& scene, const Caps& caps) {
  std::string table =
      "<h3>Metrics</h3>\n<div class=\"scroll\"><table><tr><th class=\"text\">backend</th><th "
      "class=\"text\">status</th><th>render</th>"
      "<th>compile</th><th>mean</th><th>RMS</th><th>PSNR</th><th>max error</th><th>% pixels over</th>"
      "<th>% stable over</th><th>% edge over</th><th>NaN/Inf</th><th class=\"text\">device</th></tr>\n";
  table += note_row(scene.reference_backend, "reference", scene.reference_ms,
                    "the image every backend is compared with", "");
  for (const BackendResult& b : scene.backends) table += metrics_row(b, caps);
  return table + "</table></div>\n";
}

std::string attribution_list(const SceneResult& scene) {
  std::string items;
  for (const BackendResult& b : scene.backends) {
    if (b.attribution.empty()) continue;
    std::string parts;
    for (const Attribution& a : b.attribution)
      parts += (parts.empty() ? "" : ", ") + html(attribution_text(a)) +
               formatted(" <span class=\"detail\">(%ld px)</span>", a.pixels);
    items += "<li><b>" + html(b.backend) + "</b>: " + parts + "</li>\n";
  }
  return items.empty() ? "" : "<h3>Over-threshold pixels by object</h3>\n<ul>\n" + items + "</ul>\n";
}

std::string reason_list(const SceneResult& scene) {
  std::string items;
  for (const BackendResult& b : scene.backends)
    if (!b.reason.empty())
      items += "<li><b>" + html(b.backend) + "</b> " + status_badge(b.status) + " " + html(b.reason) + "</li>\n";
  return items.empty() ? "" : "<h3>Notes</h3>\n<ul>\n" + items + "</ul>\n";
}

// ---------------------------------------------------------------------------
// HTML: the error-vs-time chart

struct Series {
  std::string name;
  std::string colour;
  std::vector<SweepPoint> points;  // by spp
};

std::vector<Series> chart_series(const SceneResult& scene, const Palette& palette) {
  std::vector<Series> series;
  if (!scene.reference_sweep.empty())
    series.push_back({scene.reference_backend, kReferenceColour, scene.reference_sweep});
  for (const BackendResult& b : scene.backends)
    if (!b.sweep.empty()) series.push_back({b.backend, palette.colour(b.backend), b.sweep});
  for (Series& s : series)
    std::sort(s.points.begin(), s.points.end(), [](const SweepPoint& a, const SweepPoint& b) { return a.spp < b.spp; });
  return series;
}

bool drawable_on_log_axis(double value) { return std::isfinite(value) && value > 0; }

// A log10 axis over whole decades, mapped onto [from, to] pixels. Zero,
// negative and non-finite values cannot sit on a log axis; they are drawn at
// `floor`, a decade below the smallest value that can, instead of being dropped.
struct LogAxis {
  int low = 0, high = 1;  // decade exponents
  double from = 0, to = 1;
  double floor = 1;

  double position(double value) const {
    const double drawn = drawable_on_log_axis(value) ? value : floor;
    return from + (std::log10(drawn) - low) / double(high - low) * (to - from);
  }
};

// `fallback_floor` is the floor when no value at all can be drawn.
LogAxis log_axis(const std::vector<double>& values, double from, double to, double fallback_floor) {
  double lowest = std::numeric_limits<double>::infinity(), highest = 0;
  for (double v : values)
    if (drawable_on_log_axis(v)) lowest = std::min(lowest, v), highest = std::max(highest, v);
  const double floor = highest > 0 ? lowest / 10 : fallback_floor;
  if (!std::all_of(values.begin(), values.end(), drawable_on_log_axis)) lowest = floor;
  if (highest <= 0) highest = floor;
  LogAxis axis{int(std::floor(std::log10(lowest))), int(std::ceil(std::log10(highest))), from, to, floor};
  if (axis.high == axis.low) ++axis.high;  // a single point, or values on one power of ten
  return axis;
}

constexpr double kFallbackTimeFloorMs = 1e-3;
constexpr double kFallbackErrorFloor = 1e-6;

std::vector<double> series_values(const std::vector<Series>& series, double SweepPoint::*field) {
  std::vector<double> values;
  for (const Series& s : series)
    for (const SweepPoint& p : s.points) values.push_back(p.*field);
  return values;
}

struct ChartFrame {
  static constexpr double kWidth = 760, kHeight = 420;
  static constexpr double kLeft = 72, kRight = 170, kTop = 16, kBottom = 52;
  LogAxis x, y;
};

std::string decade_label(int exponent) { return formatted("%g", std::pow(10.0, exponent)); }

std::string chart_axes(const ChartFrame& f) {
  std::string svg;
  const double x0 = f.x.from, x1 = f.x.to, y0 = f.y.from, y1 = f.y.to;
  for (int e = f.x.low; e <= f.x.high; ++e) {
    const double x = f.x.position(std::pow(10.0, e));
    svg += formatted("<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>", x, y0, x, y1) +
           formatted("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", x, y0 + 18) + decade_label(e) + "</text>\n";
  }
  for (int e = f.y.low; e <= f.y.high; ++e) {
    const double y = f.y.position(std::pow(10.0, e));
    svg += formatted("<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>", x0, y, x1, y) +
           formatted("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">", x0 - 6, y + 4) + decade_label(e) + "</text>\n";
  }
  svg += formatted("<polyline class=\"axis\" fill=\"none\" points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\"/>\n", x0, y1, x0,
                   y0, x1, y0);
  svg += formatted("<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">render time (ms, log scale)</text>\n",
                   (x0 + x1) / 2, y0 + 40);
  svg += formatted(
      "<text transform=\"translate(16 %.1f) rotate(-90)\" text-anchor=\"middle\">RMS error (log scale)</text>\n",
      (y0 + y1) / 2);
  return svg;
}

// One sweep point: a marker with a tooltip, labelled with its spp. Hollow when
// the point sits at an axis floor rather than where its value is.
std::string chart_marker(const Series& s, const SweepPoint& p, double x, double y) {
  const bool at_floor = !drawable_on_log_axis(p.render_ms) || !drawable_on_log_axis(p.rms_error);
  const std::string tooltip = s.name + formatted(": %d spp, ", p.spp) + ms_text(p.render_ms) + ", RMS " +
                              error_text(p.rms_error) + (at_floor ? " (not positive: drawn at the axis floor)" : "");
  return formatted("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" stroke-width=\"1.5\" stroke=\"%s\" fill=\"%s\">", x, y,
                   s.colour.c_str(), at_floor ? "#fff" : s.colour.c_str()) +
         "<title>" + html(tooltip) + "</title></circle>" +
         formatted("<text class=\"spp\" x=\"%.1f\" y=\"%.1f\">%d</text>\n", x + 6, y - 6, p.spp);
}

std::string chart_series_svg(const Series& s, const ChartFrame& f) {
  std::string line, markers;
  for (const SweepPoint& p : s.points) {
    const double x = f.x.position(p.render_ms), y = f.y.position(p.rms_error);
    line += formatted("%.1f,%.1f ", x, y);
    markers += chart_marker(s, p, x, y);
  }
  return "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" + s.colour + "\" points=\"" + line + "\"/>\n" + markers;
}

std::string chart_legend(const std::vector<Series>& series, const ChartFrame& f) {
  std::string svg;
  const double x = f.x.to + 20;
  for (size_t i = 0; i < series.size(); ++i) {
    const double y = f.y.to + 10 + 20.0 * double(i);
    svg += formatted("<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke-width=\"2\" stroke=\"%s\"/>", x, y,
                     x + 22, y, series[i].colour.c_str()) +
           formatted("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"/>", x + 11, y, series[i].colour.c_str()) +
           formatted("<text x=\"%.1f\" y=\"%.1f\">", x + 30, y + 4) + html(series[i].name) + "</text>\n";
  }
  return svg + formatted("<text class=\"spp\" x=\"%.1f\" y=\"%.1f\">labels: samples per pixel</text>\n", x,
                         f.y.to + 14 + 20.0 * double(series.size()));
}

std::string error_time_chart(const SceneResult& scene, const Palette& palette) {
  const std::vector<Series> series = chart_series(scene, palette);
  const std::string against =
      scene.sweep_reference.empty() ? "" : "<p class=\"meta\">Errors against " + html(scene.sweep_reference) + "</p>\n";
  if (series.empty()) return against.empty() ? "" : "<h3>Error vs time</h3>\n" + against;
  using F = ChartFrame;
  const ChartFrame frame{
      log_axis(series_values(series, &SweepPoint::render_ms), F::kLeft, F::kWidth - F::kRight, kFallbackTimeFloorMs),
      log_axis(series_values(series, &SweepPoint::rms_error), F::kHeight - F::kBottom, F::kTop, kFallbackErrorFloor)};
  std::string svg =
      formatted("<svg class=\"chart\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" role=\"img\">",
                F::kWidth, F::kHeight, F::kWidth, F::kHeight);
  svg += "<title>RMS error against render time: " + html(scene_title(scene)) + "</title>\n" + chart_axes(frame);
  for (const Series& s : series) svg += chart_series_svg(s, frame);
  return "<h3>Error vs time</h3>\n" + svg + chart_legend(series, frame) + "</svg>\n" + against;
}

// A scene where a backend failed or errored: its section starts open.
bool has_failure(const SceneResult& scene) {
  for (const BackendResult& b : scene.backends)
    if (b.status == "fail" || b.status == "error") return true;
  return false;
}

// Collapsed (<details>) when every backend passed or was skipped, open otherwise.
std::string scene_section(const SceneResult& scene, size_t index, const Caps& caps, const Palette& palette) {
  const bool failed = has_failure(scene);
  return "<section id=\"" + scene_anchor(index) + "\"><details" + (failed ? " open" : "") + "><summary><h2>" +
         html(scene_title(scene)) + "</h2> " + status_badge(failed ? "fail" : "pass") +
         "</summary>\n<p class=\"meta\">" +
         html(settings_text(scene.image)) + (scene.file.empty() ? "" : " · " + html(scene.file.string())) + "</p>\n" +
         gallery(scene, caps.threshold) + metrics_table(scene, caps) + attribution_list(scene) + reason_list(scene) +
         error_time_chart(scene, palette) + "</details></section>\n";
}

// The stability suite's table and chart, as its runner wrote them.
std::string stability_section(const StabilityResults& results) {
  std::string table = "<table class=\"metrics\">\n";
  for (size_t r = 0; r < results.rows.size(); ++r) {
    const char* cell = r == 0 ? "th" : "td";
    table += "<tr>";
    for (const std::string& field : results.rows[r]) table += std::string("<") + cell + ">" + html(field) + "</" + cell + ">";
    table += "</tr>\n";
  }
  table += "</table>\n";
  const size_t svg = results.chart_svg.find("<svg");
  return "<section id=\"stability\"><h2>Numerical stability</h2>\n<p class=\"meta\">" +
         html("Every intersector against a quad-precision oracle, error beside time per ray (" +
              results.source.string() + ")") +
         "</p>\n" + (svg == std::string::npos ? "" : results.chart_svg.substr(svg)) + table + "</section>\n";
}

std::string report_html(const RunResult& run) {
  const std::vector<std::string> names = backend_names(run);
  const Palette palette(names);
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>Prism conformance report</title>\n<style>" +
      std::string(kStyle) + "</style></head>\n<body>\n";
  page += page_header(run, names.size()) + backend_summary(run) + summary_table(run, names);
  for (size_t i = 0; i < run.scenes.size(); ++i) page += scene_section(run.scenes[i], i, run.caps, palette);
  if (run.stability) page += stability_section(*run.stability);
  return page + kScript + "</body></html>\n";
}

}  // namespace

Image heat_map(const Image& reference, const Image& image, float threshold) {
  if (!same_size(reference, image) || !has_pixels(reference) || !has_pixels(image))
    throw std::invalid_argument("heat_map: the images must have pixels and the same size");
  Image map;
  map.width = image.width;
  map.height = image.height;
  map.rgb.assign(image.rgb.size(), 0.0f);
  for (size_t p = 0; p < map.rgb.size(); p += 3) {
    // The ramp is designed in display colours; the PNG writer encodes linear
    // values to sRGB, so decode here to land on the designed colours.
    const Rgb colour = heat_colour(pixel_difference(&reference.rgb[p], &image.rgb[p]), threshold);
    map.rgb[p + 0] = float(srgb_to_linear(colour.r));
    map.rgb[p + 1] = float(srgb_to_linear(colour.g));
    map.rgb[p + 2] = float(srgb_to_linear(colour.b));
  }
  return map;
}

void write_results_json(const RunResult& run, const fs::path& file) {
  Json scenes = Json::array();
  for (const SceneResult& scene : run.scenes) scenes.push_back(to_json(scene));
  const std::vector<BackendSummary> summaries = summarize(run);
  Json backends = Json::array();
  for (const BackendSummary& s : summaries) backends.push_back(to_json(s));
  const std::string fastest = fastest_passing(summaries);
  const Json root = {{"started", run.started},
                     {"wall_ms", number(run.wall_ms)},
                     {"passed", run.passed()},
                     {"caps", to_json(run.caps)},
                     {"fastest_passing", fastest.empty() ? Json(nullptr) : Json(fastest)},
                     {"backends", std::move(backends)},
                     {"scenes", std::move(scenes)}};
  write_text_file_atomically(file, root.dump(2) + "\n");
}

// The sweep points go to a second file beside `file` (results.csv ->
// results_sweep.csv): one table per file keeps both loadable by any CSV reader.
void write_results_csv(const RunResult& run, const fs::path& file) {
  std::string results = csv_row({"scene",       "backend",     "status",     "width",       "height",
                                 "spp",         "render_ms",   "compile_ms", "mean_error",  "rms_error",
                                 "psnr",        "max_error",   "pixels",     "pixels_over", "stable_pixels",
                                 "stable_over", "edge_pixels", "edge_over",  "nonfinite",   "top_attribution"});
  std::string sweep = csv_row({"scene", "backend", "spp", "render_ms", "rms_error", "mean_error"});
  for (const SceneResult& scene : run.scenes) {
    sweep += sweep_rows(scene.name, scene.reference_backend, scene.reference_sweep);
    for (const BackendResult& b : scene.backends) {
      results += csv_row(backend_row(scene, b));
      sweep += sweep_rows(scene.name, b.backend, b.sweep);
    }
  }
  write_text_file_atomically(file, results);
  // Written even when empty, so a stale file from an earlier run never survives.
  write_text_file_atomically(file.parent_path() / (file.stem().string() + "_sweep.csv"), sweep);
}

StabilityResults read_stability_results(const fs::path& dir) {
  StabilityResults results;
  results.source = dir;
  for (const char* name : {"stability.csv", "stability.svg"})
    if (!fs::exists(dir / name)) throw InputError("--stability: no " + (dir / name).string() + " (prism_stability --out writes it)");
  std::istringstream csv(read_bytes(dir / "stability.csv"));
  for (std::string line; std::getline(csv, line);)
    if (!line.empty()) results.rows.push_back(csv_fields(line));
  results.chart_svg = read_bytes(dir / "stability.svg");
  return results;
}

void write_report(const RunResult& run, const fs::path& dir) {
  fs::create_directories(dir);
  write_results_json(run, dir / "results.json");
  write_results_csv(run, dir / "results.csv");
  write_text_file_atomically(dir / "index.html", report_html(run));
}

}  // namespace prism::conform
