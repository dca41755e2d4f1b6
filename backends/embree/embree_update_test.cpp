// Backend::update on the embree and reference backends: counters, and
// images bit for bit those of a fresh backend prepared on the edited scene.
#include <gtest/gtest.h>

#include <cstdio>

#include "embree_live_field.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

// The cumulative counters of prism::counter.
struct Counts {
  double prepares, updates, uploaded, builds, refits, kernels;
  static Counts of(const Backend& backend) {
    const auto counters = backend.stats().counters;
    auto get = [&](const char* name) {
      auto it = counters.find(name);
      return it == counters.end() ? -1.0 : it->second;
    };
    return {get(counter::kPrepares), get(counter::kUpdates), get(counter::kObjectsUploaded),
            get(counter::kBvhBuilds), get(counter::kBvhRefits), get(counter::kKernelBuilds)};
  }
};

// ---- Both CPU backends

TEST(BackendUpdate, CountersStartAtZeroAndCountPrepares) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  const LiveField field({4, 4, 4});
  for (const std::string name : {"embree", "reference"}) {
    const auto backend = create_backend(name);
    const Counts zero = Counts::of(*backend);
    for (double c : {zero.prepares, zero.updates, zero.uploaded, zero.builds, zero.refits, zero.kernels}) {
      EXPECT_EQ(c, 0.0) << name;
    }
    backend->prepare(field.scene);
    const Counts after = Counts::of(*backend);
    EXPECT_EQ(after.prepares, 1.0) << name;
    EXPECT_EQ(after.uploaded, 65.0) << name;
    EXPECT_EQ(after.builds, name == "embree" ? 1.0 : 0.0) << name;
    EXPECT_EQ(after.updates + after.refits + after.kernels, 0.0) << name;
  }
}

TEST(BackendUpdate, ReferenceRereadsOnlyTheChangedObjects) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({5, 4, 5});
  const auto backend = create_backend("reference");
  backend->prepare(field.scene);
  backend->render(small_frame());
  backend->update(field.scene, field.move(17, glm::dvec3(1.5, 2, -3), 0.8));
  Counts c = Counts::of(*backend);
  EXPECT_EQ(c.updates, 1.0);
  EXPECT_EQ(c.uploaded, 101.0 + 1.0);
  EXPECT_EQ(c.builds + c.refits, 0.0);
  expect_fresh_image(*backend, field.edited, "reference");
  backend->update(field.scene, field.append(sphere(glm::dvec3(0, 0, -6), 1.0)));
  c = Counts::of(*backend);
  EXPECT_EQ(c.uploaded, 102.0 + 102.0);  // ids may shift: every object is read again
  EXPECT_EQ(c.builds + c.refits, 0.0);
  expect_fresh_image(*backend, field.edited, "reference");
}

// ---- Embree: moves layer while the last frame traced few rays per object,
// and build again otherwise (kLayerRaysPerObject = 15, embree_backend.cpp)

TEST(EmbreeUpdate, AfterAFrameOfManyRaysPerObjectAMoveBuildsAgain) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({7, 7, 6});  // 294 spheres
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  backend->render(small_frame());  // 96 x 64: over 15 camera rays per sphere alone
  backend->update(field.scene, field.move(40, glm::dvec3(0.5, 1, -2), 0.9));
  Counts c = Counts::of(*backend);
  EXPECT_EQ(c.updates, 1.0);
  EXPECT_EQ(c.builds, 2.0);
  EXPECT_EQ(c.refits, 0.0);
  EXPECT_EQ(c.uploaded, 2 * 295.0);
  expect_fresh_image(*backend, field.edited, "embree");
  // A new material leaves every box as it was: nothing to build.
  backend->update(field.scene, field.set(41, with_material(field.objects[41], "glass")));
  c = Counts::of(*backend);
  EXPECT_EQ(c.builds, 2.0);
  EXPECT_EQ(c.refits, 0.0);
  EXPECT_EQ(c.uploaded, 2 * 295.0 + 1);
  expect_fresh_image(*backend, field.edited, "embree");
}

TEST(EmbreeUpdate, AfterAFrameOfManyRaysPerObjectLargeScenesBuildAgainToo) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({25, 16, 25});
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  RenderSettings large = small_frame();
  large.image.width = 640;
  large.image.height = 360;
  backend->render(large);
  ASSERT_GE(backend->stats().rays, 15u * 10000u);
  backend->update(field.scene, field.move(5000, field.scene.objects[5000].center + glm::dvec3(0.2), 0.5));
  const Counts counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 2.0);
  EXPECT_EQ(counts.refits, 0.0);
  expect_fresh_image(*backend, field.edited, "embree");
}

TEST(EmbreeUpdate, AfterAFrameOfFewRaysPerObjectMovesAreLayered) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({25, 16, 25});  // 10,000 spheres
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  backend->render(small_frame());  // 96 x 64: a few rays per sphere
  const glm::dvec3 c = field.scene.objects[5000].center;
  backend->update(field.scene, field.move(5000, c + glm::dvec3(0.3, -0.2, 0.1), 0.7));
  Counts counts = Counts::of(*backend);
  EXPECT_EQ(counts.updates, 1.0);
  EXPECT_EQ(counts.refits, 1.0);
  EXPECT_EQ(counts.builds, 1.0);
  EXPECT_EQ(counts.uploaded, 10001.0 + 1.0);
  EXPECT_EQ(backend->stats().ms.count("update"), 1u);
  expect_fresh_image(*backend, field.edited, "embree");
  // Across the field, then the first one again.
  backend->update(field.scene, field.move(123, glm::dvec3(-3, 14, -22), 0.5));
  backend->update(field.scene, field.move(5000, c - glm::dvec3(0.2, 0.4, 0.1), 0.4));
  counts = Counts::of(*backend);
  EXPECT_EQ(counts.refits, 3.0);
  EXPECT_EQ(counts.builds, 1.0);
  EXPECT_EQ(counts.uploaded, 10001.0 + 3.0);
  expect_fresh_image(*backend, field.edited, "embree");
}

