#include "window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "prism/errors.hpp"

namespace prism::viewer {

namespace {

std::string glfw_last_error;  // the most recent message from GLFW's error callback

void on_glfw_error(int code, const char* description) {
  glfw_last_error = (description ? description : "unknown error") + std::string(" (GLFW error ") +
                    std::to_string(code) + ")";
}

Window* self(GLFWwindow* window) { return static_cast<Window*>(glfwGetWindowUserPointer(window)); }

// One try at a window with a GL 3.3 core context made by `api`.
GLFWwindow* try_create(int width, int height, const std::string& title, int api) {
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_CREATION_API, api);
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);  // the frame arrives sRGB-encoded already
  glfwWindowHint(GLFW_DEPTH_BITS, 0);
  glfwWindowHint(GLFW_STENCIL_BITS, 0);
  glfwWindowHint(GLFW_SAMPLES, 0);
  return glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
}

}  // namespace

struct Window::Callbacks {
  static void key(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/) {
    if (action != GLFW_PRESS) return;
    Input& in = self(w)->input_;
    if (key == GLFW_KEY_ESCAPE) in.quit = true;
    if (key == GLFW_KEY_P) in.screenshot = true;
    if (key == GLFW_KEY_R) in.reset = true;
    if (key == GLFW_KEY_C) in.print_camera = true;
    if (key == GLFW_KEY_H) in.toggle_help = true;
  }
  static void refresh(GLFWwindow* w) { self(w)->input_.refresh = true; }
  static void cursor(GLFWwindow* w, double x, double y) {
    Window* win = self(w);
    if (win->have_last_ && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
      win->input_.drag_x += x - win->last_x_;
      win->input_.drag_y += y - win->last_y_;
    }
    win->last_x_ = x;
    win->last_y_ = y;
    win->have_last_ = true;
  }
  static void scroll(GLFWwindow* w, double /*dx*/, double dy) { self(w)->input_.scroll += dy; }
  static void close(GLFWwindow* w) { self(w)->input_.quit = true; }
};

Window::Window(int width, int height, const std::string& title) {
  glfwSetErrorCallback(on_glfw_error);
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw RuntimeError("no display: the DISPLAY environment variable is not set (a window needs an X server; "
                       "without a screen, run it under Xvfb, e.g. xvfb-run)");
  if (!glfwInit())
    throw RuntimeError("cannot open display '" + std::string(display) + "': " + glfw_last_error);
  window_ = try_create(width, height, title, GLFW_EGL_CONTEXT_API);
  context_api_ = "EGL";
  std::string egl_error = glfw_last_error;
  if (!window_) {
    window_ = try_create(width, height, title, GLFW_NATIVE_CONTEXT_API);
    context_api_ = "GLX";
  }
  if (!window_) {
    const std::string native_error = glfw_last_error;
    glfwTerminate();
    throw RuntimeError("cannot open a window with an OpenGL 3.3 core context: EGL: " + egl_error +
                       "; native: " + native_error);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, Callbacks::key);
  glfwSetCursorPosCallback(window_, Callbacks::cursor);
  glfwSetScrollCallback(window_, Callbacks::scroll);
  glfwSetWindowCloseCallback(window_, Callbacks::close);
  glfwSetWindowRefreshCallback(window_, Callbacks::refresh);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);  // frames are paced by rendering, and the frame rate shown is the renderer's
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::pair<int, int> Window::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
void Window::poll_events() { glfwPollEvents(); }
void Window::wait_events(double seconds) { glfwWaitEventsTimeout(seconds); }
void Window::swap_buffers() { glfwSwapBuffers(window_); }
void Window::make_current() { glfwMakeContextCurrent(window_); }
void Window::release_current() { glfwMakeContextCurrent(nullptr); }

Input Window::take_input() {
  Input in = input_;
  input_ = Input{};
  auto held = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS; };
  in.fly_right = int(held(GLFW_KEY_D)) - int(held(GLFW_KEY_A));
  in.fly_forward = int(held(GLFW_KEY_W)) - int(held(GLFW_KEY_S));
  in.fly_up = int(held(GLFW_KEY_E) || held(GLFW_KEY_SPACE)) -
              int(held(GLFW_KEY_Q) || held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT));
  return in;
}

}  // namespace prism::viewer
