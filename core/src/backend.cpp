#include "prism/backend.hpp"

#include <string>

#include "prism/errors.hpp"

namespace prism {

const char* precision_name(Precision precision) {
  switch (precision) {
    case Precision::float32:
      return "float";
    case Precision::float64:
      return "double";
    case Precision::automatic:
      break;
  }
  return "auto";
}

std::optional<Precision> parse_precision(std::string_view text) {
  for (Precision p : {Precision::automatic, Precision::float32, Precision::float64})
    if (text == precision_name(p)) return p;
  return std::nullopt;
}

void Backend::set_precision(Precision precision) {
  if (precision == Precision::float32)
    throw InputError(
        "this backend computes in double only; --precision float is for a backend with a float path "
        "(the reference backend runs each plugin's float instantiation)");
}

void check_region(const RenderSettings& settings) {
  if (!settings.region) return;
  const PixelRect& r = *settings.region;
  const ImageSettings& image = settings.image;
  if (r.width < 1 || r.height < 1 || r.x < 0 || r.y < 0 || r.x > image.width - r.width ||
      r.y > image.height - r.height)
    throw InputError("region " + std::to_string(r.width) + "x" + std::to_string(r.height) + " at (" +
                     std::to_string(r.x) + ", " + std::to_string(r.y) + ") is not a non-empty part of the " +
                     std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
}

}  // namespace prism
