// The Embree backend against the brute-force double oracle: the BVH may only
// choose candidates, never change an answer (same id, same t).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "embree_device.hpp"
#include "embree_query.hpp"
#include "embree_test_scenes.hpp"

namespace prism::embree {
namespace {

using namespace prism::embree::testing;

Device& device() {
  static Device instance;
  return instance;
}

// What a test compared: rays, oracle hits, and hits whose t is bit-identical
// (the rest must be within 1e-12 relative).
struct Tally {
  int rays = 0;
  int hits = 0;
  int exact = 0;
  ~Tally() {
    std::printf("[   info   ] %d rays compared, %d hits, %d with bit-identical t\n", rays, hits, exact);
  }
};

// Compares one closest-hit query with the oracle.
void expect_same_closest(const Scene& scene, const EmbreeQuery& query, const Ray& ray, double tmin, Tally& tally) {
  const Hit want = brute_closest(scene, ray, tmin);
  const Hit got = query.closest(ray, tmin);
  ASSERT_EQ(got.id, want.id) << "ray o=(" << ray.origin.x << "," << ray.origin.y << "," << ray.origin.z << ") d=("
                             << ray.dir.x << "," << ray.dir.y << "," << ray.dir.z << ") tmin=" << tmin
                             << " t_want=" << want.t << " t_got=" << got.t;
  ++tally.rays;
  if (!want.found()) return;
  EXPECT_NEAR(got.t, want.t, 1e-12 * want.t) << "object " << want.id;
  ++tally.hits;
  tally.exact += (got.t == want.t);
}

TEST(EmbreeQuery, MatchesBruteForceOnRandomMixedScenes) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  std::printf("[   info   ] types:");
  for (const auto& type : types) std::printf(" %s", type.c_str());
  std::printf("\n");
  Rng rng(1);
  Tally tally;
  for (int s = 0; s < 6; ++s) {
    // Odd scenes have few objects: the box filter answers, not Embree's traversal.
    const Scene scene = load(random_objects_json(rng, types, s % 2 ? 12 : 60));
    const EmbreeQuery query(scene, device());
    ASSERT_EQ(query.filters(), s % 2 == 1);
    for (int i = 0; i < 3000; ++i) {
      const Ray ray = random_ray(rng, scene, 14);
      const double tmin = rng() % 2 == 0 ? 0.0 : uniform(rng, 0.0, 10.0);
      ASSERT_NO_FATAL_FAILURE(expect_same_closest(scene, query, ray, tmin, tally));
    }
  }
  EXPECT_GT(tally.hits, 6000);
}

// The random scenes draw every type whose cases module has random objects,
// a new primitive's too (sdk.ninth_primitive runs this with the capsule).
TEST(EmbreeQuery, RandomScenesHoldEveryAvailableType) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  Rng rng(16);
  const Scene scene = load(random_objects_json(rng, types, 40 * int(types.size())));
  std::set<std::string> drawn;
  for (const Object& object : scene.objects) drawn.insert(object.desc->type_name);
  EXPECT_EQ(std::vector<std::string>(drawn.begin(), drawn.end()), types);
}

