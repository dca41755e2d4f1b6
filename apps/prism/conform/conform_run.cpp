#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <set>
#include <tuple>

#include "cli_common.hpp"
#include "conform/conform.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/image_file.hpp"
#include "prism/limits.hpp"
#include "prism/scene_loader.hpp"
#include "prism/stats_keys.hpp"

namespace prism::conform {

namespace fs = std::filesystem;

namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

// The RGB channels of a stored reference image (R, G, B by name, else the first three).
ImageFile rgb_of(const ImageFile& stored) {
  ImageFile rgb;
  rgb.width = stored.width;
  rgb.height = stored.height;
  rgb.channels = 3;
  rgb.pixels.resize(size_t(stored.width) * stored.height * 3);
  for (size_t p = 0; p < size_t(stored.width) * stored.height; ++p)
    for (int c = 0; c < 3; ++c) rgb.pixels[p * 3 + c] = stored.pixels[p * stored.channels + c];
  return rgb;
}

std::string object_label(const Scene& scene, int id) {
  if (id == -1) return "background";
  if (id <= -2) return "light " + std::to_string(-2 - id);
  if (size_t(id) < scene.objects.size())
    return std::string(scene.objects[size_t(id)].desc->type_name) + " (object " + std::to_string(id) + ")";
  return "object " + std::to_string(id);
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f %%", 100.0 * fraction);
  return text;
}

double fraction(long part, long whole) { return whole > 0 ? double(part) / double(whole) : 0.0; }

// Renders and times one frame; the backend's kernel compile time is kept apart.
struct Timed {
  Image image;
  double render_ms = 0, compile_ms = 0;
};
Timed timed_render(Backend& backend, const RenderSettings& settings) {
  auto compile_so_far = [&] {
    const BackendStats s = backend.stats();
    auto it = s.ms.find(ms_key::kCompile);
    return it == s.ms.end() ? 0.0 : it->second;
  };
  const double compile_before = compile_so_far();
  const cli::PhaseTimer timer;
  Timed t;
  t.image = backend.render(settings);
  const double wall = timer.total();
  t.compile_ms = compile_so_far() - compile_before;
  t.render_ms = std::max(0.0, wall - t.compile_ms);
  return t;
}

RenderSettings settings_for(const Scene& scene, bool with_aovs) {
  RenderSettings settings;
  settings.image = scene.image;
  settings.aov_id = with_aovs;
  settings.aov_path = with_aovs;
  return settings;
}

// Error-vs-time: renders at spp 1, 2, 4, ... and compares with the stored image.
std::vector<SweepPoint> sweep(Backend& backend, const Scene& scene, const ImageFile& truth, int max_spp) {
  std::vector<SweepPoint> points;
  for (int spp = 1; spp <= max_spp; spp *= 2) {
    RenderSettings settings = settings_for(scene, false);
    settings.image.spp = spp;
    const Timed t = timed_render(backend, settings);
    const ImageComparison c = compare_image_files(rgb_file(t.image), truth, 1.0f);
    points.push_back({spp, t.render_ms, c.rms_error, c.mean_error});
  }
  return points;
}

// A backend under test, probed once for the whole run (a GPU backend's
// probe starts a device).
struct Subject {
  std::string name;
  std::shared_ptr<const BackendPlugin> plugin;
  PrismBackendProbe probe;
};

class SceneRun {
 public:
  SceneRun(Registry& registry, const Options& options, const std::function<void(const std::string&)>& log)
      : registry_(registry), options_(options), log_(log) {}

  SceneResult run(const fs::path& file, const std::vector<Subject>& subjects) {
    Scene scene = load_scene(file, registry_);
    if (options_.size) std::tie(scene.image.width, scene.image.height) = *options_.size;
    SceneResult result;
    result.name = file.stem().string();
    result.file = file;
    result.image = scene.image;
    result.reference_backend = "reference";
    std::optional<ImageFile> truth = stored_reference(result);
    cli::BackendChoice reference = open_backend(registry_, "reference");
    reference.backend->prepare(scene);
    Timed r = timed_render(*reference.backend, settings_for(scene, true));
    result.reference = std::move(r.image);
    result.reference_ms = r.render_ms;
    result.stable = stable_pixels(result.reference);
    if (truth) result.reference_sweep = sweep(*reference.backend, scene, *truth, options_.sweep_max_spp);
    for (const Subject& subject : subjects) {
      result.backends.push_back(run_backend(scene, result, subject, truth));
      log_(line(result, result.backends.back()));
    }
    return result;
  }

