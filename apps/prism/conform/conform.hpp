// `prism conform`: every backend's image of a scene against the reference
// backend's at the same settings, with error beside run time.
//
// Pixels are split by the reference image's `path` AOV (sample 0's path
// signature): a pixel is *stable* when its 3x3 neighbourhood shares one
// signature, an *edge* otherwise (silhouettes, shadow edges, reflected
// edges). The backend under test never classifies its own pixels.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "prism/backend.hpp"
#include "prism/conform_metrics.hpp"
#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism::conform {

// The pass/fail caps. They may be tightened, never loosened.
struct Caps {
  float threshold = 0.016f;                // a pixel is over when any channel differs by more
  double stable_over_gpu = 0.0005;         // fraction of stable pixels over: float-shading backends
  double stable_over_double = 0.0;         // ... backends whose info.precision is "double"
  double all_over = 0.005;                 // fraction of all pixels over, any backend
};

// Over-threshold pixels attributed to an object: the share of them whose
// 3x3 neighbourhood in the reference `id` AOV contains the object.
struct Attribution {
  int object_id = -1;      // -1: background only (no object in the neighbourhood)
  std::string label;       // "torus (object 3)", "background", "light 0"
  long pixels = 0;
  double fraction = 0;     // of the over-threshold pixels
};

// One point of an error-vs-time curve: error against the stored high-spp
// reference image.
struct SweepPoint {
  int spp = 1;
  double render_ms = 0;
  double rms_error = 0;
  double mean_error = 0;
};

struct BackendResult {
  std::string backend;
  std::string status;  // "pass", "fail", "skipped", "error"
  std::string reason;  // why skipped / error / what failed
  std::string device;  // info.device or the probe's description
  std::string precision;
  double render_ms = 0;   // the render alone (the backend's compile time subtracted)
  double compile_ms = 0;  // kernel compile (GPU backends), 0 otherwise
  double prepare_ms = 0;  // prepare(scene): acceleration structure, upload
  // What a user waits for before the first image: prepare, compile, render.
  double first_frame_ms() const { return prepare_ms + compile_ms + render_ms; }
  Metrics metrics;
  std::vector<Attribution> attribution;  // most pixels first
  std::vector<SweepPoint> sweep;         // with --sweep
  Image image;                            // the backend's rendering (empty when skipped)
};

struct SceneResult {
  std::string name;  // file stem
  std::filesystem::path file;
  ImageSettings image;            // as rendered
  std::string reference_backend;  // "reference"
  double reference_ms = 0;
  Image reference;  // rgb, id and path AOVs
  std::vector<uint8_t> stable;    // per pixel: 1 stable, 0 edge
  std::vector<BackendResult> backends;
  std::vector<SweepPoint> reference_sweep;  // the reference backend's own curve (--sweep)
  std::string sweep_reference;              // the stored high-spp EXR, or why there is none
};

// The stability suite's results (tests/stability: `prism_stability --out
// DIR` writes stability.csv and stability.svg), shown in the report.
struct StabilityResults {
  std::filesystem::path source;                // the folder they were read from
  std::vector<std::vector<std::string>> rows;  // stability.csv, the header first
  std::string chart_svg;                       // stability.svg: error against ns per ray
};
// Reads DIR/stability.csv and DIR/stability.svg; InputError when missing.
StabilityResults read_stability_results(const std::filesystem::path& dir);

struct RunResult {
  std::vector<SceneResult> scenes;
  std::optional<StabilityResults> stability;
  Caps caps;
  double wall_ms = 0;
  std::string started;  // ISO 8601 UTC
  bool passed() const;  // no backend failed or errored (skips do not fail; required ones are "fail")
};

struct Options {
  std::vector<std::filesystem::path> scenes;  // scene files (folders: every *.json in them)
  std::vector<std::string> backends;          // empty: every backend found but the reference
  std::vector<std::string> required;          // PRISM_REQUIRE_BACKENDS: cannot-run is a failure
  bool sweep = false;
  int sweep_max_spp = 16;                     // the sweep renders spp 1, 2, 4, ... up to this
  std::optional<std::pair<int, int>> size;    // --size: width and height in place of the scenes' own
  std::filesystem::path references;           // folder of the stored high-spp <scene>.exr images
  Caps caps;
  Precision precision = Precision::automatic; // --precision of the backends tested (the reference: double)
};

// One backend over the whole run, for the top of the report.
struct BackendSummary {
  std::string backend;
  int passed = 0, failed = 0, errors = 0, skipped = 0;  // scenes by status
  int compared = 0;           // scenes it was measured on (passed + failed)
  double speedup = 0;         // geometric mean over them of reference time / render time; 0: not measured
  double worst_max_error = 0; // the largest per-pixel error in any of them
  double worst_rms_error = 0;
  double compile_ms = 0;      // summed over the scenes
  double first_frame_ms = 0;  // mean over the scenes of prepare + compile + render
  // Passed every scene it ran on, and ran on at least one.
  bool passes() const { return passed > 0 && failed == 0 && errors == 0; }
};

// Per backend, in the order the run first met them.
std::vector<BackendSummary> summarize(const RunResult& run);
// The passing backend with the largest speedup; empty when none passes.
std::string fastest_passing(const std::vector<BackendSummary>& summaries);
// "fastest backend that passes here: NAME" (or "none"), as the console and the report say it.
std::string fastest_line(const std::vector<BackendSummary>& summaries);

// "WxH" (e.g. 320x180), each side 1..16384; InputError naming --size otherwise.
std::pair<int, int> parse_size(const std::string& text);

// Runs every scene through the reference backend and every backend asked
// for; `log` gets one line per scene and backend as results come in.
// InputError for a bad scene or an unknown backend name.
RunResult run_conformance(Registry& registry, const Options& options, const std::function<void(const std::string&)>& log);

// The parts of the comparison, exposed for tests (stable_pixels and measure
// are the core's, prism/conform_metrics.hpp).
std::vector<Attribution> attribute(const Scene& scene, const Image& reference, const Image& image, float threshold);
// Empty when the metrics meet the caps, else what broke them.
std::string verdict(const Metrics& m, const Caps& caps, bool double_precision);

// The report: DIR/index.html (self-contained: images inline as data URIs, the
// error-vs-time chart as inline SVG), DIR/results.json, DIR/results.csv.
// Written to temporary names and renamed when complete.
void write_report(const RunResult& run, const std::filesystem::path& dir);
void write_results_json(const RunResult& run, const std::filesystem::path& file);
void write_results_csv(const RunResult& run, const std::filesystem::path& file);

// A per-pixel heat map of |backend - reference| (max over channels), on a
// logarithmic scale: below the threshold from black (1/1000 of it or less)
// to blue, one third of the way per factor of 10; from the threshold red
// through yellow to white at 8x; NaN/Inf pixels magenta.
Image heat_map(const Image& reference, const Image& image, float threshold);

}  // namespace prism::conform