// PRISM_PRIMITIVE_CONVEX is a promise the shading path relies on (it skips
// the object in shadow and reflected rays from its own front-facing hits):
// for every plugin that makes it, rays leaving a front-facing hit from the
// format's offset origin, in any direction on the outward side down to
// grazing ones, must find no hit on that object.
TEST(EmbreeQuery, ConvexPluginsAreNotMetAgainByRaysLeavingTheirFront) {
  REQUIRE_PRIMITIVE("sphere");
  int claimed = 0, checked = 0;
  for (const std::string& type : available_types()) {
    Rng rng(23);
    const Scene scene = load(random_objects_json(rng, {type}, 12));
    if (!(scene.objects[0].desc->flags & PRISM_PRIMITIVE_CONVEX)) continue;
    ++claimed;
    for (int i = 0; i < 4000; ++i) {
      const Ray ray = random_ray(rng, scene, 3.0);
      const Hit hit = brute_closest(scene, ray, 0.0);
      if (hit.id < 0) continue;
      const Object& object = scene.objects[size_t(hit.id)];
      const SurfacePoint sp = surface_of(object, ray, hit.prim);
      if (!(glm::dot(ray.dir, sp.normal) < 0)) continue;  // back-facing: no promise
      const glm::dvec3 p = sp.position;
      const double epsilon = 1e-4 * (1 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
      // Toward the outward side; every fourth ray within 1e-6 of grazing.
      glm::dvec3 dir = random_unit(rng);
      if (glm::dot(dir, sp.normal) < 0) dir = -dir;
      if (i % 4 == 0) dir = glm::normalize(dir - glm::dot(dir, sp.normal) * sp.normal + 1e-6 * sp.normal);
      if (!(glm::dot(dir, sp.normal) > 0)) continue;
      PrismHit again;
      ASSERT_FALSE(intersect_object(object, Ray{p + epsilon * sp.normal, dir}, 0.0, kInfinity, again))
          << type << " object " << hit.id << " met again at t = " << again.t;
      ++checked;
    }
  }
  std::printf("[   info   ] %d convex types, %d rays leaving a front face\n", claimed, checked);
  EXPECT_GE(claimed, 2);
  EXPECT_GT(checked, 1000 * claimed);
}

TEST(EmbreeQuery, MatchesBruteForceForRaysFromFarAway) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  Rng rng(2);
  Tally tally;
  for (int s = 0; s < 4; ++s) {
    const Scene scene = load(random_objects_json(rng, types, s % 2 ? 12 : 60));
    const EmbreeQuery query(scene, device());
    for (int i = 0; i < 2000; ++i) {
      Ray ray = random_ray(rng, scene, 1.0);
      const glm::dvec3 target = ray.origin + 20.0 * ray.dir;
      ray.origin = 1e5 * random_unit(rng);  // |origin| = 1e5, aimed into the scene
      ray.dir = glm::normalize(target - ray.origin);
      ASSERT_NO_FATAL_FAILURE(expect_same_closest(scene, query, ray, 0.0, tally));
    }
  }
  EXPECT_GT(tally.hits, 3000);
}

// Objects of size ~1e-2 some 1e4 from the origin, rays through points on
// their world boxes (faces, edges, corners: where an object can touch its
// box, and a culling float box would lose the hit), from near and from 1e5.
TEST(EmbreeQuery, RaysThroughTheBoxBoundariesOfSmallFarObjects) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  const Placement far{glm::dvec3(1e4, -2e3, 3e3), 1e-2};
  Rng rng(12);
  Tally tally;
  for (int s = 0; s < 4; ++s) {
    const Scene scene = load(random_objects_json(rng, types, s % 2 ? 12 : 60, far));
    const EmbreeQuery query(scene, device());
    for (int i = 0; i < 4000; ++i) {
      Ray ray = random_ray(rng, scene, 0.2, far.offset);
      if (i % 2 == 1) ray.origin -= 1e5 * ray.dir;  // the same line, from 1e5 away
      ASSERT_NO_FATAL_FAILURE(expect_same_closest(scene, query, ray, 0.0, tally));
      ASSERT_EQ(query.occluded(ray, kInfinity), brute_occluded(scene, ray, kInfinity));
    }
  }
  EXPECT_GT(tally.hits, 4000);
}

// Rays that clip an edge of an axis-aligned box by a sliver of depth eta
// (1e-12 to 1e-7 of its size): the plugin's double test finds those hits,
// while a float ray, off by ~1e-7 of the frame's size, would leave the
// unpadded float box there. Boxes near the origin and small ones 1e4 away.
TEST(EmbreeQuery, RaysClippingBoxEdgesAreNotCulled) {
  REQUIRE_PRIMITIVE("box");
  Rng rng(13);
  for (const auto& [at, count] : {std::pair{Placement{}, 64}, std::pair{Placement{glm::dvec3(1e4, -2e3, 3e3), 1e-2}, 64},
                                  std::pair{Placement{}, 16}, std::pair{Placement{glm::dvec3(1e4, -2e3, 3e3), 1e-2}, 16}}) {
    std::string json;
    std::vector<Box3> boxes;
    for (int i = 0; i < count; ++i) {  // well apart, so that BVH leaves hold one box each
      const glm::dvec3 cell(i % 4, (i / 4) % 4, i / 16);
      const glm::dvec3 c = at.offset + at.scale * (4.0 * cell - 6.0 + glm::dvec3(uniform(rng, -1, 1)));
      const glm::dvec3 h = at.scale * glm::dvec3(uniform(rng, 0.2, 0.9), uniform(rng, 0.2, 0.9), uniform(rng, 0.2, 0.9));
      json += (i ? "," : "") + std::string(R"({"type": "box", "center": )") + vec(c.x, c.y, c.z) +
              ", \"half_size\": " + vec(h.x, h.y, h.z) + "}";
      boxes.push_back(Box3{c - h, c + h});
    }
    const Scene scene = load(json);
    const EmbreeQuery query(scene, device());
    Tally tally;
    int slivers = 0;
    for (int i = 0; i < 4000; ++i) {
      const int id = static_cast<int>(rng() % boxes.size());
      const Box3& box = boxes[id];
      const int a = static_cast<int>(rng() % 3), b = (a + 1 + static_cast<int>(rng() % 2)) % 3, c = 3 - a - b;
      const double sa = rng() % 2 ? 1.0 : -1.0, sb = rng() % 2 ? 1.0 : -1.0;
      glm::dvec3 edge;  // a point on the edge where faces a (side sa) and b (side sb) meet
      edge[a] = sa > 0 ? box.hi[a] : box.lo[a];
      edge[b] = sb > 0 ? box.hi[b] : box.lo[b];
      edge[c] = uniform(rng, box.lo[c], box.hi[c]);
      const double eta = (box.hi[a] - box.lo[a]) * std::pow(10.0, uniform(rng, -12, -7));
      glm::dvec3 inside = edge, dir(0);
      inside[a] -= sa * eta;
      inside[b] -= sb * eta;
      dir[a] = sa;  // leaves through face a while entering through face b
      dir[b] = -sb;
      dir[c] = uniform(rng, -1, 1);
      const Ray ray{inside - (i % 2 ? 1e5 : 30.0) * glm::normalize(dir), glm::normalize(dir)};
      ASSERT_NO_FATAL_FAILURE(expect_same_closest(scene, query, ray, 0.0, tally));
      slivers += brute_closest(scene, ray, 0.0).id == id;
    }
    EXPECT_EQ(query.filters(), count <= 16);
    EXPECT_GT(slivers, 1000);
  }
}

