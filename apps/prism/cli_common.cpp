#include "cli_common.hpp"

#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <thread>
#include <nlohmann/json.hpp>

#include "prism/status.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/image_file.hpp"
#include "prism/image_io.hpp"
#include "prism/stats_keys.hpp"

namespace prism::cli {

double PhaseTimer::lap() {
  auto now = std::chrono::steady_clock::now();
  double ms = std::chrono::duration<double, std::milli>(now - last_).count();
  last_ = now;
  return ms;
}

double PhaseTimer::total() const {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
}

namespace {
// The primitive plugins the scene uses that hide another file of the same
// type later in the search path (a `sphere` in PRISM_PLUGIN_PATH before the
// built-in one): {type: {"used": file, "overrides": [files]}}.
nlohmann::ordered_json plugin_overrides(const Scene& scene) {
  const Registry registry;
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const Object& object : scene.objects) {
    if (!object.plugin) continue;
    const std::string type = object.plugin->name();
    if (out.contains(type)) continue;
    std::vector<std::string> hidden;
    for (const auto& file : registry.files_of("primitive", type))
      if (file != object.plugin->path()) hidden.push_back(file.string());
    if (!hidden.empty()) out[type] = {{"used", object.plugin->path().string()}, {"overrides", hidden}};
  }
  return out;
}
}  // namespace

std::vector<std::pair<std::string, double>> phase_times(const BackendChoice& choice, const PhaseTimer& timer,
                                                        std::map<std::string, double> ms) {
  const BackendStats stats = choice.backend->stats();
  // A GPU backend compiles its kernel inside its first render or trace call:
  // that time is `compile`, not `render`.
  if (auto it = stats.ms.find(ms_key::kCompile); it != stats.ms.end()) {
    ms[ms_key::kCompile] = it->second;
    if (ms.count(ms_key::kRender)) ms[ms_key::kRender] = std::max(0.0, ms[ms_key::kRender] - it->second);
  }
  ms["total"] = timer.total();
  std::vector<std::pair<std::string, double>> times;
  // load and total are the command's own phases: no backend reports them.
  for (const char* phase : {"load", ms_key::kBuild, ms_key::kCompile, ms_key::kRender, "total"}) {
    auto it = ms.find(phase);
    times.emplace_back(phase, it == ms.end() ? 0.0 : it->second);
  }
  return times;
}

std::string phase_times_line(const std::vector<std::pair<std::string, double>>& times) {
  std::string line;
  char part[64];
  for (const auto& [phase, ms] : times) {
    std::snprintf(part, sizeof part, "%s%s %.1f ms", line.empty() ? "" : ", ", phase.c_str(), ms);
    line += part;
  }
  return line;
}

StagedFile stage_stats(const std::string& file, const BackendChoice& choice, const Scene& scene, const PhaseTimer& timer,
                       std::map<std::string, double> ms) {
  const BackendStats stats = choice.backend->stats();
  nlohmann::ordered_json j;
  j["backend"] = choice.name;
  j["plugins_loaded"] = scene.plugin_names();
  if (auto overrides = plugin_overrides(scene); !overrides.empty()) j["plugins_overriding"] = overrides;
  j["kernel_features"] = stats.kernel_features;
  j["rays"] = stats.rays;
  j["rays_by_kind"] = stats.rays_by_kind;
  if (!stats.counters.empty()) j["counters"] = stats.counters;
  if (!stats.info.empty()) j["info"] = stats.info;
  nlohmann::ordered_json times;
  for (const auto& [phase, value] : phase_times(choice, timer, std::move(ms))) times[phase] = value;
  j["ms"] = times;
  // Whether this run needed OpenImageIO (PNG, JPEG, EXR and HDR output do not).
  j["loaded_libraries"] = {{"openimageio", openimageio_loaded()}};
  return stage_text_file(file, j.dump(2) + "\n");
}

void write_stats(const std::string& file, const BackendChoice& choice, const Scene& scene, const PhaseTimer& timer,
                 std::map<std::string, double> ms) {
  stage_stats(file, choice, scene, timer, std::move(ms)).commit();
}

