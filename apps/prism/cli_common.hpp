// What the `prism` subcommands share: choosing a backend, timing phases,
// writing --stats, and the progress bar.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <string>

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

// A progress bar on stderr, drawn only when stderr is a terminal.
std::function<void(double)> progress_bar();
void finish_progress_bar();

}  // namespace prism::cli
