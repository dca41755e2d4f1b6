// What the `prism` subcommands share: choosing a backend, timing phases,
// writing --stats, and the progress bar.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "prism/backend.hpp"
#include "prism/image_io.hpp"
#include "prism/registry.hpp"
#include "prism/scene.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli {

// The backend named on the command line, started: prism::open_backend
// (registry.hpp) loads, probes and starts it ("auto": the fastest usable one).
using BackendChoice = OpenedBackend;

// The scene's image settings with the command line's --width, --height,
// --spp and --max-depth applied (any Args with those optional members),
// checked against the format's ranges (InputError).
template <class Args>
ImageSettings image_with_overrides(const Scene& scene, const Args& args) {
  ImageSettings image = scene.image;
  if (args.width) image.width = *args.width;
  if (args.height) image.height = *args.height;
  if (args.spp) image.spp = *args.spp;
  if (args.max_depth) image.max_depth = *args.max_depth;
  check_image_settings(image, "--");
  return image;
}

class PhaseTimer {
 public:
  PhaseTimer() : start_(std::chrono::steady_clock::now()), last_(start_) {}
  // Milliseconds since the previous lap (or the start).
  double lap();
  double total() const;

 private:
  std::chrono::steady_clock::time_point start_, last_;
};

// The phase times --stats writes, in milliseconds, in its order: load,
// build, compile (a GPU backend's kernel, taken out of render), render, total.
std::vector<std::pair<std::string, double>> phase_times(const BackendChoice& choice, const PhaseTimer& timer,
                                                        std::map<std::string, double> ms);
// The same as one line for -v: "load 1.2 ms, build 0.3 ms, ...".
std::string phase_times_line(const std::vector<std::pair<std::string, double>>& times);

// Writes the --stats JSON (atomically): the phases timed in `ms`, the
// backend's own compile time, and the total so far.
void write_stats(const std::string& file, const BackendChoice& choice, const Scene& scene, const PhaseTimer& timer,
                 std::map<std::string, double> ms);
// The same, written under a temporary name and not yet in place, for a
// command that commits it together with its main output.
StagedFile stage_stats(const std::string& file, const BackendChoice& choice, const Scene& scene, const PhaseTimer& timer,
                       std::map<std::string, double> ms);

// Makes SIGINT and SIGTERM request cancellation (prism/cancel.hpp), so a
// render or trace stops within a tile, its temporary file is removed and
// main() exits 128 + the signal. A second signal ends the process at once.
// A run still going kStopGraceSeconds after the first signal (stuck in a
// plugin that never returns) is ended then by SIGALRM: the registered
// temporary files are removed and the process exits 128 + the signal.
inline constexpr unsigned kStopGraceSeconds = 2;
void stop_on_interrupt();

// What the progress bar says beside the fraction done: the frame of a
// sequence, and the ray rate of an earlier frame, shown until this frame's
// backend reports the rays it has traced.
struct ProgressLabel {
  int frame = 0, frames = 1;     // frame `frame` (0-based) of `frames`
  double rays_per_second = 0;    // 0: not known yet
};
// Sets `settings`' progress callbacks to draw a progress bar on stderr, only
// when stderr is a terminal:
// `[####    ]  69%  1.2 s, 0.5 s left, 7.0 Mrays/s, frame 2/24`.
// The ray rate is this frame's as soon as the backend reports rays
// (RenderSettings::rays_traced), so it shows during the first frame too.
void show_progress_bar(RenderSettings& settings, const ProgressLabel& label = {});
// The bar is complete: the next output starts on a line of its own.
void finish_progress_bar();
// Before a message while a bar may be half drawn (an error, an interrupt):
// ends its line, so that the message is not glued to it.
void end_progress_line();

// A long step before the bar starts (loading the scene, starting or
// preparing the backend), shown on the bar's line while it runs:
// `loading big.json... 1.2 s`, its clock redrawn every quarter second by a
// thread of its own. The line is cleared when the object goes, so the next
// step or the bar takes its place. Nothing when stderr is not a terminal or
// `show` is false (-q).
class PhaseLine {
 public:
  PhaseLine(std::string what, bool show);
  ~PhaseLine();
  PhaseLine(const PhaseLine&) = delete;
  PhaseLine& operator=(const PhaseLine&) = delete;

 private:
  struct Ticker;
  std::unique_ptr<Ticker> ticker_;  // null: not shown
};
// Runs `step` with `what` shown as a PhaseLine; returns what it returns.
template <class Step>
auto with_phase_line(const std::string& what, bool show, Step&& step) {
  PhaseLine line(what, show);
  return step();
}
// How a phase line names the scene file: "standard input" for -.
std::string scene_name_for_phase(const std::string& scene_file);
// open_backend and Backend::prepare, each shown as a phase line:
// "starting embree..." ("choosing the backend..." for auto) and
// "embree: preparing the scene..." (building its BVH, uploading it).
// Sets `precision` (Backend::set_precision) before anything is prepared.
BackendChoice open_backend_showing_it(Registry& registry, const std::string& backend, bool show,
                                      Precision precision = Precision::automatic);
void prepare_showing_it(const BackendChoice& choice, const Scene& scene, bool show);

// Prints the core's notices of slow steps (prism/status.hpp) on stderr,
// each on a line of its own: "prism: compiling the opengl kernel for this scene (cached afterwards)…".
void show_status_notices();

// --precision auto|float|double, on render, trace, bench and conform.
inline constexpr const char* kPrecisionHelp =
    "Intersection arithmetic: auto (the backend's choice), float (each plugin's float instantiation; "
    "the reference backend) or double (default auto)";
// The Precision --precision names; InputError naming the flag otherwise.
Precision precision_flag(const std::string& text);
// Backend::set_precision on an opened backend; a refusal is InputError
// naming the backend and the flag.
void set_backend_precision(Backend& backend, const std::string& name, Precision precision);

// --threads N: InputError unless N >= 1.
void check_thread_count(const std::optional<int>& threads);
// TBB's worker limit for the run (the CPU backends render and trace with
// TBB in this process), held while the returned object lives; no limit when
// `threads` is empty. Checks it first.
std::shared_ptr<void> limit_threads(const std::optional<int>& threads);
// The number of threads TBB may use now (-v says it).
size_t thread_limit();

// "1.7 s", "85 ms"; "7.0 Mrays/s", "350.2 krays/s".
std::string format_duration(double ms);
std::string format_ray_rate(double rays_per_second);

}  // namespace prism::cli
