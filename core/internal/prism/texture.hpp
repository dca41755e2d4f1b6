// Texture decoding and sampling exactly as the scene format fixes it.
#pragma once

#include <cstdint>

#include <filesystem>

#include <glm/glm.hpp>

#include "prism/limits.hpp"
#include "prism/scene.hpp"

namespace prism {

// Decodes PNG/JPG/EXR to linear RGBA float (sRGB curve on 8/16-bit colour
// unless `srgb` is false, unassociated alpha). Throws InputError, also for
// a file of more than `pixels_left` pixels (what the scene's textures before
// it left of limits::kMaxTexturePixels), refused from its header before any
// pixel is allocated.
Texture load_texture(const std::filesystem::path& path, bool srgb,
                     size_t pixels_left = limits::kMaxTexturePixels);

// One texture a scene names: its file, whether its 8/16-bit colour is sRGB,
// and what its errors lead with (its JSON path in a scene file).
struct TextureRequest {
  std::string name;
  std::filesystem::path file;
  bool srgb = true;
  std::string path;
};

// A scene's textures, in the order of `requests`. Reads every header first
// and refuses the set when its distinct files (one file read with one srgb
// setting counts once, however many names it has) hold more than
// `pixels_left` pixels together, before decoding anything; then decodes
// each distinct file once. Refuses NaN and infinite texels, naming the first.
// InputError, led by the failing request's `path`.
std::vector<Texture> load_textures(const std::vector<TextureRequest>& requests,
                                   size_t pixels_left = limits::kMaxTexturePixels);

// Bilinear, repeat wrap; v = 0 is the top row.
glm::dvec4 sample_texture(const Texture& texture, glm::dvec2 uv);

// Background radiance for a miss along `dir` (colour or cube map).
glm::dvec3 background_radiance(const Scene& scene, const glm::dvec3& dir);

// IEC 61966-2-1 transfer functions.
double srgb_to_linear(double encoded);
double linear_to_srgb(double linear);

// The 8-bit code of a linear value: round(255 * linear_to_srgb(clamp(v, 0, 1)))
// exactly, and 0 for NaN. Found in a table of the codes' thresholds, without
// the pow() per value that made a 1280x720 PNG's encoding take ~70 ms.
uint8_t linear_to_srgb8(float linear);

}  // namespace prism