TEST(EmbreeQuery, OcclusionMatchesBruteForce) {
  REQUIRE_PRIMITIVE("sphere");
  const auto types = available_types();
  Rng rng(3);
  int blocked = 0;
  for (int s = 0; s < 6; ++s) {
    const Scene scene = load(random_objects_json(rng, types, s % 2 ? 12 : 60));
    const EmbreeQuery query(scene, device());
    for (int i = 0; i < 3000; ++i) {
      const Ray ray = random_ray(rng, scene, 14);
      const double tmax = rng() % 8 == 0 ? kInfinity : uniform(rng, 0.0, 30.0);
      const bool want = brute_occluded(scene, ray, tmax);
      ASSERT_EQ(query.occluded(ray, tmax), want) << "tmax " << tmax;
      blocked += want;
      // tmax exactly at the closest hit: that hit does not block (0 < t < tmax).
      const Hit first = brute_closest(scene, ray, 0.0);
      if (first.found()) {
        ASSERT_EQ(query.occluded(ray, first.t), brute_occluded(scene, ray, first.t));
      }
    }
  }
  EXPECT_GT(blocked, 1000);
}

TEST(EmbreeQuery, EqualTGoesToTheLowerId) {
  REQUIRE_PRIMITIVE("sphere");
  // A field of spheres with exact copies of one sphere among them (ids 3, 8, ...).
  const std::string copy = R"({"type": "sphere", "center": [0.25, -0.5, 3], "radius": 1.5})";
  Rng rng(4);
  for (const int count : {40, 12}) {  // through Embree, and through the box filter
    std::string json;
    std::vector<int32_t> copies;
    for (int i = 0; i < count; ++i) {
      const bool is_copy = i % 5 == 3 || (count < 20 && i % 5 == 1);
      if (is_copy) copies.push_back(i);
      json += (i ? "," : "") + (is_copy ? copy : random_object(rng, "sphere"));
    }
    const Scene scene = load(json);
    const EmbreeQuery query(scene, device());
    ASSERT_EQ(query.filters(), count <= 16);
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
      const Ray ray{glm::dvec3(0, 0, -20) + random_unit(rng), glm::normalize(glm::dvec3(uniform(rng, -0.08, 0.08),
                                                                                        uniform(rng, -0.08, 0.08), 1))};
      const Hit want = brute_closest(scene, ray, 0.0);
      const Hit got = query.closest(ray, 0.0);
      ASSERT_EQ(got.id, want.id);
      ASSERT_EQ(got.t, want.t);
      if (std::ranges::find(copies, want.id) != copies.end()) {
        ASSERT_EQ(got.id, copies.front()) << "a later copy won the tie";
        ++checked;
      }
    }
    EXPECT_GT(checked, 100);
  }
}