 private:
  std::optional<ImageFile> stored_reference(SceneResult& result) const {
    if (!options_.sweep) return std::nullopt;
    const fs::path file = options_.references / (result.name + ".exr");
    if (!fs::exists(file)) {
      result.sweep_reference = "no stored reference " + file.string() + " (scripts/make_conformance_references.sh makes it)";
      return std::nullopt;
    }
    ImageFile stored = read_image_file(file);
    if (stored.width != result.image.width || stored.height != result.image.height || stored.channels < 3) {
      result.sweep_reference = file.string() + " does not match the scene's image size; regenerate it";
      return std::nullopt;
    }
    result.sweep_reference = file.string();
    return rgb_of(stored);
  }

  // A backend's refusal of --precision, told apart from its failures.
  struct PrecisionRefused : InputError {
    using InputError::InputError;
  };

  void set_precision(Backend& backend, const std::string& name) const {
    try {
      cli::set_backend_precision(backend, name, options_.precision);
    } catch (const InputError& e) {
      throw PrecisionRefused(e.what());
    }
  }

  bool required(const std::string& name) const {
    return std::find(options_.required.begin(), options_.required.end(), name) != options_.required.end();
  }

  BackendResult run_backend(const Scene& scene, const SceneResult& scene_result, const Subject& subject,
                            const std::optional<ImageFile>& truth) {
    BackendResult b;
    b.backend = subject.name;
    const PrismBackendProbe& probe = subject.probe;
    if (!probe.usable) {
      b.status = required(subject.name) ? "fail" : "skipped";
      b.reason = std::string("cannot run here: ") + probe.reason +
                 (required(subject.name) ? " (it is in PRISM_REQUIRE_BACKENDS)" : "");
      return b;
    }
    try {
      const std::unique_ptr<Backend> backend = start_backend(*subject.plugin, subject.name);
      set_precision(*backend, subject.name);
      const cli::PhaseTimer prepare_timer;
      backend->prepare(scene);
      b.prepare_ms = prepare_timer.total();
      Timed t = timed_render(*backend, settings_for(scene, false));
      const BackendStats stats = backend->stats();
      b.device = stats.info.count(info_key::kDevice) ? stats.info.at(info_key::kDevice) : probe.reason;
      b.precision = stats.info.count(info_key::kPrecision) ? stats.info.at(info_key::kPrecision) : "";
      b.render_ms = t.render_ms;
      b.compile_ms = t.compile_ms;
      b.image = std::move(t.image);
      judge(scene, scene_result, b);
      if (truth) b.sweep = sweep(*backend, scene, *truth, options_.sweep_max_spp);
    } catch (const Cancelled&) {
      throw;  // an interrupt ends the whole run; it is not this backend's failure
    } catch (const PrecisionRefused&) {
      throw;  // a flag the backend cannot honour is bad input (exit 2), not a failed scene
    } catch (const std::exception& e) {
      b.status = "error";
      b.reason = e.what();
    }
    return b;
  }

  void judge(const Scene& scene, const SceneResult& s, BackendResult& b) const {
    if (b.image.width != s.reference.width || b.image.height != s.reference.height) {
      b.status = "error";
      b.reason = "returned a " + std::to_string(b.image.width) + "x" + std::to_string(b.image.height) + " image";
      return;
    }
    b.metrics = measure(s.reference, s.stable, b.image, options_.caps.threshold);
    b.attribution = attribute(scene, s.reference, b.image, options_.caps.threshold);
    b.reason = verdict(b.metrics, options_.caps, b.precision == "double");
    b.status = b.reason.empty() ? "pass" : "fail";
  }