namespace {
volatile sig_atomic_t first_signal = 0;
// Whether a progress bar is on the current line of stderr, for the deadline
// handler's message (which must not call into stdio).
volatile sig_atomic_t progress_line_open = 0;

// Removes the temporary files and exits as the signal asked, without
// unwinding anything (write, unlink and _exit are async-signal-safe).
template <size_t N>
[[noreturn]] void end_at_once(const char (&message)[N]) {
  if (progress_line_open) {
    [[maybe_unused]] const ssize_t ended = write(STDERR_FILENO, "\n", 1);
  }
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, message, N - 1);
  remove_temporary_files();
  _exit(128 + (first_signal != 0 ? int(first_signal) : SIGTERM));
}

// Only async-signal-safe calls: atomics, alarm() and end_at_once.
void on_interrupt(int signal) {
  if (first_signal == 0) first_signal = signal;
  if (uninterruptible_work_running())  // a kernel compile: no check would come for seconds
    end_at_once("prism: interrupted while compiling a GPU kernel: ended at once, the output files were left as they were\n");
  request_cancel(signal);
  alarm(kStopGraceSeconds);  // a run stuck in a plugin never checks the request
}

// The grace period ran out.
void on_deadline(int) {
  end_at_once("prism: interrupted, and the run did not stop within the grace period: ended at once, the output files were left as they were\n");
}
}  // namespace

void stop_on_interrupt() {
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the default action is back after the first signal, so a
  // second Ctrl-C kills a run that does not stop quickly enough.
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  struct sigaction deadline = {};
  deadline.sa_handler = on_deadline;
  sigemptyset(&deadline.sa_mask);
  sigaction(SIGALRM, &deadline, nullptr);
}

void check_thread_count(const std::optional<int>& threads) {
  if (threads && *threads < 1) throw InputError("--threads: must be at least 1, got " + std::to_string(*threads));
}

std::shared_ptr<void> limit_threads(const std::optional<int>& threads) {
  check_thread_count(threads);
  if (!threads) return nullptr;
  return std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(*threads));
}

size_t thread_limit() { return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism); }

std::string format_duration(double ms) {
  char text[32];
  if (ms < 1000.0) std::snprintf(text, sizeof text, "%.0f ms", ms);
  else std::snprintf(text, sizeof text, "%.1f s", ms / 1000.0);
  return text;
}

std::string format_ray_rate(double rays_per_second) {
  char text[32];
  if (rays_per_second >= 1e6) std::snprintf(text, sizeof text, "%.1f Mrays/s", rays_per_second / 1e6);
  else std::snprintf(text, sizeof text, "%.1f krays/s", rays_per_second / 1e3);
  return text;
}

namespace {
std::mutex progress_mutex;
bool line_open = false;   // a bar or a phase line is on the current line of stderr
int progress_drawn = -1;  // percent last drawn; -1: no bar drawn yet
std::chrono::steady_clock::time_point progress_start, progress_redrawn;
// The rays this frame's render has traced so far (RenderSettings::rays_traced).
std::atomic<uint64_t> frame_rays{0};

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Marks the line as holding a bar or phase line; under progress_mutex.
void open_line() {
  line_open = true;
  progress_line_open = 1;
}

// The ray rate the bar shows: this frame's once it has traced rays, else the earlier frames'.
double shown_ray_rate(double elapsed_ms, const ProgressLabel& label) {
  const uint64_t rays = frame_rays.load(std::memory_order_relaxed);
  if (rays > 0 && elapsed_ms > 0.0) return double(rays) / (elapsed_ms / 1000.0);
  return label.rays_per_second;
}

// What follows the percentage: times, ray rate, frame.
std::string progress_details(double fraction, const ProgressLabel& label) {
  const double elapsed = ms_since(progress_start);
  std::string text = format_duration(elapsed);
  if (fraction > 0.0 && fraction < 1.0) text += ", " + format_duration(elapsed * (1.0 - fraction) / fraction) + " left";
  if (const double rate = shown_ray_rate(elapsed, label); rate > 0.0) text += ", " + format_ray_rate(rate);
  if (label.frames > 1) text += ", frame " + std::to_string(label.frame + 1) + "/" + std::to_string(label.frames);
  return text;
}

void draw_progress(double fraction, const ProgressLabel& label) {
  const int percent = std::clamp(static_cast<int>(fraction * 100.0), 0, 100);
  std::lock_guard lock(progress_mutex);
  // Redrawn when the percentage moves on, or every quarter second for the
  // clock; a thread's report older than what is shown is dropped.
  const auto now = std::chrono::steady_clock::now();
  if (percent < progress_drawn) return;
  if (percent == progress_drawn && now - progress_redrawn < std::chrono::milliseconds(250)) return;
  progress_drawn = percent;
  open_line();
  progress_redrawn = now;
  constexpr int kWidth = 40;
  const int filled = percent * kWidth / 100;
  // \033[K clears what a longer earlier line left on the right.
  std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %s\033[K", filled, "########################################",
               kWidth - filled, "", percent, progress_details(fraction, label).c_str());
  std::fflush(stderr);
}
}  // namespace

