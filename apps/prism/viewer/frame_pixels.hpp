// Converting between a rendered Image (linear float RGB, top row first) and
// the 8-bit RGBA the window shows, with exactly the quantisation prism uses
// for PNG output: round(255 * srgb_oetf(clamp(v, 0, 1))) in double
// (prism::linear_to_srgb, the IEC 61966-2-1 curve).
#pragma once

#include <cstdint>
#include <vector>

#include "prism/backend.hpp"

namespace prism::viewer {

// The 8-bit sRGB code of one linear value, as a .png written by prism stores it.
uint8_t srgb8(float linear);

// RGBA8 (alpha 255), row 0 = the image's top row.
std::vector<uint8_t> to_rgba8(const Image& image);

// An Image whose write_image(.png) stores exactly these 8-bit codes
// (RGBA8, row 0 at the top; alpha ignored). Each code c becomes
// srgb_to_linear(c / 255), which srgb8() maps back to c.
Image from_rgba8(const std::vector<uint8_t>& rgba, int width, int height);

}  // namespace prism::viewer
