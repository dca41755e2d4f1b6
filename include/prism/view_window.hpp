// A window that shows rendered frames: what `prism view` draws with, for
// programs built on the library API (prism/api.hpp). Link Prism::view.
//
//   prism::ViewWindow window(640, 360, "my renderer");
//   while (window.show(renderer.render(scene), "frame 12  30.1 FPS")) {
//     // edit the scene for the next frame
//   }
//
// Frames are shown exactly as a .png written by Prism stores them (8-bit
// sRGB), stretched to the window's size, nearest pixel. The window's OpenGL
// context is current only inside these calls, so a backend with OpenGL
// contexts of its own (the `opengl` backend) renders between them with
// nothing to arrange. Use the window from the thread that made it, and one
// window at a time (GLFW is set up and torn down with it).
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "prism/backend.hpp"

#ifndef PRISM_VIEW_API
#define PRISM_VIEW_API __attribute__((visibility("default")))
#endif

namespace prism {

class PRISM_VIEW_API ViewWindow {
 public:
  // Opens a width x height window (1..16384 each). Throws InputError for a
  // bad size and RuntimeError when there is no X display (DISPLAY unset:
  // run under xvfb-run) or no OpenGL 3.3 core context.
  ViewWindow(int width, int height, const std::string& title);
  ~ViewWindow();
  ViewWindow(ViewWindow&&) noexcept;
  ViewWindow& operator=(ViewWindow&&) noexcept;

  // Handles the window's events, then shows `frame` with `status` on a
  // translucent band at its top-left (nothing when empty; letters are drawn
  // as capitals). Returns false, showing nothing, once the user has closed
  // the window or pressed Esc. Throws InputError for an Image whose pixels
  // do not match its size.
  bool show(const Image& frame, const std::string& status = "");

  // Handles the window's events without drawing: false once it was closed.
  bool poll();
  bool is_open() const;

  void set_title(const std::string& title);
  // The drawable size in pixels (0 x 0 while minimised).
  std::pair<int, int> size() const;

  struct Impl;  // the GLFW window and its GL drawing (view_window.cpp)

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace prism
