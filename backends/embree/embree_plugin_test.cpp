// The Embree backend as a plugin, loaded through the registry as `prism`
// loads it: its entry, and bit-identical images and traces against the
// reference backend.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstring>
#include <memory>

#include "embree_test_scenes.hpp"
#include "prism/backend.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

bool bit_equal(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(EmbreeBackend, EntryNamesRanksAndProbes) {
  const auto plugin = registry().backend("embree");
  EXPECT_STREQ(plugin->desc().name, "embree");
  EXPECT_EQ(plugin->desc().speed_rank, 50);
  const PrismBackendProbe probe = plugin->probe();
  EXPECT_EQ(probe.usable, 1) << probe.reason;
  EXPECT_NE(std::strstr(probe.reason, "Embree 3."), nullptr) << probe.reason;
}

// A lit scene with every kind of material, so the whole shading path runs.
Scene lit_scene(uint64_t seed, int count) {
  Rng rng(seed);
  auto types = available_types();
  std::erase(types, "plane");  // a random plane would hide the rest; a floor instead
  const char* materials[] = {"matte", "mirror", "glass", "shiny"};
  std::string objects;
  if (has_primitive("plane")) {
    objects = R"({"type": "plane", "point": [0, -9, 0], "normal": [0, 1, 0], "material": "mirror"},)";
  }
  for (int i = 0; i < count; ++i) {
    std::string o = random_object(rng, types[rng() % types.size()]);
    o.insert(1, std::string("\"material\": \"") + materials[rng() % 4] + "\", ");
    objects += o + (i + 1 < count ? "," : "");
  }
  const std::string json = R"({"prism": 1,
    "camera": {"position": [2, 6, -28], "look_at": [0, 0, 0], "fov_y": 45},
    "background": {"color": [0.1, 0.2, 0.4]}, "ambient": [0.05, 0.05, 0.05], "shadow_ambient": [0.1, 0.1, 0.1],
    "materials": {"matte": {"color": [0.9, 0.4, 0.2]}, "mirror": {"reflect": 0.7},
                  "glass": {"ior": 1.5, "absorb": [0.1, 0.2, 0.3]}, "shiny": {"specular": 0.6, "shininess": 50}},
    "lights": [{"type": "point", "position": [6, 14, -12], "radius": 0.75, "intensity": 1.2},
               {"type": "directional", "direction": [-1, -2, 1], "intensity": 0.5}],
    "objects": [)" + objects + "]}";
  return load_scene_from_string(json, ".", registry(), "<lit scene>");
}

TEST(EmbreeBackend, RendersTheReferenceImageBitForBit) {
  REQUIRE_PRIMITIVE("sphere");
  const Scene scene = lit_scene(7, 40);
  RenderSettings settings;
  settings.image = ImageSettings{128, 72, 2, 6};
  settings.aov_id = settings.aov_path = true;
  const auto embree = create_backend("embree");
  const auto reference = create_backend("reference");
  embree->prepare(scene);
  reference->prepare(scene);
  const Image got = embree->render(settings);
  const Image want = reference->render(settings);
  EXPECT_TRUE(bit_equal(got.rgb, want.rgb));
  EXPECT_TRUE(bit_equal(got.id, want.id));
  EXPECT_TRUE(bit_equal(got.path, want.path));
  const BackendStats stats = embree->stats();
  EXPECT_EQ(stats.ms.count("build"), 1u);
  EXPECT_GT(stats.rays_by_kind.at("shadow"), 0u);
  EXPECT_GT(stats.rays_by_kind.at("reflect"), 0u);
  EXPECT_GT(stats.rays_by_kind.at("refract"), 0u);
  EXPECT_GT(std::ranges::count_if(got.id, [](float id) { return id >= 0; }), 128 * 72 / 10);
}

TEST(EmbreeBackend, TracesTheReferenceResultsBitForBit) {
  REQUIRE_PRIMITIVE("sphere");
  const Scene scene = lit_scene(8, 60);
  Rng rng(9);
  std::vector<TraceQuery> rays;
  for (int i = 0; i < 4000; ++i) {
    const Ray ray = random_ray(rng, scene, 14);
    rays.push_back(TraceQuery{ray.origin, ray.dir, rng() % 2 ? 0.0 : uniform(rng, 0, 5)});
  }
  const auto embree = create_backend("embree");
  const auto reference = create_backend("reference");
  embree->prepare(scene);
  reference->prepare(scene);
  const auto got = embree->trace(rays);
  const auto want = reference->trace(rays);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].id, want[i].id) << "ray " << i;
    ASSERT_EQ(got[i].t, want[i].t) << "ray " << i;
    ASSERT_EQ(got[i].normal, want[i].normal) << "ray " << i;
  }
}

}  // namespace
}  // namespace prism::embree