TEST(EmbreeQuery, EqualTBetweenBvhAndBruteForceObjects) {
  REQUIRE_PRIMITIVE("plane");
  REQUIRE_PRIMITIVE("ring");
  // A ring (in the BVH) lying in a plane (brute force): hits at the same t.
  const std::string ring = R"({"type": "ring", "center": [0, 0, 0], "outer_radius": 2})";
  const std::string plane = R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]})";
  for (bool ring_first : {true, false}) {
    const Scene scene = load(ring_first ? ring + "," + plane : plane + "," + ring);
    const EmbreeQuery query(scene, device());
    ASSERT_EQ(query.bvh_object_count(), 1u);
    for (double x : {-1.5, -0.25, 0.0, 0.75, 1.25}) {
      const Ray ray{glm::dvec3(x, 5, 0.5), glm::dvec3(0, -1, 0)};
      const Hit want = brute_closest(scene, ray, 0.0);
      const Hit got = query.closest(ray, 0.0);
      EXPECT_EQ(got.id, 0) << "the lower id wins at equal t";
      EXPECT_EQ(got.id, want.id);
      EXPECT_EQ(got.t, want.t);
    }
  }
}

// 300 overlapping rings in the plane y = 0.5 (their hits share one t
// exactly, whatever their centre and radius) in different BVH leaves: when
// the first ring found is not the lowest id, the lower one must still be
// visited, so Embree's tfar must not drop below the tie.
TEST(EmbreeQuery, EqualTOnCoplanarRingsGoesToTheLowerId) {
  REQUIRE_PRIMITIVE("ring");
  Rng rng(15);
  std::string json;
  for (int i = 0; i < 300; ++i) {
    json += (i ? "," : "") + std::string(R"({"type": "ring", "center": )") +
            vec(uniform(rng, -10, 10), 0.5, uniform(rng, -10, 10)) + ", \"inner_radius\": " +
            num(uniform(rng, 0, 0.5)) + ", \"outer_radius\": " + num(uniform(rng, 1, 3)) + "}";
  }
  const Scene scene = load(json);
  const EmbreeQuery query(scene, device());
  int ties = 0;
  for (int i = 0; i < 3000; ++i) {
    const Ray ray{glm::dvec3(uniform(rng, -12, 12), uniform(rng, 1, 20), uniform(rng, -12, 12)),
                  glm::normalize(glm::dvec3(uniform(rng, -0.5, 0.5), -1, uniform(rng, -0.5, 0.5)))};
    const Hit want = brute_closest(scene, ray, 0.0);
    const Hit got = query.closest(ray, 0.0);
    ASSERT_EQ(got.id, want.id) << "ray " << i;
    ASSERT_EQ(got.t, want.t) << "ray " << i;
    ties += std::ranges::count_if(scene.objects, [&](const Object& object) {
              PrismHit hit;
              return want.found() && intersect_object(object, ray, 0.0, want.t, hit) && hit.t == want.t;
            }) > 1;
  }
  EXPECT_GT(ties, 1000);
}

struct Ball {
  glm::dvec3 center;
  double radius;
  int32_t id;
};

// Rays that graze a ball (missing its centre by 1 - 1e-6, 1 - 1e-9 and
// 1 + 1e-9 of the radius), half of them in the plane of a face of its box
// (where the box is hardly wider than the ball), from near and from 1e5
// away: whatever the oracle hits, the query must hit too.
void check_grazing(const Scene& scene, const EmbreeQuery& query, const std::vector<Ball>& balls) {
  Rng rng(5);
  int grazed = 0;
  for (int i = 0; i < 600; ++i) {
    const Ball& ball = balls[rng() % balls.size()];
    glm::dvec3 side(0);
    glm::dvec3 axis;
    if (i % 2 == 0) {
      side[rng() % 3] = rng() % 2 ? 1.0 : -1.0;
      axis = glm::normalize(glm::cross(side, random_unit(rng)));  // travels in the face plane
    } else {
      axis = random_unit(rng);
      side = glm::normalize(glm::cross(axis, random_unit(rng)));
    }
    for (double miss : {1.0 - 1e-6, 1.0 - 1e-9, 1.0 + 1e-9}) {
      const glm::dvec3 through = ball.center + miss * ball.radius * side;
      for (double distance : {0.05, 30.0, 1e5}) {
        const Ray ray{through - distance * axis, axis};
        const Hit want = brute_closest(scene, ray, 0.0);
        const Hit got = query.closest(ray, 0.0);
        ASSERT_EQ(got.id, want.id) << "distance " << distance << " miss " << miss << " ray " << i;
        ASSERT_EQ(got.t, want.t);
        ASSERT_EQ(query.occluded(ray, kInfinity), brute_occluded(scene, ray, kInfinity));
        grazed += (miss < 1.0 && want.id == ball.id);
      }
    }
  }
  EXPECT_GT(grazed, 1200);  // of 3600 hitting rays; the rest hit a neighbour first
}

