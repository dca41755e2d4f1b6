// The keys of BackendStats (prism/stats_keys.hpp) are what `--stats` JSON,
// `prism bench` and the Python module's stats() show: renaming a constant's
// value is a change of that format, not a refactoring.
#include <gtest/gtest.h>

#include <iterator>

#include "prism/stats_keys.hpp"

namespace prism {
namespace {

TEST(StatsKeys, RayKindsAreSpeltAsTheStatsShowThem) {
  ASSERT_EQ(std::size(kRayKindNames), 6u);
  EXPECT_STREQ(kRayKindNames[0], "camera");
  EXPECT_STREQ(kRayKindNames[5], "shade1");
  EXPECT_STREQ(ray_kind::kTrace, "trace");
}

TEST(StatsKeys, PhasesAreSpeltAsTheStatsShowThem) {
  EXPECT_STREQ(ms_key::kBuild, "build");
  EXPECT_STREQ(ms_key::kUpdate, "update");
  EXPECT_STREQ(ms_key::kCompile, "compile");
  EXPECT_STREQ(ms_key::kRender, "render");
  EXPECT_STREQ(ms_key::kProfilePrefix, "profile.");
}

TEST(StatsKeys, CountersAndInfoAreSpeltAsTheStatsShowThem) {
  EXPECT_STREQ(counter::kSceneBytes, "scene_bytes");
  EXPECT_STREQ(counter::kKernelBuilds, "kernel_builds");
  EXPECT_STREQ(counter::kGlCompileShaderCalls, "gl_compile_shader_calls");
  EXPECT_STREQ(counter::kFirstDispatchMs, "first_dispatch_ms");
  EXPECT_STREQ(info_key::kPrecision, "precision");
  EXPECT_STREQ(info_key::kProgramCache, "program_cache");
}

}  // namespace
}  // namespace prism
