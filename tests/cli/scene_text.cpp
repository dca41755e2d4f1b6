#include "scene_text.hpp"

namespace prism::cli_test {

std::string SceneText::text() const {
  std::string out = "{\n";
  auto member = [&](const char* key, const std::string& value) {
    if (!value.empty()) out += std::string("  \"") + key + "\": " + value + ",\n";
  };
  member("prism", prism);
  member("camera", camera);
  member("image", image);
  if (!extra.empty()) out += "  " + extra + ",\n";
  member("lights", lights);
  member("objects", objects);
  if (out.size() >= 2 && out.compare(out.size() - 2, 2, ",\n") == 0) out.erase(out.size() - 2, 1);
  return out + "}\n";
}

}  // namespace prism::cli_test
