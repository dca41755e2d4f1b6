// prism view SCENE [-b BACKEND]: the scene live in a window, rendered by a
// backend from a camera the mouse and keyboard move: 1 spp while it moves,
// refined up to the scene's spp when it stops, then idle until an event.
// The window, camera, font and GL drawing live in viewer/.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <tuple>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/scene_loader.hpp"
#include "viewer/camera_controller.hpp"
#include "viewer/frame_pixels.hpp"
#include "viewer/gl_display.hpp"
#include "viewer/overlay.hpp"
#include "viewer/refinement.hpp"
#include "viewer/window.hpp"

namespace prism::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kOrbitRadiansPerPixel = 0.005;  // a 1257-pixel drag turns all the way round
constexpr double kDollyPerClick = 0.9;           // each wheel click: 10% closer to the target
constexpr double kMaxFlyStepSeconds = 0.25;      // a slow frame does not turn one key press into a leap
constexpr double kIdleWaitSeconds = 0.5;         // longest sleep while idle (events wake it sooner)

constexpr const char* kControls =
    "Controls: drag with the left button to orbit about the target point (at first the scene's look_at), "
    "wheel to dolly towards it, W/A/S/D to fly forward/left/back/right, E or Space up, Q or Shift down "
    "(speed: a quarter of the scene's size per second), R back to the scene's camera, P to save the frame "
    "as prism-view-<n>.png in the current folder once it reaches the scene's spp, C to print the camera as "
    "scene JSON on standard output, H to show or hide the keys, Esc to quit.\n"
    "While the camera moves, frames are 1 sample per pixel; when it stops, the view is rendered again at "
    "2, 4, 8, ... up to the scene's spp, then nothing is rendered until something changes.\n";

