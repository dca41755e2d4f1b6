#include "prism/backend.hpp"

#include <string>

#include "prism/errors.hpp"

namespace prism {

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
