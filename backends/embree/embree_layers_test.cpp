// EmbreeQuery's layered updates (embree_update.hpp), driven directly on
// small scenes: answers against the brute-force oracle, the cost limit, and
// what the layers cannot hold.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "embree_device.hpp"
#include "embree_live_field.hpp"
#include "embree_query.hpp"
#include "embree_update.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

Device& device() {
  static Device instance;
  return instance;
}

// `query` answers every ray as the brute-force oracle over `scene`.
void expect_oracle_answers(const Scene& scene, const EmbreeQuery& query, uint64_t seed) {
  Rng rng(seed);
  for (int i = 0; i < 3000; ++i) {
    const Ray ray = random_ray(rng, scene, 30);
    const double tmin = i % 3 == 0 ? uniform(rng, 0.0, 10.0) : 0.0;
    const Hit want = brute_closest(scene, ray, tmin);
    const Hit got = query.closest(ray, tmin);
    ASSERT_EQ(got.id, want.id) << "ray " << i;
    ASSERT_EQ(got.t, want.t) << "ray " << i;
    const double tmax = want.found() ? want.t : uniform(rng, 1.0, 60.0);
    ASSERT_EQ(query.occluded(ray, tmax), brute_occluded(scene, ray, tmax)) << "ray " << i;
  }
}

TEST(EmbreeLayers, MovedObjectsAnswerAsTheOracleAndRenderAsAFreshScene) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({7, 7, 6});
  EmbreeQuery query(field.scene, device());
  Rng rng(5);
  for (int round = 0; round < 3; ++round) {
    std::vector<uint32_t> ids;
    std::vector<std::string> jsons;
    for (int k = 0; k < 5; ++k) {
      ids.push_back(1 + uint32_t(rng() % 294));
      jsons.push_back(sphere(glm::dvec3(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -4, 4)), 0.4));
    }
    ASSERT_EQ(query.update(field.set(ids, jsons).objects), UpdateResult::kUpdated);
  }
  // Moved objects that tie exactly with unmoved ones, on either side in id order.
  ASSERT_EQ(query.update(field.set({250, 30}, {field.objects[20], field.objects[260]}).objects),
            UpdateResult::kUpdated);
  EXPECT_GT(query.moved_count(), 12u);
  EXPECT_GT(query.layered_cost(), 1.0);
  ASSERT_NO_FATAL_FAILURE(expect_oracle_answers(field.scene, query, 6));
  BackendStats stats;
  const Image got = render_cpu(field.scene, query, small_frame(), stats);
  const Image want = fresh_render("reference", field.edited);
  EXPECT_TRUE(bit_equal(got.rgb, want.rgb));
  EXPECT_TRUE(bit_equal(got.id, want.id));
}

TEST(EmbreeLayers, MovingTheSameObjectsAgainKeepsTheCost) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({7, 7, 6});
  EmbreeQuery query(field.scene, device());
  const std::vector<uint32_t> ids = {50, 51, 105, 142, 197};  // inside the field: they stay inside B
  std::vector<glm::dvec3> home;
  for (uint32_t id : ids) home.push_back(field.scene.objects[id].center);
  double cost = 0;
  for (int step = 0; step < 30; ++step) {
    std::vector<std::string> jsons;
    for (const glm::dvec3& c : home) jsons.push_back(sphere(c + glm::dvec3(step % 2 ? 0.1 : -0.1, 0.05, 0), 0.5));
    ASSERT_EQ(query.update(field.set(ids, jsons).objects), UpdateResult::kUpdated) << "step " << step;
    if (step == 1) cost = query.layered_cost();
    if (step > 1) {
      EXPECT_NEAR(query.layered_cost(), cost, 1e-9) << "step " << step;
    }
  }
  EXPECT_EQ(query.moved_count(), ids.size());
  EXPECT_LT(query.layered_cost(), 1.05);
  ASSERT_NO_FATAL_FAILURE(expect_oracle_answers(field.scene, query, 7));
}

TEST(EmbreeLayers, ScatteringPassesTheCostLimitAndLeavesTheQueryAsItWas) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({7, 7, 6});
  EmbreeQuery query(field.scene, device());
  Rng rng(8);
  int updated = 0;
  for (uint32_t id = 1; id <= 294; ++id) {
    const double cost = query.layered_cost();
    const size_t moved = query.moved_count();
    const auto changes = field.move(id, glm::dvec3(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -4, 4)), 0.4);
    if (query.update(changes.objects) == UpdateResult::kNeedsBuild) {
      EXPECT_EQ(query.layered_cost(), cost);
      EXPECT_EQ(query.moved_count(), moved);
      break;
    }
    ++updated;
    EXPECT_LE(query.layered_cost(), kMaxLayeredCost);
  }
  std::printf("[   info   ] %d spheres scattered before the cost limit\n", updated);
  EXPECT_GT(updated, 15);  // a tenth of the area is ~35 spheres
  EXPECT_LT(updated, 200);
}

TEST(EmbreeLayers, WhatLayersCannotHoldNeedsABuild) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  struct Case {
    const char* what;
    std::function<SceneChanges(LiveField&)> edit;
    UpdateResult want;
  };
  const std::vector<Case> cases = {
      {"bounded to unbounded", [](LiveField& f) { return f.set(5, f.objects[0]); }, UpdateResult::kNeedsBuild},
      {"outsized", [](LiveField& f) { return f.move(5, glm::dvec3(0, -900, 0), 800); }, UpdateResult::kNeedsBuild},
      {"out of the frame", [](LiveField& f) { return f.move(5, glm::dvec3(0, 0, -9), 0.5); },
       UpdateResult::kNeedsBuild},
      {"an object added", [](LiveField& f) {
         f.append(sphere(glm::dvec3(0), 1));
         return SceneChanges{.objects = {5}};
       }, UpdateResult::kNeedsBuild},
      {"layering not allowed", [](LiveField& f) { return f.move(5, glm::dvec3(0.5), 0.5); },
       UpdateResult::kNeedsBuild},
      {"a material", [](LiveField& f) { return f.set(5, with_material(f.objects[5], "glass")); },
       UpdateResult::kUnchanged},
      {"the floor (beside the BVH)",
       [](LiveField& f) { return f.set(0, R"({"type": "plane", "point": [0, -7, 0], "normal": [0, 1, 0]})"); },
       UpdateResult::kUnchanged},
      {"a box in its type's place", [](LiveField& f) {
         const glm::dvec3 c = f.edited.objects[6].center;
         return f.set(6, R"({"type": "box", "center": )" + vec(c.x, c.y, c.z) + R"(, "half_size": [0.3, 0.3, 0.3]})");
       }, UpdateResult::kUpdated},
  };
  for (const Case& c : cases) {
    if (std::string(c.what).starts_with("a box") && !has_primitive("box")) continue;
    LiveField field({4, 4, 4});
    EmbreeQuery query(field.scene, device());
    const SceneChanges changes = c.edit(field);
    const bool may_layer = std::string(c.what) != "layering not allowed";
    EXPECT_EQ(query.update(changes.objects, may_layer), c.want) << c.what;
    if (c.want == UpdateResult::kNeedsBuild) {
      EXPECT_EQ(query.moved_count(), 0u) << c.what;
      continue;
    }
    ASSERT_NO_FATAL_FAILURE(expect_oracle_answers(field.scene, query, 9)) << c.what;
  }
}

}  // namespace
}  // namespace prism::embree
