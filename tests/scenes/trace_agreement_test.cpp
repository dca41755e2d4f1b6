// `trace` on random rays agrees with the reference backend in double, per
// primitive (each primitive's objects come from its folder:
// tests/cases/primitive_cases.hpp) and per instantiation of its one source:
// C++ in float (the reference backend with --precision float), and every
// other backend in double and, where it has a float path, in float (the GPU
// backends' GLSL float instantiation). Each is held to the same object id on
// at least 99.9 % of rays and a relative t error whose 99th percentile is at
// most 1e-4 (the stability suite's float caps). Each primitive is rotated and
// off the origin; rays start 2 to 50 units away (and some inside the bounds)
// and aim at random points around the object, so hits, misses, silhouettes
// and rays from inside all occur.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "primitive_cases.hpp"
#include "prism/backend.hpp"
#include "prism/errors.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"
#include "test_support.hpp"

namespace prism::cases {
// gtest shows a case by its name (not its bytes).
void PrintTo(const AgreementCase& c, std::ostream* os) { *os << c.name; }
}  // namespace prism::cases

namespace {

using prism::cases::AgreementCase;

// Every primitive's agreement cases, from its folder (primitive_cases.hpp).
std::vector<AgreementCase> all_cases() {
  std::vector<AgreementCase> all;
  for (const prism::cases::PrimitiveCases* cases : prism::cases::all_primitive_cases())
    all.insert(all.end(), cases->agreement.begin(), cases->agreement.end());
  return all;
}

std::string scene_for(const AgreementCase& c) {
  std::string object = c.object;
  // Rotate the primitive (unless the case says not to) so the local frame is exercised.
  if (c.rotate)
    object.insert(object.size() - 1, R"(, "rotation": {"axis": [1, 2, 0.5], "degrees": 37})");
  return std::string(R"({"prism": 1, "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0]}, "objects": [)") +
         object + "]}";
}

std::vector<prism::TraceQuery> random_rays(const AgreementCase& c, int count) {
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
    if (c.aim && !inside) target = c.aim(centre, [&] { return unit(rng); });
    rays.push_back({origin, glm::normalize(target - origin), 0.0});
  }
  return rays;
}

// `backend`'s answers in `precision`; nullopt when it has no such path (the
// default Backend refuses float).
std::optional<std::vector<prism::TraceResult>> trace(prism::Registry& registry, const std::string& backend,
                                                     prism::Precision precision, const prism::Scene& scene,
                                                     const std::vector<prism::TraceQuery>& rays) {
  auto instance = registry.backend(backend)->create();
  try {
    instance->set_precision(precision);
  } catch (const prism::InputError&) {
    return std::nullopt;
  }
  instance->prepare(scene);
  return instance->trace(rays);
}

void expect_agreement(const std::vector<prism::TraceResult>& expected, const std::vector<prism::TraceResult>& actual,
                      const std::string& what) {
  ASSERT_EQ(actual.size(), expected.size());
  size_t same_id = 0, hits = 0;
  std::vector<double> t_errors;
  for (size_t i = 0; i < expected.size(); ++i) {
    hits += expected[i].id >= 0;
    if (actual[i].id != expected[i].id) continue;
    ++same_id;
    if (expected[i].id >= 0) t_errors.push_back(std::abs(actual[i].t - expected[i].t) / expected[i].t);
  }
  std::sort(t_errors.begin(), t_errors.end());
  const double p99 = t_errors.empty() ? 0.0 : t_errors[size_t(0.99 * double(t_errors.size() - 1))];
  std::printf("%s: %zu hits of %zu rays, id agreement %.4f %%, relative t error p99 %.3g, max %.3g\n", what.c_str(), hits,
              expected.size(), 100.0 * double(same_id) / double(expected.size()), p99,
              t_errors.empty() ? 0.0 : t_errors.back());
  EXPECT_GT(hits, expected.size() / 10) << what << ": too few hits to measure anything";
  EXPECT_GE(double(same_id), 0.999 * double(expected.size())) << what;
  EXPECT_LE(p99, 1e-4) << what;
}

class TraceAgreement : public testing::TestWithParam<std::tuple<std::string, AgreementCase>> {};

TEST_P(TraceAgreement, MatchesReferenceOnRandomRays) {
  const auto& [backend, primitive] = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  prism::Registry registry;
  prism::Scene scene = prism::load_scene_from_string(scene_for(primitive), ".", registry);
  const auto rays = random_rays(primitive, 20000);
  const auto expected = trace(registry, "reference", prism::Precision::float64, scene, rays).value();
  if (backend != "reference")
    expect_agreement(expected, trace(registry, backend, prism::Precision::float64, scene, rays).value(),
                     primitive.name + " on " + backend + " in double");
  const PrismPrimitiveDesc& type = *scene.objects[0].desc;
  if (type.intersect_float == type.intersect) {  // ABI 4: no float instantiation (not in the shared dialect)
    std::printf("%s has no float instantiation to measure\n", type.type_name);
  } else if (auto in_float = trace(registry, backend, prism::Precision::float32, scene, rays)) {
    expect_agreement(expected, *in_float, primitive.name + " on " + backend + " in float");
  } else {
    std::printf("%s computes in double only: no float instantiation to measure\n", backend.c_str());
  }
}

std::string name_of(const testing::TestParamInfo<TraceAgreement::ParamType>& info) {
  std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param).name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Primitives, TraceAgreement,
                         testing::Combine(testing::ValuesIn(prism::test::backend_names()),
                                          testing::ValuesIn(all_cases())),
                         name_of);

}  // namespace
