// A private X server for the viewer tests (Xvfb on a display it picks
// itself through -displayfd), and a client that finds the viewer's window
// and sends it key presses and a mouse drag as X events.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>

typedef struct _XDisplay Display;

namespace prism::view_test {

// Full path of the Xvfb program on PATH, or empty.
std::string find_xvfb();

class XServer {
 public:
  // Starts `Xvfb -displayfd FD -screen 0 1280x1024x24 -nolisten tcp`, its
  // output going to `log_file`. ok() says whether it came up.
  explicit XServer(const std::filesystem::path& log_file);
  ~XServer();  // SIGTERM, then SIGKILL if it lingers
  XServer(const XServer&) = delete;
  XServer& operator=(const XServer&) = delete;

  bool ok() const { return !display_.empty(); }
  const std::string& display() const { return display_; }  // ":N"
  const std::string& error() const { return error_; }

 private:
  pid_t pid_ = -1;
  std::string display_, error_;
};

// An X client connection for driving a window.
class XClient {
 public:
  explicit XClient(const std::string& display);
  ~XClient();
  XClient(const XClient&) = delete;
  XClient& operator=(const XClient&) = delete;

  bool ok() const { return display_ != nullptr; }
  // A mapped top-level window whose title starts with `prefix`, waiting up to
  // `seconds` for it; 0 when none appears.
  unsigned long find_window(const std::string& prefix, double seconds);
  // Presses and releases the key `keysym_name` ("p", "Escape", "r"); false
  // when the server refused an event. The window may close on the press (Esc
  // quits): a release that finds it gone is no error, as for a real keyboard.
  bool tap_key(unsigned long window, const char* keysym_name);
  // Resizes the window (there is no window manager to say otherwise); false
  // when the server refused it.
  bool resize(unsigned long window, int width, int height);
  // Moves to (x0, y0), presses the left button, moves to (x1, y1), releases;
  // false when the server refused an event.
  bool drag(unsigned long window, int x0, int y0, int x1, int y1);
  // The last X error the server reported, as text ("" when none).
  const std::string& last_error() const { return last_error_; }

 private:
  // Sends and waits for the server's answer: the X error code, 0 for none.
  int send(unsigned long window, long mask, void* event);
  int sync_for_error();
  Display* display_ = nullptr;
  std::string last_error_;
  unsigned long time_ = 1000;  // event timestamps: non-zero and increasing
};

}  // namespace prism::view_test