  std::string line(const SceneResult& s, const BackendResult& b) const {
    char text[512];
    if (b.status == "skipped" || b.status == "error" || b.image.rgb.empty()) {
      std::snprintf(text, sizeof text, "%-18s %-10s %s: %s", s.name.c_str(), b.backend.c_str(),
                    b.status == "skipped" ? "SKIPPED" : b.status == "error" ? "ERROR" : "FAIL", b.reason.c_str());
      return text;
    }
    const Metrics& m = b.metrics;
    std::snprintf(text, sizeof text,
                  "%-18s %-10s %-4s rms %.2e  max %.2e  over %s (stable %s, edge %s)  render %.1f ms  compile %.0f ms",
                  s.name.c_str(), b.backend.c_str(), b.status == "pass" ? "PASS" : "FAIL", m.rms_error, m.max_error,
                  percent(fraction(m.pixels_over, m.pixels)).c_str(),
                  percent(fraction(m.stable_over, m.stable_pixels)).c_str(),
                  percent(fraction(m.edge_over, m.edge_pixels)).c_str(), b.render_ms, b.compile_ms);
    std::string out = text;
    if (b.status != "pass") out += "\n    " + b.reason;
    if (b.status != "pass" && !b.attribution.empty()) {
      out += "\n    over-threshold pixels near:";
      for (size_t i = 0; i < std::min<size_t>(3, b.attribution.size()); ++i)
        out += " " + b.attribution[i].label + " " + percent(b.attribution[i].fraction) + (i + 1 < 3 ? "," : "");
    }
    return out;
  }

  Registry& registry_;
  const Options& options_;
  const std::function<void(const std::string&)>& log_;
};

std::vector<fs::path> scene_files(const std::vector<fs::path>& given) {
  std::vector<fs::path> files;
  for (const fs::path& path : given) {
    if (!fs::is_directory(path)) {
      files.push_back(path);
      continue;
    }
    std::vector<fs::path> in_folder;
    for (const auto& entry : fs::directory_iterator(path))
      if (entry.path().extension() == ".json") in_folder.push_back(entry.path());
    std::sort(in_folder.begin(), in_folder.end());
    if (in_folder.empty()) throw InputError("no scene (*.json) in " + path.string());
    files.insert(files.end(), in_folder.begin(), in_folder.end());
  }
  return files;
}

std::vector<Subject> subjects_for(Registry& registry, const Options& options) {
  std::vector<Subject> subjects;
  if (!options.backends.empty()) {
    for (const std::string& name : options.backends) {
      auto plugin = registry.backend(name);  // InputError when unknown
      subjects.push_back({name, plugin, plugin->probe()});
    }
    return subjects;
  }
  // Every backend found: each probed in a child process first, so that one
  // that crashes or exits is reported as unusable instead of ending the run.
  std::vector<std::string> names;
  for (const std::string& name : registry.backend_names_found())
    if (name != "reference") names.push_back(name);
  for (const auto& [name, probe] : registry.probe_backends(names)) {
    const PrismBackendProbe result = probe.as_probe();
    subjects.push_back({name, result.usable ? registry.backend(name) : nullptr, result});
  }
  return subjects;
}

}  // namespace

std::vector<Attribution> attribute(const Scene& scene, const Image& reference, const Image& image, float threshold) {
  std::map<int, long> counts;
  long over = 0;
  const int w = reference.width, h = reference.height;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!(pixel_error(reference, image, size_t(y) * w + x) > threshold)) continue;
      ++over;
      std::set<int> near;
      for_each_neighbour(w, h, x, y, [&](size_t q) { near.insert(reference.id.empty() ? -1 : int(reference.id[q])); });
      for (int id : near) ++counts[id];
    }
  }
  std::vector<Attribution> result;
  for (const auto& [id, n] : counts) result.push_back({id, object_label(scene, id), n, fraction(n, over)});
  std::stable_sort(result.begin(), result.end(), [](const Attribution& a, const Attribution& b) { return a.pixels > b.pixels; });
  return result;
}

