// The scenes of the live-update tests (gpu_update_test.cpp on the host,
// gpu_update_backend_test.cpp through the GPU backends): a grid of spheres
// and the variants an edit turns it into, as scene JSON, so that an edited
// object, material or light is copied from a scene loaded independently.
#pragma once

#include <string>

namespace prism::gpu::testing_scenes {

struct Options {
  int count = 200;            // spheres in rows of 20, every seventh red
  int moved = -1;             // this sphere moves by (0.3, 0.2, -2)
  int removed = -1;           // this sphere is left out
  int scattered_every = 0;    // > 0: every n-th sphere flies hundreds of units away
  bool red_is_glass = false;  // the red material turns dielectric
  double light_x = 4;         // the point light's x
  bool second_light = false;  // a second point light
  double background_red = 0.1;
  int width = 64, height = 48;
};

inline std::string spheres_json(const Options& o) {
  std::string objects;
  for (int i = 0; i < o.count; ++i) {
    if (i == o.removed) continue;
    double x = (i % 20 - 9.5) * 0.9, y = (i / 20 - 5) * 0.9, z = 0;
    if (i == o.moved) x += 0.3, y += 0.2, z -= 2;
    if (o.scattered_every && i % o.scattered_every == 0) x += 500 + i, z += 300;
    objects += std::string(objects.empty() ? "" : ", ") + R"({"type": "sphere", "center": [)" + std::to_string(x) + ", " +
               std::to_string(y) + ", " + std::to_string(z) + R"(], "radius": 0.4)" +
               (i % 7 == 0 ? R"(, "material": "red")" : "") + "}";
  }
  return R"({"prism": 1, "camera": {"position": [0, 0, -22], "look_at": [0, 0, 0], "fov_y": 45},
    "image": {"width": )" + std::to_string(o.width) + R"(, "height": )" + std::to_string(o.height) + R"(},
    "background": {"color": [)" + std::to_string(o.background_red) + R"(, 0.2, 0.3]}, "ambient": [0.05, 0.05, 0.05],
    "materials": {"red": {"color": [0.9, 0.1, 0.1])" + (o.red_is_glass ? R"(, "ior": 1.5)" : "") + R"(}},
    "lights": [{"type": "point", "position": [)" + std::to_string(o.light_x) + R"(, 8, -10]})" +
         (o.second_light ? R"(, {"type": "point", "position": [-3, -8, -12], "intensity": 0.5})" : "") + R"(],
    "objects": [)" + objects + "]}";
}

}  // namespace prism::gpu::testing_scenes