struct ViewArgs {
  std::string scene, backend = "auto", capture;
  std::optional<int> width, height, spp, max_depth, frames;
  std::optional<double> scale;
};

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// P: the frame as rendered (no status band), to the first free prism-view-<n>.png.
// Served once the frame on screen has reached the scene's spp, so camera
// moves made before the key press are in it, the image is the refined one,
// and a press before the first frame is not lost.
void save_screenshot(const Image& frame) {
  fs::path file;
  for (int n = 1;; ++n) {
    file = "prism-view-" + std::to_string(n) + ".png";
    std::error_code ec;
    if (!fs::exists(file, ec)) break;
  }
  try {
    write_image(frame, file);
    std::printf("prism view: saved %s\n", file.c_str());
    std::fflush(stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism: warning: screenshot not saved: %s\n", e.what());
  }
}

void check_view_args(const ViewArgs& args) {
  if (!args.capture.empty()) check_output_path(args.capture, {".png"});
  if (args.frames && *args.frames < 1) throw InputError("--frames: must be >= 1, got " + std::to_string(*args.frames));
  const double scale = args.scale.value_or(1.0);
  if (!(scale > 0.0 && scale <= 1.0)) {
    char got[32];
    std::snprintf(got, sizeof got, "%g", scale);
    throw InputError(std::string("--scale: must be in (0, 1], got ") + got);
  }
}

RenderSettings initial_settings(const Scene& scene, const ViewArgs& args) {
  RenderSettings settings;
  settings.image = image_with_overrides(scene, args);
  return settings;
}

// Moves the camera as the input says; true when it moved.
bool move_camera(const viewer::Input& in, double fly_step, viewer::CameraController& controller) {
  bool moved = false;
  if (in.reset) {
    controller.reset();
    moved = true;
  }
  if (in.drag_x != 0 || in.drag_y != 0) {
    controller.orbit(-in.drag_x * kOrbitRadiansPerPixel, in.drag_y * kOrbitRadiansPerPixel);
    moved = true;
  }
  if (in.scroll != 0) {
    controller.dolly(std::pow(kDollyPerClick, in.scroll));
    moved = true;
  }
  if (in.fly_right || in.fly_up || in.fly_forward) {
    controller.fly(in.fly_right * fly_step, in.fly_up * fly_step, in.fly_forward * fly_step);
    moved = true;
  }
  return moved;
}

// The window, the backend and the view they show: one frame per step().
class Viewer {
 public:
  Viewer(const ViewArgs& args, Registry& registry, const Scene& scene);
  void run();
  void print_summary() const;
  void write_capture() const;

 private:
  // One turn of the loop; false to quit.
  bool step();
  void render(int spp);
  void draw();
  void after_swap(bool rendered);
  void save_pending_screenshot();

  const ViewArgs& args_;
  const double scale_;
  RenderSettings settings_;
  viewer::CameraController controller_;
  viewer::Refinement refinement_;
  const std::optional<Box3> bounds_;
  // Declared before the window so that it is destroyed after it: the backend
  // never runs with the display context current, not even in its destructor.
  BackendChoice choice_;
  viewer::Window window_;
  viewer::GlDisplay display_;
  std::string title_;

  viewer::FrameRate rate_;
  Image frame_;  // the frame on screen, as the backend rendered it
  int fb_width_ = 0, fb_height_ = 0;
  std::vector<uint8_t> captured_;
  int captured_width_ = 0, captured_height_ = 0;
  int frames_ = 0;
  bool screenshot_pending_ = false;  // P: saved once the frame on screen is final
  bool show_help_ = false;           // H
  bool flying_ = false;              // a fly key is held: keep moving without waiting for events
  double first_ms_ = 0, later_ms_ = 0, render_ms_total_ = 0, fly_seconds_ = 0;
  Clock::time_point last_swap_ = Clock::now(), last_title_ = last_swap_ - std::chrono::seconds(1);
};

Viewer::Viewer(const ViewArgs& args, Registry& registry, const Scene& scene)
    : args_(args),
      scale_(args.scale.value_or(1.0)),
      settings_(initial_settings(scene, args)),
      controller_(scene.camera,
                  viewer::orbit_start(scene.camera, viewer::read_camera_hints(read_text(scene.source)),
                                      viewer::scene_bounds(scene))),
      refinement_(settings_.image.spp),
      bounds_(viewer::scene_bounds(scene)),
      window_(settings_.image.width, settings_.image.height,
              "prism view: " + fs::path(args.scene).filename().string()) {
  {
    viewer::ContextRelease release(window_);
    choice_ = open_backend(registry, args.backend);
    choice_.backend->prepare(scene);
  }
  title_ = "prism view: " + fs::path(args.scene).filename().string() + " (" + choice_.name + ")";
  window_.set_title(title_);
}

void Viewer::run() {
  while (step()) {
  }
}

bool Viewer::step() {
  // Nothing to render and no key held: sleep until an event (the timeout only bounds a missed wake-up).
  const bool idle = refinement_.done() && !args_.frames && !flying_;
  if (idle) {
    window_.wait_events(kIdleWaitSeconds);
    last_swap_ = Clock::now();  // time asleep is no frame's time
  } else {
    window_.poll_events();
  }
  const viewer::Input in = window_.take_input();
  if (in.quit) return false;
  if (in.screenshot) screenshot_pending_ = true;
  if (in.print_camera) {
    std::printf("%s\n", viewer::camera_json(controller_).c_str());
    std::fflush(stdout);
  }
  if (in.toggle_help) show_help_ = !show_help_;
  flying_ = in.fly_right || in.fly_up || in.fly_forward;
  const double fly_step = viewer::fly_speed(bounds_, controller_.distance()) * fly_seconds_;
  if (move_camera(in, fly_step, controller_)) refinement_.restart();

  std::tie(fb_width_, fb_height_) = window_.framebuffer_size();
  if (fb_width_ <= 0 || fb_height_ <= 0) {  // minimised
    window_.wait_events(0.1);
    last_swap_ = Clock::now();
    return true;
  }
  const int width = std::clamp(int(std::lround(fb_width_ * scale_)), 1, 16384);
  const int height = std::clamp(int(std::lround(fb_height_ * scale_)), 1, 16384);
  if (width != settings_.image.width || height != settings_.image.height) refinement_.restart();
  settings_.image.width = width;
  settings_.image.height = height;

  // --frames (automation, timing): every frame at the full spp, even when nothing changes.
  std::optional<int> spp = args_.frames ? std::optional<int>(refinement_.target_spp()) : refinement_.next_spp();
  if (spp) {
    render(*spp);
  } else if (!in.refresh && !in.toggle_help) {
    save_pending_screenshot();  // P on a final frame: nothing to render first
    return true;                // the frame on screen is final and undamaged
  }
  draw();
  after_swap(spp.has_value());
  return !(args_.frames && frames_ >= *args_.frames);
}

// P waits for the frame on screen to reach the scene's spp (every frame does under --frames).
void Viewer::save_pending_screenshot() {
  if (!screenshot_pending_ || !(args_.frames || refinement_.done())) return;
  save_screenshot(frame_);
  screenshot_pending_ = false;
  last_swap_ = Clock::now();  // the write is not part of the next frame's time
}

void Viewer::render(int spp) {
  settings_.image.spp = spp;
  settings_.camera = controller_.camera();
  const Clock::time_point start = Clock::now();
  {
    viewer::ContextRelease release(window_);
    frame_ = choice_.backend->render(settings_);
  }
  render_ms_total_ += ms_since(start);
  refinement_.rendered(spp);
  if (frame_.width != settings_.image.width || frame_.height != settings_.image.height ||
      frame_.rgb.size() != size_t(frame_.width) * frame_.height * 3)
    throw RuntimeError("backend '" + choice_.name + "' returned a " + std::to_string(frame_.width) + "x" +
                       std::to_string(frame_.height) + " frame for a " + std::to_string(settings_.image.width) + "x" +
                       std::to_string(settings_.image.height) + " request");
}

void Viewer::draw() {
  const viewer::Rgba8Image pixels{frame_.width, frame_.height, viewer::to_rgba8(frame_)};
  const int overlay_scale = viewer::overlay_scale(fb_width_);
  const int max_chars = viewer::chars_that_fit(fb_width_, overlay_scale);
  std::vector<std::string> lines = {
      viewer::with_refinement(viewer::status_line(rate_, choice_.name, frame_.width, frame_.height, max_chars),
                              refinement_.shown_spp(), refinement_.target_spp(), max_chars)};
  if (show_help_) lines.insert(lines.end(), viewer::key_help_lines().begin(), viewer::key_help_lines().end());
  display_.draw(pixels, viewer::overlay_image(lines, overlay_scale, fb_width_), fb_width_, fb_height_);
  if (!args_.capture.empty()) {
    // From the back buffer, before the swap: after it the back buffer is
    // undefined (and reads as zeros under Xvfb).
    captured_ = display_.read_back(fb_width_, fb_height_);
    captured_width_ = fb_width_;
    captured_height_ = fb_height_;
  }
  window_.swap_buffers();
}

// Frame timing, the title's frame rate and a pending screenshot, after a
// frame is shown (`rendered`: a new one, not the last one drawn again).
void Viewer::after_swap(bool rendered) {
  const Clock::time_point now = Clock::now();
  const double frame_ms = std::chrono::duration<double, std::milli>(now - last_swap_).count();
  last_swap_ = now;
  fly_seconds_ = std::min(frame_ms / 1000.0, kMaxFlyStepSeconds);
  if (rendered) {
    rate_.add(frame_ms);
    (frames_ == 0 ? first_ms_ : later_ms_) += frame_ms;
    ++frames_;
  }
  if (rate_.has_value() && std::chrono::duration<double>(now - last_title_).count() >= 0.5) {
    char fps[64];
    std::snprintf(fps, sizeof fps, " %.1f fps", rate_.fps());
    window_.set_title(title_ + fps);
    last_title_ = now;
  }
  save_pending_screenshot();
}

void Viewer::print_summary() const {
  if (frames_ == 0) return;
  std::printf("prism view: %d frame%s at %dx%d with %s: first %.1f ms", frames_, frames_ == 1 ? "" : "s",
              settings_.image.width, settings_.image.height, choice_.name.c_str(), first_ms_);
  if (frames_ > 1) std::printf(", then %.2f ms mean", later_ms_ / (frames_ - 1));
  std::printf(" (render %.2f ms mean); display context: %s\n", render_ms_total_ / frames_,
              window_.context_api().c_str());
}

void Viewer::write_capture() const {
  if (args_.capture.empty()) return;
  if (captured_.empty()) throw RuntimeError("--capture: the window closed before a frame was shown");
  write_image(viewer::from_rgba8(captured_, captured_width_, captured_height_), args_.capture);
}

int run_view(const ViewArgs& args) {
  // Everything the command line alone can get wrong is found before a window opens.
  check_view_args(args);
  Registry registry;
  const Scene scene = load_scene(args.scene, registry);
  write_warnings(scene, std::cerr);
  // An unknown or broken backend plugin is bad input (exit 2) whether or not there is a display.
  if (args.backend != "auto") registry.backend(args.backend);
  Viewer viewer(args, registry, scene);
  viewer.run();
  viewer.print_summary();
  viewer.write_capture();
  return 0;
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* sub = app.add_subcommand("view", "Show a scene live in a window (needs an X display)");
  sub->footer(kControls);
  sub->add_option("scene", args->scene, "Scene file (JSON)")->required();
  sub->add_option("-b,--backend", args->backend, "Backend name, or auto for the fastest usable one (default auto)");
  sub->add_option("--width", args->width, "Initial window width in pixels (1..16384; default the scene's image width)");
  sub->add_option("--height", args->height,
                  "Initial window height in pixels (1..16384; default the scene's image height)");
  sub->add_option("--spp", args->spp, "Samples per pixel the still view is refined to (1..4096)");
  sub->add_option("--max-depth", args->max_depth, "Surface interactions per camera sample (1..64)");
  sub->add_option("--scale", args->scale,
                  "Render at this fraction of the window's size, shown enlarged (0 < S <= 1; default 1)");
  sub->add_option("--frames", args->frames, "Quit after this many frames, each at the full spp (for automation and timing)");
  sub->add_option("--capture", args->capture,
                  "Write the last frame shown, status line included, to this .png (window pixels as displayed)");
  return [args] { return run_view(*args); };
}

}  // namespace prism::cli
