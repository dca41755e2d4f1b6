// Drawing the frame into the window: the frame as an RGBA8 texture fetched
// texel by texel (no filtering, no colour conversion: the bytes are already
// the 8-bit sRGB codes a .png from prism holds), the status band blended over
// its top-left corner, and reading the back buffer for --capture.
// Needs the window's context current for every call, construction and
// destruction included. Exported from libprism_view.so like window.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include "bitmap_font.hpp"

#ifndef PRISM_VIEW_API
#define PRISM_VIEW_API __attribute__((visibility("default")))
#endif

namespace prism::viewer {

class PRISM_VIEW_API GlDisplay {
 public:
  GlDisplay();  // throws RuntimeError when the shaders do not build
  ~GlDisplay();
  GlDisplay(const GlDisplay&) = delete;
  GlDisplay& operator=(const GlDisplay&) = delete;

  // Draws `frame` (row 0 at the top) stretched over the whole
  // viewport_width x viewport_height framebuffer, nearest texel (1:1 when
  // the sizes agree), then `overlay` unscaled at the top-left.
  void draw(const Rgba8Image& frame, const Rgba8Image& overlay, int viewport_width, int viewport_height);

  // The back buffer's pixels as RGBA8, row 0 at the top. Call before the
  // buffers are swapped.
  std::vector<uint8_t> read_back(int width, int height);

 private:
  struct Texture {
    unsigned id = 0;
    int width = 0, height = 0;
  };
  void upload(Texture& texture, const Rgba8Image& image);
  void draw_rect(const Texture& texture, int x, int y, int width, int height);

  unsigned program_ = 0, vao_ = 0;
  int u_rect_ = -1, u_viewport_ = -1, u_tex_size_ = -1, u_tex_ = -1;
  Texture frame_, overlay_;
};

}  // namespace prism::viewer
