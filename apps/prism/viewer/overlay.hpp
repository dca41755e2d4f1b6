// The status line drawn over the image (top-left): frame rate, frame time,
// backend and render resolution, on a translucent dark band.
#pragma once

#include <string>
#include <vector>

#include "bitmap_font.hpp"

namespace prism::viewer {

// Frame rate averaged over about half a second; until the first half second
// is complete, over the frames so far. The first frame is left out: it
// carries the window's start-up (mapping, first texture allocation).
class FrameRate {
 public:
  void add(double frame_ms);
  bool has_value() const { return shown_frames_ > 0; }
  double ms() const { return shown_ms_; }  // mean frame time
  double fps() const { return shown_ms_ > 0.0 ? 1000.0 / shown_ms_ : 0.0; }

 private:
  static constexpr double kWindowMs = 500.0;
  bool skipped_first_ = false, first_window_done_ = false;
  int frames_ = 0, shown_frames_ = 0;
  double sum_ms_ = 0.0, shown_ms_ = 0.0;
};

// e.g. "24.8 FPS  40.3 MS  embree  160x90" ("-- FPS" until a frame is
// measured), in the most spacious of three layouts that fits `max_chars`
// (the most compact one, "25FPS 40MS embree 160x90", when none does).
std::string status_line(const FrameRate& rate, const std::string& backend, int width, int height, int max_chars);

// The status line with the refinement's progress, "... 4/16 SPP", when the
// scene has more than 1 spp and it fits in `max_chars`; else `status` alone.
std::string with_refinement(const std::string& status, int shown_spp, int target_spp, int max_chars);

// How many characters fit across `pixels` at `scale`, padding included.
int chars_that_fit(int pixels, int scale);

constexpr int kOverlayPadding = 2;  // font pixels around the text

// 1, or 2 for windows at least 640 pixels wide.
int overlay_scale(int window_width);

// Height in pixels of the band the overlay covers at `scale`.
constexpr int overlay_height(int scale) { return (kGlyphHeight + 2 * kOverlayPadding) * scale; }

// Rows between two lines of text, in font pixels.
constexpr int kOverlayLineGap = 2;

// Height in pixels of a band of `lines` lines at `scale`.
constexpr int overlay_height(int lines, int scale) {
  return (lines * kGlyphHeight + (lines - 1) * kOverlayLineGap + 2 * kOverlayPadding) * scale;
}

// The band: black at alpha 160 behind white text, as wide as the text plus
// padding but at most `max_width` (the window's width).
Rgba8Image overlay_image(const std::string& text, int scale, int max_width);
// The same with one line of text under the other (the status line, then the keys H shows).
Rgba8Image overlay_image(const std::vector<std::string>& lines, int scale, int max_width);

// What each key does, one line each, for the list H shows.
const std::vector<std::string>& key_help_lines();

}  // namespace prism::viewer
