#include "x_server.hpp"

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <thread>
#include <vector>

extern char** environ;

namespace prism::view_test {

std::string find_xvfb() {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "/usr/bin:/bin");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const std::string candidate = (folder.empty() ? "." : folder) + "/Xvfb";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

XServer::XServer(const std::filesystem::path& log_file) {
  const std::string xvfb = find_xvfb();
  if (xvfb.empty()) {
    error_ = "Xvfb is not installed (Debian package xvfb)";
    return;
  }
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    error_ = std::string("pipe: ") + std::strerror(errno);
    return;
  }
  // The write end must survive the exec: dup it without O_CLOEXEC in the child.
  const int child_fd = 3;
  std::vector<std::string> args = {xvfb, "-displayfd", std::to_string(child_fd), "-screen", "0", "1280x1024x24",
                                   "-nolisten", "tcp"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fds[1], child_fd);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, xvfb.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    error_ = "cannot start " + xvfb + ": " + std::strerror(rc);
    return;
  }
  pid_ = pid;
  // Xvfb writes the display number and a newline once it accepts clients.
  std::string number;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (number.find('\n') == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fds[0], POLLIN, 0};
    if (::poll(&p, 1, int(left.count())) <= 0) continue;
    char buffer[32];
    const ssize_t got = ::read(fds[0], buffer, sizeof buffer);
    if (got <= 0) break;  // Xvfb exited
    number.append(buffer, size_t(got));
  }
  ::close(fds[0]);
  if (number.find('\n') == std::string::npos || number.empty() || number[0] < '0' || number[0] > '9') {
    error_ = "Xvfb did not report a display (see " + log_file.string() + ")";
    return;
  }
  display_ = ":" + number.substr(0, number.find('\n'));
}

XServer::~XServer() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  int status = 0;
  for (int i = 0; i < 500; ++i) {
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_ || (r < 0 && errno != EINTR)) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid_, SIGKILL);
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
}

namespace {

// Xlib's default handler prints the error and exits the whole test binary;
// this one keeps the error for the request that caused it to report.
XErrorEvent last_x_error{};

int record_x_error(Display* /*display*/, XErrorEvent* error) {
  last_x_error = *error;
  return 0;
}

}  // namespace

XClient::XClient(const std::string& display) {
  XSetErrorHandler(record_x_error);
  display_ = XOpenDisplay(display.c_str());
}

XClient::~XClient() {
  if (display_) XCloseDisplay(display_);
}

namespace {

// Depth-first over the window tree: the first viewable window titled `prefix...`.
Window search(Display* display, Window window, const std::string& prefix) {
  char* name = nullptr;
  if (XFetchName(display, window, &name) && name) {
    const bool match = std::strncmp(name, prefix.c_str(), prefix.size()) == 0;
    XFree(name);
    XWindowAttributes attributes;
    if (match && XGetWindowAttributes(display, window, &attributes) && attributes.map_state == IsViewable)
      return window;
  }
  Window root = 0, parent = 0, *children = nullptr;
  unsigned count = 0;
  Window found = 0;
  if (XQueryTree(display, window, &root, &parent, &children, &count)) {
    for (unsigned i = 0; i < count && !found; ++i) found = search(display, children[i], prefix);
    if (children) XFree(children);
  }
  return found;
}

}  // namespace

unsigned long XClient::find_window(const std::string& prefix, double seconds) {
  if (!display_) return 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  do {
    if (Window w = search(display_, DefaultRootWindow(display_), prefix)) return w;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  } while (std::chrono::steady_clock::now() < deadline);
  return 0;
}

// Waits until the server has handled every request sent, and returns the
// error code of a request that failed meanwhile (0: none).
int XClient::sync_for_error() {
  last_x_error = XErrorEvent{};
  XSync(display_, False);
  if (last_x_error.error_code == 0) return 0;
  char text[128] = "";
  XGetErrorText(display_, last_x_error.error_code, text, sizeof text);
  char where[64];
  std::snprintf(where, sizeof where, " (request %d, resource 0x%lx)", int(last_x_error.request_code),
                last_x_error.resourceid);
  last_error_ = std::string(text) + where;
  return last_x_error.error_code;
}

int XClient::send(unsigned long window, long mask, void* event) {
  XSendEvent(display_, window, True, mask, static_cast<XEvent*>(event));
  return sync_for_error();
}

bool XClient::tap_key(unsigned long window, const char* keysym_name) {
  XEvent event{};
  XKeyEvent& key = event.xkey;
  key.display = display_;
  key.window = window;
  key.root = DefaultRootWindow(display_);
  key.subwindow = None;
  key.x = key.y = key.x_root = key.y_root = 1;
  key.same_screen = True;
  key.keycode = XKeysymToKeycode(display_, XStringToKeysym(keysym_name));
  key.type = KeyPress;
  key.time = ++time_;
  if (send(window, KeyPressMask, &event) != 0) return false;
  key.type = KeyRelease;
  key.time = ++time_;
  const int release = send(window, KeyReleaseMask, &event);
  return release == 0 || release == BadWindow;  // BadWindow: the press closed it
}

bool XClient::resize(unsigned long window, int width, int height) {
  XResizeWindow(display_, window, unsigned(width), unsigned(height));
  return sync_for_error() == 0;
}

bool XClient::drag(unsigned long window, int x0, int y0, int x1, int y1) {
  auto motion = [&](int x, int y, unsigned state) {
    XEvent event{};
    XMotionEvent& m = event.xmotion;
    m.type = MotionNotify;
    m.display = display_;
    m.window = window;
    m.root = DefaultRootWindow(display_);
    m.x = m.x_root = x;
    m.y = m.y_root = y;
    m.state = state;
    m.same_screen = True;
    m.time = ++time_;
    return send(window, PointerMotionMask, &event) == 0;
  };
  auto button = [&](int type, int x, int y) {
    XEvent event{};
    XButtonEvent& b = event.xbutton;
    b.type = type;
    b.display = display_;
    b.window = window;
    b.root = DefaultRootWindow(display_);
    b.x = b.x_root = x;
    b.y = b.y_root = y;
    b.button = Button1;
    b.state = type == ButtonRelease ? Button1Mask : 0;
    b.same_screen = True;
    b.time = ++time_;
    return send(window, type == ButtonPress ? ButtonPressMask : ButtonReleaseMask, &event) == 0;
  };
  return motion(x0, y0, 0) && button(ButtonPress, x0, y0) && motion((x0 + x1) / 2, (y0 + y1) / 2, Button1Mask) &&
         motion(x1, y1, Button1Mask) && button(ButtonRelease, x1, y1);
}

}  // namespace prism::view_test
