// prism_animated: the showcase scene built in code with the library API
// (prism/api.hpp), animated, and rendered frame after frame by one Renderer,
// which after the first frame sends the backend only what moved.
// See README.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <prism/api.hpp>
#include <prism/image_io.hpp>
#include <prism/view_window.hpp>

#include "options.hpp"
#include "showcase.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Animation time advances by a fixed step per frame, not by the clock, so
// that frame N is the same picture on every backend and every machine.
constexpr double kSecondsPerFrame = 1.0 / 30.0;
constexpr int kDefaultFrames = 120;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The rate at which frames reach the window, over the last kSpan of them:
// the rate the user sees, display included.
class RateMeter {
 public:
  void tick(Clock::time_point now) {
    times_.push_back(now);
    if (times_.size() > kSpan) times_.pop_front();
  }
  double fps() const {
    if (times_.size() < 2) return 0;
    return 1000.0 * double(times_.size() - 1) / ms_between(times_.front(), times_.back());
  }

 private:
  static constexpr size_t kSpan = 16;
  std::deque<Clock::time_point> times_;
};

std::string frame_file(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return name;
}

std::string status_text(double fps, const std::string& backend, const prism::Image& image, int frame) {
  char text[128];
  if (fps > 0)
    std::snprintf(text, sizeof text, "%.1f FPS  %s  %dx%d  FRAME %d", fps, backend.c_str(), image.width,
                  image.height, frame);
  else
    std::snprintf(text, sizeof text, "-- FPS  %s  %dx%d  FRAME %d", backend.c_str(), image.width, image.height,
                  frame);
  return text;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The first frame prepares the scene (acceleration structure, GPU kernel),
// so it is reported apart and the median is taken over the frames after it.
void print_summary(const std::vector<double>& frame_ms, const prism::UpdateCounters& c) {
  if (frame_ms.empty()) return;
  std::printf("first frame: %.2f ms (prepares the scene)\n", frame_ms.front());
  const bool later = frame_ms.size() > 1;
  const std::vector<double> steady(frame_ms.begin() + (later ? 1 : 0), frame_ms.end());
  const double m = median(steady);
  std::printf("median frame time: %.2f ms (%.1f FPS) over %zu frame%s%s\n", m, m > 0 ? 1000.0 / m : 0.0,
              steady.size(), steady.size() == 1 ? "" : "s", later ? " after the first" : "");
  std::printf("counters: prepares %llu, updates %llu, objects_uploaded %llu, bvh_builds %llu, bvh_refits %llu, "
              "kernel_builds %llu\n",
              (unsigned long long)c.prepares, (unsigned long long)c.updates, (unsigned long long)c.objects_uploaded,
              (unsigned long long)c.bvh_builds, (unsigned long long)c.bvh_refits,
              (unsigned long long)c.kernel_builds);
}

// Before anything is rendered: a folder that cannot be made fails at once.
void make_out_folder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw prism::RuntimeError("--out: cannot create " + folder.string() + ": " + ec.message());
}

int run(const animated::Options& options) {
  if (!options.out.empty()) make_out_folder(options.out);
  prism::Engine engine;  // finds the plugins beside libprism_core.so, or on PRISM_PLUGIN_PATH
  prism::LiveScene scene(engine);
  const animated::Showcase showcase = animated::build_showcase(scene, options.textures);
  scene.set_image({.width = options.width, .height = options.height, .spp = options.spp,
                   .max_depth = options.max_depth});
  prism::Renderer renderer(engine, options.backend);  // starts the backend: fails here, before a window opens
  std::optional<prism::ViewWindow> window;
  if (options.window)
    window.emplace(options.width, options.height, "prism animated (" + renderer.backend_name() + ")");
  std::printf("backend %s, %dx%d, %d spp, max depth %d\n", renderer.backend_name().c_str(), options.width,
              options.height, options.spp, options.max_depth);

  const int frames = options.frames.value_or(options.window ? 0 : kDefaultFrames);  // 0: until closed
  std::vector<double> frame_ms;
  RateMeter rate;
  for (int frame = 0; frames == 0 || frame < frames; ++frame) {
    // A frame's time: the edits and the render, up to the image in host memory.
    const Clock::time_point start = Clock::now();
    animated::animate(scene, showcase, frame * kSecondsPerFrame);
    const prism::Image image = renderer.render(scene);
    frame_ms.push_back(ms_between(start, Clock::now()));
    std::printf("frame %4d: %8.2f ms\n", frame, frame_ms.back());
    std::fflush(stdout);

    if (!options.out.empty()) prism::write_image(image, options.out / frame_file(frame));
    if (window) {
      rate.tick(Clock::now());
      if (!window->show(image, status_text(rate.fps(), renderer.backend_name(), image, frame))) break;
    }
  }
  print_summary(frame_ms, renderer.counters());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const animated::Options options = animated::parse_options(argc, argv);
    if (options.help) {
      std::fputs(animated::usage().c_str(), stdout);
      return 0;
    }
    return run(options);
  } catch (const prism::InputError& e) {  // bad arguments, an unknown backend, a missing texture
    std::fprintf(stderr, "prism_animated: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // a backend that cannot start or fails, an unwritable file
    std::fprintf(stderr, "prism_animated: %s\n", e.what());
    return 1;
  }
}