std::string verdict(const Metrics& m, const Caps& caps, bool double_precision) {
  std::string why;
  auto add = [&](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  if (m.nonfinite > 0) add(std::to_string(m.nonfinite) + " NaN or Inf pixel(s)");
  const double stable_cap = double_precision ? caps.stable_over_double : caps.stable_over_gpu;
  if (fraction(m.stable_over, m.stable_pixels) > stable_cap)
    add(std::to_string(m.stable_over) + " stable pixels (" + percent(fraction(m.stable_over, m.stable_pixels)) +
        ") over " + std::to_string(caps.threshold).substr(0, 5) + ", cap " + percent(stable_cap));
  if (fraction(m.pixels_over, m.pixels) > caps.all_over)
    add(std::to_string(m.pixels_over) + " pixels (" + percent(fraction(m.pixels_over, m.pixels)) + ") over " +
        std::to_string(caps.threshold).substr(0, 5) + ", cap " + percent(caps.all_over));
  return why;
}

std::vector<BackendSummary> summarize(const RunResult& run) {
  std::vector<BackendSummary> summaries;
  std::map<std::string, double> log_speedup_sum;
  std::map<std::string, int> speedups;
  auto summary_of = [&](const std::string& name) -> BackendSummary& {
    for (BackendSummary& s : summaries)
      if (s.backend == name) return s;
    summaries.push_back({});
    summaries.back().backend = name;
    return summaries.back();
  };
  for (const SceneResult& scene : run.scenes) {
    for (const BackendResult& b : scene.backends) {
      BackendSummary& s = summary_of(b.backend);
      if (b.status == "skipped") ++s.skipped;
      if (b.status == "error") ++s.errors;
      if (b.status != "pass" && b.status != "fail") continue;
      ++(b.status == "pass" ? s.passed : s.failed);
      ++s.compared;
      s.worst_max_error = std::max(s.worst_max_error, b.metrics.max_error);
      s.worst_rms_error = std::max(s.worst_rms_error, b.metrics.rms_error);
      s.compile_ms += b.compile_ms;
      s.first_frame_ms += b.first_frame_ms();
      // A ratio of times averages as a geometric mean: 2x faster and 2x slower cancel.
      if (b.render_ms > 0 && scene.reference_ms > 0) {
        log_speedup_sum[b.backend] += std::log(scene.reference_ms / b.render_ms);
        ++speedups[b.backend];
      }
    }
  }
  for (BackendSummary& s : summaries) {
    if (s.compared > 0) s.first_frame_ms /= s.compared;
    if (speedups[s.backend] > 0) s.speedup = std::exp(log_speedup_sum[s.backend] / speedups[s.backend]);
  }
  return summaries;
}

std::string fastest_passing(const std::vector<BackendSummary>& summaries) {
  const BackendSummary* fastest = nullptr;
  for (const BackendSummary& s : summaries)
    if (s.passes() && (!fastest || s.speedup > fastest->speedup)) fastest = &s;
  return fastest ? fastest->backend : "";
}

std::string fastest_line(const std::vector<BackendSummary>& summaries) {
  const std::string fastest = fastest_passing(summaries);
  return "fastest backend that passes here: " + (fastest.empty() ? std::string("none") : fastest);
}

std::pair<int, int> parse_size(const std::string& text) {
  const auto fail = [&] {
    throw InputError("--size: expected WIDTHxHEIGHT with each side in [1, " + std::to_string(limits::kMaxImageSide) +
                     "] (e.g. 320x180), got '" + text + "'");
  };
  const size_t x = text.find('x');
  if (x == std::string::npos || x == 0 || x + 1 == text.size() || text.size() > 11) fail();
  for (size_t i = 0; i < text.size(); ++i)
    if (i != x && (text[i] < '0' || text[i] > '9')) fail();
  const int width = std::stoi(text.substr(0, x)), height = std::stoi(text.substr(x + 1));
  if (width < 1 || width > limits::kMaxImageSide || height < 1 || height > limits::kMaxImageSide) fail();
  return {width, height};
}

bool RunResult::passed() const {
  for (const SceneResult& s : scenes)
    for (const BackendResult& b : s.backends)
      if (b.status == "fail" || b.status == "error") return false;
  return true;
}

RunResult run_conformance(Registry& registry, const Options& options,
                          const std::function<void(const std::string&)>& log) {
  const cli::PhaseTimer timer;
  RunResult run;
  run.caps = options.caps;
  run.started = utc_now();
  const std::vector<fs::path> files = scene_files(options.scenes);
  const std::vector<Subject> subjects = subjects_for(registry, options);
  for (const fs::path& file : files) run.scenes.push_back(SceneRun(registry, options, log).run(file, subjects));
  run.wall_ms = timer.total();
  return run;
}

}  // namespace prism::conform
