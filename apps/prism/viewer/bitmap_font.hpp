// A tiny 5x7 bitmap font, drawn for the viewer's status line: digits,
// capitals, a lower-case x and a few symbols. Other lower-case letters are
// drawn as capitals; anything else as '?'.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace prism::viewer {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;
constexpr int kGlyphAdvance = 6;  // one blank column between characters

// Seven rows of five characters, '#' for a lit pixel, row 0 at the top.
using Glyph = std::array<std::string_view, kGlyphHeight>;

// The glyph drawn for `c`.
const Glyph& glyph_for(char c);
// True when the table has a glyph of its own for `c` (not the '?' fallback).
bool has_glyph(char c);

// An RGBA8 picture, row 0 at the top.
struct Rgba8Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;
};

// Draws `text` in `colour` into `image` with its top-left corner at (x, y),
// each font pixel as a scale x scale block; what falls outside is clipped.
void draw_text(Rgba8Image& image, int x, int y, std::string_view text, int scale, const std::array<uint8_t, 4>& colour);

// Width in pixels of `text` at `scale` (no trailing blank column).
int text_width(std::string_view text, int scale);

}  // namespace prism::viewer
