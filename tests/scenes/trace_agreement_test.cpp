// `trace` on random rays agrees with the reference backend, per primitive:
// the same object id on at least 99.9 % of rays and a relative t error
// whose 99th percentile is at most 1e-4. Each primitive is rotated and off
// the origin; rays start 2 to 50 units away (and some inside the bounds)
// and aim at random points around the object, so hits, misses, silhouettes
// and rays from inside all occur.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace {

struct PrimitiveCase {
  const char* name;
  const char* object;  // the JSON object, centred at (1, 2, 3)
  double size;         // roughly the object's radius, to aim rays
  bool aim_at_tube = false;  // an unrotated torus with R = 1: aim at its core circle
};

const PrimitiveCase kCases[] = {
    {"sphere", R"({"type": "sphere", "center": [1, 2, 3], "radius": 1.3})", 1.3},
    {"plane", R"({"type": "plane", "point": [1, 2, 3], "normal": [0.2, 1, -0.3]})", 2.0},
    {"box", R"({"type": "box", "center": [1, 2, 3], "half_size": [1, 0.5, 0.7]})", 1.2},
    {"torus", R"({"type": "torus", "center": [1, 2, 3], "major_radius": 1, "minor_radius": 0.25})", 1.25},
    {"thin_torus", R"({"type": "torus", "center": [1, 2, 3], "major_radius": 1, "minor_radius": 0.01})", 1.0, true},
    {"ring", R"({"type": "ring", "center": [1, 2, 3], "inner_radius": 0.4, "outer_radius": 1.2})", 1.2},
    {"quadric", R"({"type": "quadric", "center": [1, 2, 3], "coefficients": [1, -1, 1, 0, 0, 0, 0, 0, 0, -0.25],
                    "clip_min": [-1.5, -1, -1.5], "clip_max": [1.5, 1, 1.5]})", 1.5},
    {"cylinder", R"({"type": "cylinder", "center": [1, 2, 3], "radius": 0.8, "height": 1.6})", 1.2},
    {"cone", R"({"type": "cone", "center": [1, 2, 3], "radius": 0.8, "height": 1.6})", 1.2},
};

std::string scene_for(const PrimitiveCase& c) {
  std::string object = c.object;
  // Rotate every transformable primitive so the local frame is exercised.
  if (std::string(c.name) != "plane" && !c.aim_at_tube)
    object.insert(object.size() - 1, R"(, "rotation": {"axis": [1, 2, 0.5], "degrees": 37})");
  return std::string(R"({"prism": 1, "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0]}, "objects": [)") +
         object + "]}";
}

std::vector<prism::TraceQuery> random_rays(const PrimitiveCase& c, int count) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), distance(2.0, 50.0);
  const glm::dvec3 centre(1, 2, 3);
  auto random_direction = [&] {
    glm::dvec3 v;
    do v = {unit(rng), unit(rng), unit(rng)};
    while (glm::dot(v, v) > 1.0 || glm::dot(v, v) < 1e-6);
    return glm::normalize(v);
  };
  std::vector<prism::TraceQuery> rays;
  for (int i = 0; i < count; ++i) {
    const bool inside = i % 10 == 0;
    glm::dvec3 origin = inside ? centre + 0.5 * c.size * glm::dvec3(unit(rng), unit(rng), unit(rng))
                               : centre + distance(rng) * c.size * random_direction();
    glm::dvec3 target = inside ? origin + random_direction()
                               : centre + 1.2 * c.size * glm::dvec3(unit(rng), unit(rng), unit(rng));
    if (c.aim_at_tube && !inside) {  // a point within 0.03 of the core circle: hits, grazes and near misses
      const double angle = 3.14159265358979 * unit(rng);
      target = centre + glm::dvec3(std::cos(angle), 0.0, std::sin(angle)) +
               0.03 * glm::dvec3(unit(rng), unit(rng), unit(rng));
    }
    rays.push_back({origin, glm::normalize(target - origin), 0.0});
  }
  return rays;
}

std::vector<prism::TraceResult> trace(prism::Registry& registry, const std::string& backend, const prism::Scene& scene,
                                      const std::vector<prism::TraceQuery>& rays) {
  auto instance = registry.backend(backend)->create();
  instance->prepare(scene);
  return instance->trace(rays);
}

class TraceAgreement : public testing::TestWithParam<std::tuple<std::string, PrimitiveCase>> {};

TEST_P(TraceAgreement, MatchesReferenceOnRandomRays) {
  const auto& [backend, primitive] = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  prism::Scene scene = prism::load_scene_from_string(scene_for(primitive), ".", registry);
  const auto rays = random_rays(primitive, 20000);
  const auto expected = trace(registry, "reference", scene, rays);
  const auto actual = trace(registry, backend, scene, rays);
  ASSERT_EQ(actual.size(), expected.size());
  size_t same_id = 0, hits = 0;
  std::vector<double> t_errors;
  for (size_t i = 0; i < rays.size(); ++i) {
    hits += expected[i].id >= 0;
    if (actual[i].id != expected[i].id) continue;
    ++same_id;
    if (expected[i].id >= 0) t_errors.push_back(std::abs(actual[i].t - expected[i].t) / expected[i].t);
  }
  std::sort(t_errors.begin(), t_errors.end());
  const double p99 = t_errors.empty() ? 0.0 : t_errors[size_t(0.99 * double(t_errors.size() - 1))];
  std::printf("%s on %s: %zu hits of %zu rays, id agreement %.4f %%, relative t error p99 %.3g, max %.3g\n",
              primitive.name, backend.c_str(), hits, rays.size(), 100.0 * double(same_id) / double(rays.size()), p99,
              t_errors.empty() ? 0.0 : t_errors.back());
  EXPECT_GT(hits, rays.size() / 10) << "too few hits to measure anything";
  EXPECT_GE(double(same_id), 0.999 * double(rays.size()));
  EXPECT_LE(p99, 1e-4);
}

std::string name_of(const testing::TestParamInfo<TraceAgreement::ParamType>& info) {
  std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param).name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Primitives, TraceAgreement,
                         testing::Combine(testing::ValuesIn(prism::test::backends_except("reference")),
                                          testing::ValuesIn(kCases)),
                         name_of);

}  // namespace
