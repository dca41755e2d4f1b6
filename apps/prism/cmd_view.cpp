// prism view SCENE [-b BACKEND]: the scene live in a window, rendered by a
// backend every frame from a camera the mouse and keyboard move.
// The window, camera, font and GL drawing live in viewer/.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/scene_loader.hpp"
#include "viewer/camera_controller.hpp"
#include "viewer/frame_pixels.hpp"
#include "viewer/gl_display.hpp"
#include "viewer/overlay.hpp"
#include "viewer/window.hpp"

namespace prism::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kOrbitRadiansPerPixel = 0.005;  // a 1257-pixel drag turns all the way round
constexpr double kDollyPerClick = 0.9;           // each wheel click: 10% closer to the target
constexpr double kMaxFlyStepSeconds = 0.25;      // a slow frame does not turn one key press into a leap

constexpr const char* kControls =
    "Controls: drag with the left button to orbit about the target point (at first the scene's look_at), "
    "wheel to dolly towards it, W/A/S/D to fly forward/left/back/right, E or Space up, Q or Shift down "
    "(speed: the target distance per second), R back to the scene's camera, P to save the frame as "
    "prism-view-<n>.png in the current folder, Esc to quit.\n";

struct ViewArgs {
  std::string scene, backend = "opengl", capture;
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
// Served after the next frame is shown, so camera moves made before the key
// press are in it, and a press before the first frame is not lost.
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

int run_view(const ViewArgs& args) {
  // Everything the command line alone can get wrong is found before a window opens.
  if (!args.capture.empty()) check_output_path(args.capture, {".png"});
  if (args.frames && *args.frames < 1) throw InputError("--frames: must be >= 1, got " + std::to_string(*args.frames));
  const double scale = args.scale.value_or(1.0);
  if (!(scale > 0.0 && scale <= 1.0)) {
    char got[32];
    std::snprintf(got, sizeof got, "%g", scale);
    throw InputError(std::string("--scale: must be in (0, 1], got ") + got);
  }

  Registry registry;
  Scene scene = load_scene(args.scene, registry);
  RenderSettings settings;
  settings.image = image_with_overrides(scene, args);
  // An unknown or broken backend plugin is bad input (exit 2) whether or not there is a display.
  if (args.backend != "auto") registry.backend(args.backend);

  viewer::CameraController controller(
      scene.camera, viewer::orbit_start(scene.camera, viewer::read_camera_hints(read_text(scene.source)),
                                        viewer::scene_bounds(scene)));

  // Declared before the window so that it is destroyed after it: the backend
  // never runs with the display context current, not even in its destructor.
  BackendChoice choice;
  const std::string scene_name = fs::path(args.scene).filename().string();
  viewer::Window window(settings.image.width, settings.image.height, "prism view: " + scene_name);
  viewer::GlDisplay display;
  {
    viewer::ContextRelease release(window);
    choice = open_backend(registry, args.backend);
    choice.backend->prepare(scene);
  }
  const std::string title = "prism view: " + scene_name + " (" + choice.name + ")";
  window.set_title(title);

  viewer::FrameRate rate;
  Image frame;  // the frame on screen, as the backend rendered it
  std::vector<uint8_t> captured;
  int captured_width = 0, captured_height = 0;
  int frames = 0;
  bool screenshot_pending = false;  // P: saved once the next frame is on screen
  double first_ms = 0, later_ms = 0, render_ms_total = 0, fly_seconds = 0;
  Clock::time_point last_swap = Clock::now(), last_title = last_swap - std::chrono::seconds(1);
  while (true) {
    window.poll_events();
    const viewer::Input in = window.take_input();
    if (in.quit) break;
    if (in.screenshot) screenshot_pending = true;
    if (in.reset) controller.reset();
    if (in.drag_x != 0 || in.drag_y != 0)
      controller.orbit(-in.drag_x * kOrbitRadiansPerPixel, in.drag_y * kOrbitRadiansPerPixel);
    if (in.scroll != 0) controller.dolly(std::pow(kDollyPerClick, in.scroll));
    if (in.fly_right || in.fly_up || in.fly_forward) {
      const double step = controller.distance() * fly_seconds;
      controller.fly(in.fly_right * step, in.fly_up * step, in.fly_forward * step);
    }

    const auto [fb_width, fb_height] = window.framebuffer_size();
    if (fb_width <= 0 || fb_height <= 0) {  // minimised
      window.wait_events(0.1);
      last_swap = Clock::now();
      continue;
    }
    settings.image.width = std::clamp(int(std::lround(fb_width * scale)), 1, 16384);
    settings.image.height = std::clamp(int(std::lround(fb_height * scale)), 1, 16384);
    settings.camera = controller.camera();

    const Clock::time_point render_start = Clock::now();
    {
      viewer::ContextRelease release(window);
      frame = choice.backend->render(settings);
    }
    render_ms_total += ms_since(render_start);
    if (frame.width != settings.image.width || frame.height != settings.image.height ||
        frame.rgb.size() != size_t(frame.width) * frame.height * 3)
      throw RuntimeError("backend '" + choice.name + "' returned a " + std::to_string(frame.width) + "x" +
                         std::to_string(frame.height) + " frame for a " + std::to_string(settings.image.width) + "x" +
                         std::to_string(settings.image.height) + " request");

    const viewer::Rgba8Image pixels{frame.width, frame.height, viewer::to_rgba8(frame)};
    const int overlay_scale = viewer::overlay_scale(fb_width);
    const viewer::Rgba8Image overlay = viewer::overlay_image(
        viewer::status_line(rate, choice.name, frame.width, frame.height,
                            viewer::chars_that_fit(fb_width, overlay_scale)),
        overlay_scale, fb_width);
    display.draw(pixels, overlay, fb_width, fb_height);
    if (!args.capture.empty()) {
      // From the back buffer, before the swap: after it the back buffer is
      // undefined (and reads as zeros under Xvfb).
      captured = display.read_back(fb_width, fb_height);
      captured_width = fb_width;
      captured_height = fb_height;
    }
    window.swap_buffers();

    const Clock::time_point now = Clock::now();
    const double frame_ms = std::chrono::duration<double, std::milli>(now - last_swap).count();
    last_swap = now;
    fly_seconds = std::min(frame_ms / 1000.0, kMaxFlyStepSeconds);
    rate.add(frame_ms);
    (frames == 0 ? first_ms : later_ms) += frame_ms;
    ++frames;
    if (rate.has_value() && std::chrono::duration<double>(now - last_title).count() >= 0.5) {
      char fps[64];
      std::snprintf(fps, sizeof fps, " %.1f fps", rate.fps());
      window.set_title(title + fps);
      last_title = now;
    }
    if (screenshot_pending) {
      save_screenshot(frame);
      screenshot_pending = false;
      last_swap = Clock::now();  // the write is not part of the next frame's time
    }
    if (args.frames && frames >= *args.frames) break;
  }

  if (frames > 0) {
    std::printf("prism view: %d frame%s at %dx%d with %s: first %.1f ms", frames, frames == 1 ? "" : "s",
                settings.image.width, settings.image.height, choice.name.c_str(), first_ms);
    if (frames > 1) std::printf(", then %.2f ms mean", later_ms / (frames - 1));
    std::printf(" (render %.2f ms mean); display context: %s\n", render_ms_total / frames,
                window.context_api().c_str());
  }
  if (!args.capture.empty()) {
    if (captured.empty()) throw RuntimeError("--capture: the window closed before a frame was shown");
    write_image(viewer::from_rgba8(captured, captured_width, captured_height), args.capture);
  }
  return 0;
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* sub = app.add_subcommand("view", "Show a scene live in a window (needs an X display)");
  sub->footer(kControls);
  sub->add_option("scene", args->scene, "Scene file (JSON)")->required();
  sub->add_option("-b,--backend", args->backend, "Backend name, or auto for the fastest usable one (default opengl)");
  sub->add_option("--width", args->width, "Initial window width in pixels (1..16384; default the scene's image width)");
  sub->add_option("--height", args->height,
                  "Initial window height in pixels (1..16384; default the scene's image height)");
  sub->add_option("--spp", args->spp, "Samples per pixel (1..4096)");
  sub->add_option("--max-depth", args->max_depth, "Surface interactions per camera sample (1..64)");
  sub->add_option("--scale", args->scale,
                  "Render at this fraction of the window's size, shown enlarged (0 < S <= 1; default 1)");
  sub->add_option("--frames", args->frames, "Quit after this many frames (for automation)");
  sub->add_option("--capture", args->capture,
                  "Write the last frame shown, status line included, to this .png (window pixels as displayed)");
  return [args] { return run_view(*args); };
}

}  // namespace prism::cli
