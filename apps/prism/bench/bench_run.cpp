#include "bench/bench_run.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_common.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/stats_keys.hpp"

namespace prism::bench {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

int64_t status_field_bytes(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(field) + ":";
  while (std::getline(status, line)) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::istringstream value(line.substr(prefix.size()));
    int64_t kib = -1;
    value >> kib;
    return kib < 0 ? -1 : kib * 1024;
  }
  return -1;
}

int64_t frame_bytes(const RenderSettings& settings) {
  const int64_t pixels = int64_t(settings.image.width) * settings.image.height;
  const int64_t aovs = (settings.aov_id ? 1 : 0) + (settings.aov_path ? 1 : 0) + (settings.aov_depth ? 1 : 0) +
                       (settings.aov_normal ? 3 : 0) + (settings.aov_albedo ? 3 : 0);
  return pixels * int64_t(sizeof(float)) * (3 + aovs);
}

// Largest absolute difference between two frames' rgb (0: bit-identical).
double max_difference(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size()) return INFINITY;
  double worst = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    if (a.rgb[i] == b.rgb[i]) continue;
    const double d = std::abs(double(a.rgb[i]) - double(b.rgb[i]));
    worst = std::isnan(d) ? INFINITY : std::max(worst, d);
  }
  return worst;
}

uint64_t counted(const std::map<std::string, uint64_t>& counts, const std::string& kind) {
  auto it = counts.find(kind);
  return it == counts.end() ? 0 : it->second;
}

// One frame from `camera`, timed from the call to the image in host memory.
double timed_frame(Backend& backend, RenderSettings settings, const Camera& camera, Image* image) {
  settings.camera = camera;
  const auto start = std::chrono::steady_clock::now();
  Image frame = backend.render(settings);
  const double ms = ms_since(start);
  if (image) *image = std::move(frame);
  return ms;
}

// User + system time of the whole process so far (every thread).
double process_cpu_ms() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) / 1e3; };
  return ms(usage.ru_utime) + ms(usage.ru_stime);
}

double timed_write(const Image& image, const std::filesystem::path& file) {
  const auto start = std::chrono::steady_clock::now();
  write_image(image, file);
  const double ms = ms_since(start);
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
  return ms;
}

// The phase times of the measured frames (per frame) and the cost of
// writing the last one, into `result`.
void profile_frames(const BackendStats& before, const BackendStats& after, int frames, const Image& last,
                    Result& result) {
  const std::string prefix = ms_key::kProfilePrefix;
  for (const auto& [key, ms] : after.ms) {
    if (key.rfind(prefix, 0) != 0) continue;
    const auto it = before.ms.find(key);
    result.profile_ms[key.substr(prefix.size())] = (ms - (it == before.ms.end() ? 0.0 : it->second)) / frames;
  }
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  const std::string stem = "prism-bench-" + std::to_string(::getpid());
  result.png_write_ms = timed_write(last, folder / (stem + ".png"));
  result.exr_write_ms = timed_write(last, folder / (stem + ".exr"));
}

}  // namespace

double Result::percentile_ms(double p) const {
  if (frame_ms.empty()) return NAN;
  std::vector<double> sorted = frame_ms;
  std::sort(sorted.begin(), sorted.end());
  const size_t rank = size_t(std::ceil(p / 100.0 * double(sorted.size())));
  return sorted[std::clamp<size_t>(rank, 1, sorted.size()) - 1];
}

