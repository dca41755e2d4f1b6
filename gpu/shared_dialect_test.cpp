// The shared dialect (prism/sdk/dialect.hpp): one source, instantiated in
// C++ in double (prism::sdk::f64) and float (prism::sdk::f32), is the same
// text the kernel generator splices into the GPU kernel.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "kernel_source.hpp"
#include "prism/scene_loader.hpp"
#include "prism/sdk/library.hpp"

namespace prism::gpu {
namespace {

TEST(SharedDialect, QuadraticRootsInBothPrecisions) {
  // t^2 - 3t + 2 = (t - 1)(t - 2): both roots exact in double and in float.
  double d0 = 0, d1 = 0;
  ASSERT_EQ(sdk::f64::prism_solve_quadratic(1.0, -3.0, 2.0, d0, d1), 2);
  EXPECT_EQ(d0, 1.0);
  EXPECT_EQ(d1, 2.0);
  float f0 = 0, f1 = 0;
  ASSERT_EQ(sdk::f32::prism_solve_quadratic(1.0f, -3.0f, 2.0f, f0, f1), 2);
  EXPECT_EQ(f0, 1.0f);
  EXPECT_EQ(f1, 2.0f);
  // a == 0 exactly is linear in both: 2t - 4 = 0.
  ASSERT_EQ(sdk::f32::prism_solve_quadratic(0.0f, 2.0f, -4.0f, f0, f1), 1);
  EXPECT_EQ(f0, 2.0f);
}

TEST(SharedDialect, SphereTestInBothPrecisions) {
  // A unit sphere seen from 5 away along +z: the near root is t = 4.
  double t = 0;
  ASSERT_TRUE(sdk::f64::prism_intersect_sphere({0, 0, -5}, {0, 0, 1}, 1.0, 0.0, 1e30, t));
  EXPECT_EQ(t, 4.0);
  float tf = 0;
  ASSERT_TRUE(sdk::f32::prism_intersect_sphere({0, 0, -5}, {0, 0, 1}, 1.0f, 0.0f, 1e30f, tf));
  EXPECT_EQ(tf, 4.0f);
  // Beyond tmax, and from inside (the far root, t = 1).
  EXPECT_FALSE(sdk::f32::prism_intersect_sphere({0, 0, -5}, {0, 0, 1}, 1.0f, 0.0f, 3.5f, tf));
  ASSERT_TRUE(sdk::f32::prism_intersect_sphere({0, 0, 0}, {0, 0, 1}, 1.0f, 0.0f, 1e30f, tf));
  EXPECT_EQ(tf, 1.0f);
}

std::string read_source_file(const std::string& path) {
  std::ifstream in(std::string(PRISM_SOURCE_DIR) + "/" + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SharedDialect, TheKernelCarriesTheTextTheCppInstantiates) {
  const std::string library = read_source_file("include/prism/sdk/modules/library.shared.glsl");
  ASSERT_NE(library.find("prism_solve_quadratic"), std::string::npos);
  Registry registry;
  Scene scene = load_scene_from_string(R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "objects": [{"type": "sphere", "radius": 1}]})", ".", registry);
  const std::string kernel = generate_kernel(pack_scene(scene), {}).text;
  EXPECT_NE(kernel.find(library), std::string::npos);
  EXPECT_NE(kernel.find("#define real double"), std::string::npos);
  EXPECT_NE(kernel.find("bool sphere_intersect(PrismRecord rec, PrismRay ray, real tmin, real tmax, OUT(PrismHit) hit)"),
            std::string::npos);
}

}  // namespace
}  // namespace prism::gpu