void show_progress_bar(RenderSettings& settings, const ProgressLabel& label) {
  if (!::isatty(STDERR_FILENO)) return;
  {
    std::lock_guard lock(progress_mutex);
    progress_drawn = -1;
    progress_start = progress_redrawn = std::chrono::steady_clock::now();
    frame_rays = 0;
  }
  settings.rays_traced = [](uint64_t rays) { frame_rays.store(rays, std::memory_order_relaxed); };
  settings.progress = [label](double fraction) { draw_progress(fraction, label); };
}

void finish_progress_bar() { end_progress_line(); }

void show_status_notices() {
  set_status_handler([](const std::string& message) {
    end_progress_line();
    std::fprintf(stderr, "prism: %s\n", message.c_str());
    std::fflush(stderr);
  });
}

void end_progress_line() {
  std::lock_guard lock(progress_mutex);
  if (line_open) std::fprintf(stderr, "\n");
  line_open = false;
  progress_drawn = -1;
  progress_line_open = 0;
}

// The thread that redraws a phase line's clock until the phase ends.
struct PhaseLine::Ticker {
  std::string what;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  std::mutex mutex;
  std::condition_variable done_changed;
  bool done = false;
  std::thread thread;

  void draw() {
    std::lock_guard lock(progress_mutex);
    open_line();
    std::fprintf(stderr, "\r%s... %s\033[K", what.c_str(), format_duration(ms_since(start)).c_str());
    std::fflush(stderr);
  }
  void run() {
    std::unique_lock lock(mutex);
    do {
      lock.unlock();
      draw();
      lock.lock();
    } while (!done_changed.wait_for(lock, std::chrono::milliseconds(250), [this] { return done; }));
  }
};

PhaseLine::PhaseLine(std::string what, bool show) {
  if (!show || !::isatty(STDERR_FILENO)) return;
  ticker_ = std::make_unique<Ticker>();
  ticker_->what = std::move(what);
  ticker_->thread = std::thread([ticker = ticker_.get()] { ticker->run(); });
}

PhaseLine::~PhaseLine() {
  if (!ticker_) return;
  {
    std::lock_guard lock(ticker_->mutex);
    ticker_->done = true;
  }
  ticker_->done_changed.notify_one();
  ticker_->thread.join();
  // The step is over: its line makes room for the next one or the bar.
  std::lock_guard lock(progress_mutex);
  if (line_open) std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  line_open = false;
  progress_line_open = 0;
}

std::string scene_name_for_phase(const std::string& scene_file) {
  return scene_file == kStandardInput ? std::string("standard input") : scene_file;
}

BackendChoice open_backend_showing_it(Registry& registry, const std::string& backend, bool show,
                                      Precision precision) {
  const std::string what = backend == "auto" ? "choosing the backend" : "starting " + backend;
  BackendChoice choice = with_phase_line(what, show, [&] { return open_backend(registry, backend); });
  set_backend_precision(*choice.backend, choice.name, precision);
  return choice;
}

Precision precision_flag(const std::string& text) {
  if (auto precision = parse_precision(text)) return *precision;
  throw InputError("--precision: '" + text + "' is not one of auto, float, double");
}

void set_backend_precision(Backend& backend, const std::string& name, Precision precision) {
  try {
    backend.set_precision(precision);
  } catch (const InputError& e) {
    throw InputError("--precision " + std::string(precision_name(precision)) + ": backend '" + name + "': " + e.what());
  }
}

void prepare_showing_it(const BackendChoice& choice, const Scene& scene, bool show) {
  with_phase_line(choice.name + ": preparing the scene", show, [&] { choice.backend->prepare(scene); });
}

}  // namespace prism::cli
