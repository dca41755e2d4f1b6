// LightLanes (prism/light_lanes.hpp) against the format's local-light
// expressions, written here once more with glm as the scalar shading wrote
// them: every lane width the processor runs gives the same bits, for full
// and partial batches, point lights with falloff and directional ones.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <random>

#include "prism/geometry.hpp"
#include "prism/light_lanes.hpp"

namespace prism {
namespace {

struct ScalarTerms {
  glm::dvec3 l, energy;
  double distance;
  double ndl;
  glm::dvec3 diffuse;
  double highlight;
};

ScalarTerms scalar_terms(const Light& light, const LightLanes::Point& p) {
  ScalarTerms s;
  s.energy = light.color * light.intensity;
  s.distance = kInfinity;
  if (light.type == Light::Type::Point) {
    glm::dvec3 to = light.position - p.position;
    double d = glm::length(to);
    s.l = to / d;
    s.energy /= 1.0 + light.linear * d + light.quadratic * d * d;
    s.distance = glm::length(light.position - p.origin);
  } else {
    s.l = -light.direction;
  }
  s.ndl = glm::dot(p.n, s.l);
  s.diffuse = p.diffuse * p.color * s.ndl;
  glm::dvec3 r = -s.l - 2.0 * glm::dot(-s.l, p.n) * p.n;
  s.highlight = glm::dot(r, -p.dir);
  return s;
}

uint64_t bits(double x) { return std::bit_cast<uint64_t>(x); }

glm::dvec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
}

LightLanes::Point random_point(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0), unit(0.0, 1.0);
  LightLanes::Point p;
  p.position = glm::dvec3(coordinate(rng), coordinate(rng), coordinate(rng));
  p.n = random_unit(rng);
  p.origin = p.position + 1e-4 * (1.0 + 20.0) * p.n;
  p.color = glm::dvec3(unit(rng), unit(rng), unit(rng));
  p.dir = random_unit(rng);
  p.diffuse = unit(rng);
  p.specular = unit(rng);
  p.shininess = 1.0 + 200.0 * unit(rng);
  p.self = int32_t(rng() % 8) - 1;
  return p;
}

std::vector<Light> test_lights() {
  Light point;
  point.position = glm::dvec3(2.3, 3.4, 1.6);
  point.color = glm::dvec3(1.0, 0.8, 0.55);
  point.intensity = 1.0;
  point.linear = 0.1;
  point.quadratic = 0.05;
  Light plain;  // no falloff
  plain.position = glm::dvec3(-5.0, 6.5, 6.0);
  plain.color = glm::dvec3(0.85, 0.9, 1.0);
  plain.intensity = 0.35;
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::dvec3(-0.55, -0.45, 0.7));
  sun.color = glm::dvec3(1.0, 0.94, 0.84);
  sun.intensity = 0.55;
  return {point, plain, sun};
}

TEST(LightLanes, EveryWidthGivesTheScalarBits) {
  const glm::dvec3 ambient(0.06, 0.07, 0.09), shadow_ambient(0.12, 0.12, 0.14);
  auto lanes = std::make_unique<LightLanes>();
  for (const int width : LightLanes::widths()) {
    lanes->use_width(width);
    for (const size_t count : {LightLanes::kCapacity, size_t(37), size_t(1)}) {
      std::mt19937_64 rng(20261207 + count);
      std::vector<LightLanes::Point> points;
      std::vector<glm::dvec3> sums;
      lanes->clear();
      for (size_t j = 0; j < count; ++j) {
        points.push_back(random_point(rng));
        EXPECT_EQ(lanes->add(points.back(), ambient), j);
        sums.push_back(ambient * points.back().color);
      }
      for (const Light& light : test_lights()) {
        lanes->light_terms(light);
        LightLanes::Arrays& a = lanes->arrays();
        for (size_t j = 0; j < count; ++j) {
          const ScalarTerms s = scalar_terms(light, points[j]);
          for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(bits(a.l[size_t(c)][j]), bits(s.l[c])) << "width " << width << " point " << j;
            ASSERT_EQ(bits(a.energy[size_t(c)][j]), bits(s.energy[c])) << "width " << width << " point " << j;
            ASSERT_EQ(bits(a.diffuse[size_t(c)][j]), bits(s.diffuse[c])) << "width " << width << " point " << j;
          }
          ASSERT_EQ(bits(a.distance[j]), bits(s.distance)) << "width " << width << " point " << j;
          ASSERT_EQ(bits(a.ndl[j]), bits(s.ndl)) << "width " << width << " point " << j;
          ASSERT_EQ(bits(a.highlight[j]), bits(s.highlight)) << "width " << width << " point " << j;
          ASSERT_EQ(a.blocked[j], 0.0);
          ASSERT_EQ(a.phong[j], 0.0);
          // What the shading sets before the sum: a shadow ray's answer and a Phong term.
          const bool blocked = rng() % 3 == 0;
          const double phong = rng() % 2 == 0 ? 0.0 : std::ldexp(double(rng() % 1000), -10);
          a.blocked[j] = blocked ? 1.0 : 0.0;
          a.phong[j] = phong;
          if (!(s.ndl > 0)) continue;  // the scalar shading skips such a light
          const glm::dvec3 visibility = blocked ? shadow_ambient : glm::dvec3(1.0);
          sums[j] += s.energy * visibility * (s.diffuse + phong);
        }
        lanes->accumulate(shadow_ambient);
      }
      for (size_t j = 0; j < count; ++j)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(bits(lanes->sum(j)[c]), bits(sums[j][c])) << "width " << width << " point " << j;
    }
  }
}

TEST(LightLanes, APointBehindItsLightKeepsItsSum) {
  // n faces away from the light: n.l = -1, so the light adds nothing.
  auto lanes = std::make_unique<LightLanes>();
  LightLanes::Point p{};
  p.position = glm::dvec3(0, 0, 0);
  p.n = glm::dvec3(0, -1, 0);
  p.origin = glm::dvec3(0, -1e-4, 0);
  p.color = glm::dvec3(0.5, 0.25, 1.0);
  p.dir = glm::dvec3(0, 1, 0);
  p.diffuse = 1.0;
  p.self = kMissId;
  lanes->add(p, glm::dvec3(0.5));
  Light above;
  above.position = glm::dvec3(0, 2, 0);
  lanes->light_terms(above);
  EXPECT_EQ(lanes->arrays().ndl[0], -1.0);
  EXPECT_EQ(lanes->arrays().distance[0], 2.0 + 1e-4);
  lanes->accumulate(glm::dvec3(0.1));
  EXPECT_EQ(lanes->sum(0), glm::dvec3(0.25, 0.125, 0.5));
}

}  // namespace
}  // namespace prism
