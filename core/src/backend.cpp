#include "prism/backend.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
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
        "(the reference backend runs each plugin's float instantiation, the GPU backends its float GLSL)");
}

void assign_channel(std::vector<float>& channel, size_t n, float value) {
  constexpr size_t kPopulateFrom = size_t(1) << 20;  // bytes; below this the call costs more than it saves
  if (n > channel.capacity() && n * sizeof(float) >= kPopulateFrom) {
    std::vector<float>().swap(channel);  // the old values need no copy
    channel.reserve(n);
#ifdef MADV_POPULATE_WRITE
    const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
    const uintptr_t begin = (uintptr_t(channel.data()) + page - 1) & ~(page - 1);
    const uintptr_t end = uintptr_t(channel.data() + n) & ~(page - 1);
    if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);  // a hint only
#endif
  }
  channel.assign(n, value);
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
