#include "overlay.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace prism::viewer {

void FrameRate::add(double frame_ms) {
  if (!skipped_first_) {
    skipped_first_ = true;
    return;
  }
  ++frames_;
  sum_ms_ += frame_ms;
  // In the first window the running mean is shown; afterwards each completed
  // window replaces the value.
  if (sum_ms_ >= kWindowMs) {
    shown_frames_ = frames_;
    shown_ms_ = sum_ms_ / frames_;
    frames_ = 0;
    sum_ms_ = 0.0;
    first_window_done_ = true;
  } else if (!first_window_done_) {
    shown_frames_ = frames_;
    shown_ms_ = sum_ms_ / frames_;
  }
}

std::string status_line(const FrameRate& rate, const std::string& backend, int width, int height, int max_chars) {
  char text[3][160];
  if (rate.has_value()) {
    std::snprintf(text[0], sizeof text[0], "%.1f FPS  %.1f MS  %s  %dx%d", rate.fps(), rate.ms(), backend.c_str(),
                  width, height);
    std::snprintf(text[1], sizeof text[1], "%.1f FPS %.1f MS %s %dx%d", rate.fps(), rate.ms(), backend.c_str(), width,
                  height);
    std::snprintf(text[2], sizeof text[2], "%.0fFPS %.0fMS %s %dx%d", rate.fps(), rate.ms(), backend.c_str(), width,
                  height);
  } else {
    std::snprintf(text[0], sizeof text[0], "-- FPS  %s  %dx%d", backend.c_str(), width, height);
    std::snprintf(text[1], sizeof text[1], "-- FPS %s %dx%d", backend.c_str(), width, height);
    std::snprintf(text[2], sizeof text[2], "--FPS %s %dx%d", backend.c_str(), width, height);
  }
  for (const char* candidate : text)
    if (int(std::strlen(candidate)) <= max_chars) return candidate;
  return text[2];
}

std::string with_refinement(const std::string& status, int shown_spp, int target_spp, int max_chars) {
  if (target_spp <= 1) return status;
  const std::string longer = status + " " + std::to_string(shown_spp) + "/" + std::to_string(target_spp) + " SPP";
  return int(longer.size()) <= max_chars ? longer : status;
}

int chars_that_fit(int pixels, int scale) {
  // n characters take (n * advance - 1 + 2 * padding) * scale pixels.
  return std::max(0, (pixels / scale - 2 * kOverlayPadding + (kGlyphAdvance - kGlyphWidth)) / kGlyphAdvance);
}

int overlay_scale(int window_width) { return window_width >= 640 ? 2 : 1; }

Rgba8Image overlay_image(const std::string& text, int scale, int max_width) {
  return overlay_image(std::vector<std::string>{text}, scale, max_width);
}

Rgba8Image overlay_image(const std::vector<std::string>& lines, int scale, int max_width) {
  int widest = 0;
  for (const std::string& line : lines) widest = std::max(widest, text_width(line, scale));
  Rgba8Image image;
  image.width = std::max(1, std::min(widest + 2 * kOverlayPadding * scale, max_width));
  image.height = overlay_height(std::max<int>(1, int(lines.size())), scale);
  image.rgba.resize(size_t(image.width) * image.height * 4);
  for (size_t p = 0; p < image.rgba.size(); p += 4) {
    image.rgba[p + 0] = image.rgba[p + 1] = image.rgba[p + 2] = 0;
    image.rgba[p + 3] = 160;
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    const int y = (kOverlayPadding + int(i) * (kGlyphHeight + kOverlayLineGap)) * scale;
    draw_text(image, kOverlayPadding * scale, y, lines[i], scale, {255, 255, 255, 255});
  }
  return image;
}

const std::vector<std::string>& key_help_lines() {
  // Only what the bitmap font draws: capitals, digits and . , : / - + = _ % ( ) ?
  static const std::vector<std::string> lines = {
      "DRAG: ORBIT ABOUT THE TARGET", "WHEEL: DOLLY TO THE TARGET", "W A S D: FLY FORWARD, LEFT, BACK, RIGHT",
      "E, SPACE / Q, SHIFT: FLY UP / DOWN", "R: BACK TO THE SCENE CAMERA", "P: SAVE THE FRAME AS PNG",
      "C: PRINT THE CAMERA AS JSON", "H: HIDE THESE KEYS", "ESC: QUIT"};
  return lines;
}

}  // namespace prism::viewer
