// The viewer's GLFW window: a GL 3.3 core context for display (EGL first,
// the native GLX path if that fails), input gathered by callbacks, and the
// context switching the backends need.
// Lives in libprism_view.so, exported for `prism view` only: this header is
// not installed (prism/view_window.hpp is the installed interface).
#pragma once

#include <string>
#include <utility>

#ifndef PRISM_VIEW_API
#define PRISM_VIEW_API __attribute__((visibility("default")))
#endif

struct GLFWwindow;

namespace prism::viewer {

// Input gathered since the last take_input().
struct Input {
  double drag_x = 0, drag_y = 0;  // cursor motion with the left button held, pixels
  double scroll = 0;              // wheel clicks, positive away from the user
  bool screenshot = false;        // P
  bool reset = false;             // R
  bool print_camera = false;      // C
  bool toggle_help = false;       // H
  bool refresh = false;           // the window's contents were damaged: draw again
  bool quit = false;              // Esc or the window's close button
  // Held keys, sampled at take_input(): +1 / -1 / 0 along each fly axis.
  int fly_right = 0, fly_up = 0, fly_forward = 0;
};

class PRISM_VIEW_API Window {
 public:
  // Initialises GLFW and opens the window, its context current on this
  // thread. Throws RuntimeError when there is no display or no usable
  // OpenGL 3.3 core context.
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // "EGL" or "GLX": how the context was created.
  const std::string& context_api() const { return context_api_; }

  std::pair<int, int> framebuffer_size() const;
  void set_title(const std::string& title);
  void poll_events();
  void wait_events(double seconds);
  Input take_input();
  void swap_buffers();

  // The display context, current on this thread or not. Backends with GL
  // contexts of their own make those current inside their calls, so the
  // window's is released around every call into a backend (ContextRelease).
  void make_current();
  void release_current();

  struct Callbacks;  // GLFW's callbacks (window.cpp), filling input_

 private:
  GLFWwindow* window_ = nullptr;
  std::string context_api_;
  Input input_;
  double last_x_ = 0, last_y_ = 0;
  bool have_last_ = false;
};

// Releases the window's context for the duration of a backend call and makes
// it current again afterwards (also when the call throws).
class ContextRelease {
 public:
  explicit ContextRelease(Window& window) : window_(window) { window_.release_current(); }
  ~ContextRelease() { window_.make_current(); }
  ContextRelease(const ContextRelease&) = delete;
  ContextRelease& operator=(const ContextRelease&) = delete;

 private:
  Window& window_;
};

}  // namespace prism::viewer