TEST(EmbreeQuery, GrazingRaysOnTinyFarSpheresAreNotCulled) {
  REQUIRE_PRIMITIVE("sphere");
  const glm::dvec3 far(1e4, 2e3, -3e3);
  std::string cluster;
  std::vector<Ball> balls;
  for (int i = 0; i < 27; ++i) {  // radius 1e-3, 1e-2 apart, some 1e4 from the origin
    const glm::dvec3 c = far + 0.01 * glm::dvec3(i % 3, (i / 3) % 3, i / 9);
    cluster += (i ? "," : "") + std::string(R"({"type": "sphere", "radius": 0.001, "center": )") +
               vec(c.x, c.y, c.z) + "}";
    balls.push_back(Ball{c, 1e-3, i});
  }
  {  // alone: a frame of size ~1e-2, re-centred on the cluster
    const Scene scene = load(cluster);
    const EmbreeQuery query(scene, device());
    EXPECT_LT(query.frame().pad, 1e-7);
    check_grazing(scene, query, balls);
  }
  {  // beside a unit sphere at the origin: one frame of size ~1e4 holds both
    const Scene scene = load(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1},)" + cluster);
    const EmbreeQuery query(scene, device());
    EXPECT_EQ(query.bvh_object_count(), 28u);
    for (Ball& ball : balls) ++ball.id;
    check_grazing(scene, query, balls);
  }
}

TEST(EmbreeQuery, HugeObjectsAreTestedBesideTheBvh) {
  REQUIRE_PRIMITIVE("sphere");
  Rng rng(6);
  std::string json = R"({"type": "sphere", "center": [0, -1000001, 0], "radius": 1000000})";
  for (int i = 0; i < 50; ++i) json += "," + random_object(rng, "sphere");
  const Scene scene = load(json);
  const EmbreeQuery query(scene, device());
  EXPECT_EQ(query.brute_force_count(), 1u);
  EXPECT_LT(query.frame().pad, 1e-3);
  Tally tally;
  for (int i = 0; i < 3000; ++i) {
    ASSERT_NO_FATAL_FAILURE(expect_same_closest(scene, query, random_ray(rng, scene, 14), 0.0, tally));
  }
}

TEST(EmbreeQuery, ScenesWithoutBoundedObjects) {
  REQUIRE_PRIMITIVE("plane");
  const Scene empty = load("");
  const EmbreeQuery none(empty, device());
  EXPECT_FALSE(none.closest(Ray{}, 0.0).found());
  EXPECT_FALSE(none.occluded(Ray{}, kInfinity));
  const Scene planes = load(R"({"type": "plane", "point": [0, 0, 5], "normal": [0, 0, 1]},
                               {"type": "plane", "point": [0, 0, 5], "normal": [0, 0, -1]})");
  const EmbreeQuery query(planes, device());
  EXPECT_EQ(query.geometry_count(), 0u);
  const Hit hit = query.closest(Ray{glm::dvec3(0), glm::dvec3(0, 0, 1)}, 0.0);
  EXPECT_EQ(hit.id, 0);
  EXPECT_EQ(hit.t, 5.0);
  EXPECT_TRUE(query.occluded(Ray{glm::dvec3(0), glm::dvec3(0, 0, 1)}, 6.0));
  EXPECT_FALSE(query.occluded(Ray{glm::dvec3(0), glm::dvec3(0, 0, 1)}, 5.0));
}

TEST(EmbreeQuery, NonFiniteRaysFindNothing) {
  REQUIRE_PRIMITIVE("sphere");
  Rng rng(14);
  const Scene scene = load(random_objects_json(rng, {"sphere"}, 20));
  const EmbreeQuery query(scene, device());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Ray& ray : {Ray{glm::dvec3(nan, 0, 0), glm::dvec3(0, 0, 1)}, Ray{glm::dvec3(0), glm::dvec3(nan, 0, 0)},
                         Ray{glm::dvec3(0, 0, -kInfinity), glm::dvec3(0, 0, 1)}}) {
    EXPECT_FALSE(query.closest(ray, 0.0).found());
    EXPECT_FALSE(query.occluded(ray, kInfinity));
  }
  EXPECT_NO_THROW(device().check("non-finite rays"));
}

TEST(EmbreeDevice, EmbreeErrorsBecomeRuntimeErrors) {
  Device local;
  RTCGeometry bad = rtcNewGeometry(local.get(), static_cast<RTCGeometryType>(12345));
  EXPECT_EQ(bad, nullptr);
  EXPECT_THROW(local.check("a test"), RuntimeError);
  EXPECT_NO_THROW(local.check("a test"));  // reported once
}


}  // namespace
}  // namespace prism::embree
