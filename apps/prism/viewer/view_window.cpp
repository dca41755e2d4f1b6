#include "prism/view_window.hpp"

#include "prism/errors.hpp"
#include "viewer/frame_pixels.hpp"
#include "viewer/gl_display.hpp"
#include "viewer/overlay.hpp"
#include "viewer/window.hpp"

namespace prism {

namespace {

constexpr int kMaxSide = 16384;  // as `prism view` and the scene format allow

// Makes the window's context current for one draw and releases it after,
// also when drawing throws: between calls no context of ours is current, so
// a backend's own GL contexts never meet it.
class CurrentContext {
 public:
  explicit CurrentContext(viewer::Window& window) : window_(window) { window_.make_current(); }
  ~CurrentContext() { window_.release_current(); }
  CurrentContext(const CurrentContext&) = delete;
  CurrentContext& operator=(const CurrentContext&) = delete;

 private:
  viewer::Window& window_;
};

void check_frame(const Image& frame) {
  if (frame.width < 1 || frame.height < 1 || frame.rgb.size() != size_t(frame.width) * frame.height * 3)
    throw InputError("ViewWindow::show: the image is " + std::to_string(frame.width) + "x" +
                     std::to_string(frame.height) + " but holds " + std::to_string(frame.rgb.size()) +
                     " floats (width * height * 3 expected)");
}

}  // namespace

struct ViewWindow::Impl {
  Impl(int width, int height, const std::string& title) : window(width, height, title) {}
  viewer::Window window;
  std::unique_ptr<viewer::GlDisplay> display;  // made and destroyed with the context current
  bool open = true;
};

ViewWindow::ViewWindow(int width, int height, const std::string& title) {
  if (width < 1 || width > kMaxSide || height < 1 || height > kMaxSide)
    throw InputError("ViewWindow: size must be 1..16384 x 1..16384, got " + std::to_string(width) + "x" +
                     std::to_string(height));
  impl_ = std::make_unique<Impl>(width, height, title);  // its context is current now
  CurrentContext current(impl_->window);
  impl_->display = std::make_unique<viewer::GlDisplay>();
}

ViewWindow::~ViewWindow() {
  if (!impl_) return;  // moved from
  impl_->window.make_current();  // the display's GL objects go with the context
  impl_->display.reset();
  impl_->window.release_current();
}

ViewWindow::ViewWindow(ViewWindow&&) noexcept = default;
ViewWindow& ViewWindow::operator=(ViewWindow&& other) noexcept {
  if (this != &other) {
    ViewWindow old(std::move(*this));  // closes this window properly
    impl_ = std::move(other.impl_);
  }
  return *this;
}

bool ViewWindow::poll() {
  if (!impl_ || !impl_->open) return false;
  impl_->window.poll_events();
  if (impl_->window.take_input().quit) impl_->open = false;
  return impl_->open;
}

bool ViewWindow::is_open() const { return impl_ && impl_->open; }

bool ViewWindow::show(const Image& frame, const std::string& status) {
  check_frame(frame);
  if (!poll()) return false;
  const auto [fb_width, fb_height] = impl_->window.framebuffer_size();
  if (fb_width <= 0 || fb_height <= 0) return true;  // minimised: nothing to draw on

  const viewer::Rgba8Image pixels{frame.width, frame.height, viewer::to_rgba8(frame)};
  viewer::Rgba8Image overlay;  // empty: no band
  if (!status.empty()) overlay = viewer::overlay_image(status, viewer::overlay_scale(fb_width), fb_width);
  CurrentContext current(impl_->window);
  impl_->display->draw(pixels, overlay, fb_width, fb_height);
  impl_->window.swap_buffers();
  return true;
}

void ViewWindow::set_title(const std::string& title) {
  if (impl_) impl_->window.set_title(title);
}

std::pair<int, int> ViewWindow::size() const { return impl_ ? impl_->window.framebuffer_size() : std::pair{0, 0}; }

}  // namespace prism
