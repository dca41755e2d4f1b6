// The status line's 5x7 font (apps/prism/viewer/bitmap_font.hpp).
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "viewer/bitmap_font.hpp"

namespace prism::viewer {
namespace {

const std::string kCovered =
    " 0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.,:/-+=_%()?";

TEST(BitmapFont, EveryGlyphIsSevenRowsOfFive) {
  for (char c : kCovered) {
    const Glyph& g = glyph_for(c);
    for (const auto& row : g) {
      ASSERT_EQ(row.size(), size_t(kGlyphWidth)) << "glyph '" << c << "'";
      for (char pixel : row) ASSERT_TRUE(pixel == '#' || pixel == ' ') << "glyph '" << c << "'";
    }
  }
}

TEST(BitmapFont, CoversTheStatusLineAndFallsBackToQuestionMark) {
  for (char c : kCovered) EXPECT_TRUE(has_glyph(c)) << "'" << c << "'";
  EXPECT_FALSE(has_glyph('~'));
  EXPECT_FALSE(has_glyph('\n'));
  EXPECT_EQ(&glyph_for('~'), &glyph_for('?'));
  EXPECT_EQ(&glyph_for('e'), &glyph_for('E'));  // lower case drawn as capitals
  EXPECT_NE(&glyph_for('x'), &glyph_for('X'));  // except x, for "160x90"
}

TEST(BitmapFont, NoTwoCharactersLookAlike) {
  std::map<std::string, char> seen;
  for (char c : std::string(" 0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZx.,:/-+=_%()?")) {
    std::string bits;
    for (const auto& row : glyph_for(c)) bits += std::string(row);
    auto [it, inserted] = seen.emplace(bits, c);
    EXPECT_TRUE(inserted) << "'" << c << "' looks like '" << it->second << "'";
  }
}

TEST(BitmapFont, TextWidth) {
  EXPECT_EQ(text_width("", 1), 0);
  EXPECT_EQ(text_width("A", 1), 5);
  EXPECT_EQ(text_width("AB", 1), 11);   // 5 + 1 blank + 5
  EXPECT_EQ(text_width("160x90", 2), 70);  // (6 * 6 - 1) * 2
}

TEST(BitmapFont, DrawsTheDigitOne) {
  // '1' is " ##  " in row 1 and " ### " in row 6: 10 lit pixels in all.
  Rgba8Image image{7, 9, std::vector<uint8_t>(7 * 9 * 4, 0)};
  draw_text(image, 1, 1, "1", 1, {255, 255, 255, 255});
  auto lit = [&](int x, int y) { return image.rgba[(y * 7 + x) * 4] == 255; };
  int count = 0;
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 7; ++x) count += lit(x, y);
  EXPECT_EQ(count, 10);
  EXPECT_TRUE(lit(3, 1));   // top of the stem (glyph column 2, row 0)
  EXPECT_TRUE(lit(2, 2));   // the flag
  EXPECT_TRUE(lit(2, 7));   // the foot, left
  EXPECT_TRUE(lit(4, 7));   // the foot, right
  EXPECT_FALSE(lit(1, 1));
  EXPECT_FALSE(lit(0, 0));
}

TEST(BitmapFont, ScalesAndClips) {
  // At scale 2 the top-left lit pixel of 'T' ("#####") covers a 2x2 block;
  // drawing partly outside the image must not write outside it.
  Rgba8Image image{4, 4, std::vector<uint8_t>(4 * 4 * 4, 0)};
  draw_text(image, -2, -2, "T", 2, {9, 9, 9, 9});
  // Row 0 ("#####") lands at y -2..-1: clipped. The stem (column 2 of rows
  // 1..6) lands at x 2..3 from y 0 down; columns 0..1 stay blank.
  EXPECT_EQ(image.rgba[(0 * 4 + 2) * 4], 9);
  EXPECT_EQ(image.rgba[(1 * 4 + 3) * 4], 9);
  EXPECT_EQ(image.rgba[(0 * 4 + 0) * 4], 0);
  EXPECT_EQ(image.rgba[(3 * 4 + 0) * 4], 0);
  EXPECT_EQ(image.rgba.size(), size_t(64));
}

}  // namespace
}  // namespace prism::viewer