// Few objects: the queries test the box filter's boxes, not Embree's
// layers (embree_box_filter.hpp), and a layered move must reach them too.
TEST(EmbreeUpdate, LayeredMovesInASmallSceneReachTheBoxFilter) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({2, 2, 3});  // 12 spheres and the floor
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  const glm::dvec3 c = field.scene.objects[5].center;
  backend->update(field.scene, field.move(5, c + glm::dvec3(0.3, -0.2, 0.2), 0.6));
  const Counts counts = Counts::of(*backend);
  EXPECT_EQ(counts.refits, 1.0);  // layered (a second move of this size would pass kMaxLayeredCost in so small a scene)
  EXPECT_EQ(counts.builds, 1.0);
  expect_fresh_image(*backend, field.edited, "embree");
}

// The frame's box B has room around the objects (a quarter of the field's
// width, ~12): moving into it layers; moving out of it builds again, around
// a B with room again.
TEST(EmbreeUpdate, AnObjectLeavingTheFrameBuildsAgain) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({25, 16, 25});  // x, z in +-25, y in +-16
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  backend->update(field.scene, field.move(77, glm::dvec3(2, 1, -30), 1.0));  // in front of the field, in B
  Counts counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 1.0);
  EXPECT_EQ(counts.refits, 1.0);
  expect_fresh_image(*backend, field.edited, "embree");
  backend->update(field.scene, field.move(77, glm::dvec3(2, 1, -40), 1.0));  // out of B
  counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 2.0);
  EXPECT_EQ(counts.refits, 1.0);
  const Image image = backend->render(small_frame());
  EXPECT_TRUE(shows(image, 77));
  expect_fresh_image(*backend, field.edited, "embree");
  backend->update(field.scene, field.move(77, glm::dvec3(2, 1, -46), 1.0));
  counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 2.0);
  EXPECT_EQ(counts.refits, 2.0);
  expect_fresh_image(*backend, field.edited, "embree");
}

TEST(EmbreeUpdate, AddingRemovingOutsizingOrUnboundingObjectsBuildsAgain) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({25, 16, 25});
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  backend->update(field.scene, field.append(sphere(glm::dvec3(-2, 2, -28), 1.5, "mirror")));
  Counts counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 2.0);
  EXPECT_EQ(counts.uploaded, 10001.0 + 10002.0);
  expect_fresh_image(*backend, field.edited, "embree");
  backend->update(field.scene, field.erase(9));
  EXPECT_EQ(Counts::of(*backend).builds, 3.0);
  expect_fresh_image(*backend, field.edited, "embree");
  // Radius 2000 (over 1000 times the median): tested beside the BVH from now on.
  backend->update(field.scene, field.move(300, glm::dvec3(0, -2100, 0), 2000));
  counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 4.0);
  EXPECT_EQ(counts.refits, 0.0);
  expect_fresh_image(*backend, field.edited, "embree");
  // A sphere that becomes a plane (unbounded): beside the BVH too.
  backend->update(field.scene, field.set(400, R"({"type": "plane", "point": [0, 0, 30], "normal": [0, 0, -1]})"));
  counts = Counts::of(*backend);
  EXPECT_EQ(counts.builds, 5.0);
  EXPECT_EQ(counts.refits, 0.0);
  expect_fresh_image(*backend, field.edited, "embree");
}

TEST(EmbreeUpdate, ScatteringObjectsBuildsAgainPastTheCostLimit) {
  REQUIRE_PRIMITIVE("sphere");
  REQUIRE_PRIMITIVE("plane");
  LiveField field({25, 16, 25});
  const auto backend = create_backend("embree");
  backend->prepare(field.scene);
  Rng rng(21);
  int layered = 0;
  while (Counts::of(*backend).builds == 1.0 && layered < 20) {
    std::vector<uint32_t> ids;
    std::vector<std::string> jsons;
    for (int k = 0; k < 100; ++k) {
      ids.push_back(1 + uint32_t(rng() % 10000));
      jsons.push_back(sphere(glm::dvec3(uniform(rng, -20, 20), uniform(rng, -12, 12), uniform(rng, -20, 20)), 0.5));
    }
    backend->update(field.scene, field.set(ids, jsons));
    layered += Counts::of(*backend).builds == 1.0;
  }
  std::printf("[   info   ] %d updates of 100 scattered spheres layered before a build\n", layered);
  // A tenth of the spheres' area traced twice: ~700 moved, ~7 updates.
  EXPECT_GE(layered, 3);
  EXPECT_LE(layered, 15);
  EXPECT_EQ(Counts::of(*backend).refits, double(layered));
  expect_fresh_image(*backend, field.edited, "embree");
}

}  // namespace
}  // namespace prism::embree