double Result::median_ms() const {
  if (frame_ms.empty()) return NAN;
  std::vector<double> sorted = frame_ms;
  std::sort(sorted.begin(), sorted.end());
  const size_t n = sorted.size();
  return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

double Result::rays_per_second() const {
  double total_ms = 0;
  for (double ms : frame_ms) total_ms += ms;
  return total_ms > 0 ? double(rays) / (total_ms / 1000.0) : 0.0;
}

FrameCameras::FrameCameras(const Scene& scene, double orbit_degrees)
    : initial_(scene.camera), radians_per_frame_(orbit_degrees * 3.14159265358979323846 / 180.0) {
  std::ifstream in(scene.source, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  start_ = viewer::orbit_start(scene.camera, viewer::read_camera_hints(text.str()), viewer::scene_bounds(scene));
}

void check_orbit_degrees(double degrees) {
  if (!std::isfinite(degrees)) throw InputError("--orbit must be a finite number of degrees");
}

Camera FrameCameras::operator()(int index) const {
  viewer::CameraController controller(initial_, start_);
  if (index != 0) controller.orbit(index * radians_per_frame_, 0.0);
  return controller.camera();
}

Result run_backend(Registry& registry, const Scene& scene, const std::string& name, const Options& options) {
  Result result;
  result.backend = name;
  auto plugin = registry.backend(name);  // InputError when unknown
  const PrismBackendProbe probe = plugin->probe();
  result.device = probe.reason;
  if (!probe.usable) {
    result.skipped = std::string("cannot run here: ") + probe.reason;
    return result;
  }
  auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Backend> backend = start_backend(*plugin, name);
  cli::set_backend_precision(*backend, name, options.precision);
  result.start_ms = ms_since(start);
  result.memory.loaded_bytes = resident_bytes();
  result.memory.frame_bytes = frame_bytes(options.settings);
  const FrameCameras cameras(scene, options.orbit_degrees);

  start = std::chrono::steady_clock::now();
  backend->prepare(scene);
  result.build_ms = ms_since(start);

  // Warm-up from cameras the measured frames do not use. A GPU backend
  // compiles its kernel in the first: that time is `compile`, not a frame.
  for (int i = 0; i < options.warmup; ++i) {
    const double ms = timed_frame(*backend, options.settings, cameras(-(i + 1)), nullptr);
    if (i == 0) result.first_frame_ms = ms;
  }
  BackendStats before = backend->stats();
  if (auto it = before.ms.find(ms_key::kCompile); it != before.ms.end()) {
    result.compile_ms = it->second;
    result.first_frame_ms = std::max(0.0, result.first_frame_ms - it->second);
  }
  if (auto it = before.counters.find(counter::kSceneBytes); it != before.counters.end())
    result.memory.scene_bytes = int64_t(it->second);
  if (auto it = before.info.find(info_key::kDevice); it != before.info.end()) result.device = it->second;
  if (auto it = before.info.find(info_key::kPrecision); it != before.info.end()) result.precision = it->second;

  reset_peak_resident();
  Image last;
  const double cpu_before = process_cpu_ms();
  for (int i = 0; i < options.frames; ++i) {
    const Camera camera = cameras(i);
    result.frame_ms.push_back(timed_frame(*backend, options.settings, camera, i + 1 == options.frames ? &last : nullptr));
  }
  result.cpu_ms_per_frame = (process_cpu_ms() - cpu_before) / options.frames;
  result.memory.peak_bytes = peak_resident_bytes();
  const BackendStats after = backend->stats();
  result.rays = after.rays - before.rays;
  for (const auto& [kind, count] : after.rays_by_kind) {
    const uint64_t frames_count = count - counted(before.rays_by_kind, kind);
    if (frames_count > 0) result.rays_by_kind[kind] = frames_count;
  }

  if (options.profile) profile_frames(before, after, options.frames, last, result);
  if (options.check && options.frames > 0) {
    // What `prism render` does for that camera: a fresh backend, prepared once, one render.
    std::unique_ptr<Backend> fresh = start_backend(*plugin, name);
    fresh->set_precision(options.precision);
    fresh->prepare(scene);
    Image expected;
    timed_frame(*fresh, options.settings, cameras(options.frames - 1), &expected);
    result.checked = true;
    result.check_max_difference = max_difference(last, expected);
  }
  return result;
}

int64_t resident_bytes() { return status_field_bytes("VmRSS"); }
int64_t peak_resident_bytes() { return status_field_bytes("VmHWM"); }

bool reset_peak_resident() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // "Reset the peak resident set size" (proc(5), Linux 4.0)
  clear.flush();
  return bool(clear);
}

}  // namespace prism::bench
