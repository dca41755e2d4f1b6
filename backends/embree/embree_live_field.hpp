// Helpers for the update tests (embree_update_test.cpp, embree_layers_test.cpp):
// a scene edited in place the way the library API edits a live scene. The
// edited scene is loaded from JSON and its changed objects copied into the
// prepared one; expected images come from a fresh backend prepared on the
// edited scene, never from the code under test.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "embree_test_scenes.hpp"

namespace prism::embree::testing {

inline std::string sphere(const glm::dvec3& c, double radius, const std::string& material = "matte") {
  return R"({"type": "sphere", "material": ")" + material + "\", \"center\": " + vec(c.x, c.y, c.z) +
         ", \"radius\": " + num(radius) + "}";
}

// A scene being edited: `objects` (JSON) is what it holds now; `scene` was
// prepared by the backends under test and is edited in place; `edited` is
// loaded afresh from `objects` after every edit.
struct LiveField {
  glm::ivec3 cells;  // spheres per axis, 2 apart
  std::vector<std::string> objects;
  Scene scene;
  Scene edited;

  // nx * ny * nz spheres (ids 1..) on a jittered grid centred on the origin,
  // above a mirror floor (id 0, a plane: tested beside the BVH).
  explicit LiveField(glm::ivec3 n, uint64_t seed = 1) : cells(n) {
    Rng rng(seed);
    const char* materials[] = {"matte", "mirror", "glass", "shiny"};
    objects.push_back(R"({"type": "plane", "point": [0, )" + num(-n.y - 1.0) +
                      R"(, 0], "normal": [0, 1, 0], "material": "mirror"})");
    for (int i = 0; i < n.x; ++i)
      for (int j = 0; j < n.y; ++j)
        for (int k = 0; k < n.z; ++k) {
          const glm::dvec3 c = 2.0 * glm::dvec3(i, j, k) - glm::dvec3(n - 1) +
                               glm::dvec3(uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3));
          objects.push_back(sphere(c, uniform(rng, 0.25, 0.6), materials[rng() % 4]));
        }
    scene = load_field();
    edited = load_field();
  }

  Scene load_field() const {
    std::string list;
    for (const auto& o : objects) list += (list.empty() ? "" : ",") + o;
    const double d = 3.5 * std::max({cells.x, cells.y, cells.z});
    const std::string json = R"({"prism": 1,
      "camera": {"position": )" + vec(0.2 * d, 0.5 * d, -d) + R"(, "look_at": [0, 0, 0], "fov_y": 45},
      "background": {"color": [0.1, 0.2, 0.4]}, "ambient": [0.05, 0.05, 0.05],
      "materials": {"matte": {"color": [0.9, 0.4, 0.2]}, "mirror": {"reflect": 0.7},
                    "glass": {"ior": 1.5, "absorb": [0.1, 0.2, 0.3]}, "shiny": {"specular": 0.6, "shininess": 50}},
      "lights": [{"type": "point", "position": )" + vec(0.3 * d, d, -0.5 * d) + R"(, "intensity": 1.2},
                 {"type": "directional", "direction": [-1, -2, 1], "intensity": 0.5}],
      "objects": [)" + list + "]}";
    return load_scene_from_string(json, ".", registry(), "<live field>");
  }

  // Objects `ids` become `jsons`, in `edited` and then in `scene`.
  SceneChanges set(const std::vector<uint32_t>& ids, const std::vector<std::string>& jsons) {
    for (size_t k = 0; k < ids.size(); ++k) objects[ids[k]] = jsons[k];
    edited = load_field();
    for (uint32_t id : ids) scene.objects[id] = edited.objects[id];
    SceneChanges changes;
    changes.objects = ids;
    std::ranges::sort(changes.objects);
    changes.objects.erase(std::unique(changes.objects.begin(), changes.objects.end()), changes.objects.end());
    return changes;
  }
  SceneChanges set(uint32_t id, const std::string& json) { return set(std::vector<uint32_t>{id}, {json}); }
  SceneChanges move(uint32_t id, const glm::dvec3& center, double radius) { return set(id, sphere(center, radius)); }

  SceneChanges append(const std::string& json) {
    objects.push_back(json);
    edited = load_field();
    scene.objects.push_back(edited.objects.back());
    SceneChanges changes;
    changes.objects_added_or_removed = true;
    return changes;
  }
  SceneChanges erase(uint32_t id) {
    objects.erase(objects.begin() + id);
    edited = load_field();
    scene.objects.erase(scene.objects.begin() + id);
    SceneChanges changes;
    changes.objects_added_or_removed = true;
    return changes;
  }
};

// `json` (an object) with another material.
inline std::string with_material(std::string json, const std::string& material) {
  const std::string key = "\"material\": \"";
  const size_t start = json.find(key) + key.size();
  return json.replace(start, json.find('"', start) - start, material);
}

inline RenderSettings small_frame() {
  RenderSettings settings;
  settings.image = ImageSettings{96, 64, 1, 4};
  settings.aov_id = true;
  return settings;
}

inline Image fresh_render(const std::string& backend, const Scene& scene) {
  const auto fresh = create_backend(backend);
  fresh->prepare(scene);
  return fresh->render(small_frame());
}

inline bool bit_equal(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// `backend`'s image of its (updated) scene is that of a fresh `reference`
// backend prepared on the edited scene, bit for bit.
inline void expect_fresh_image(Backend& backend, const Scene& edited, const std::string& reference) {
  const Image got = backend.render(small_frame());
  const Image want = fresh_render(reference, edited);
  EXPECT_TRUE(bit_equal(got.rgb, want.rgb)) << "rgb differs from a fresh " << reference;
  EXPECT_TRUE(bit_equal(got.id, want.id)) << "ids differ from a fresh " << reference;
}

inline bool shows(const Image& image, int32_t id) { return std::ranges::count(image.id, float(id)) > 0; }

}  // namespace prism::embree::testing
