// `prism plugin check FILE.so`: the descriptor it prints, the self-test of a
// plugin's CPU intersector against every backend, and what it refuses.
#include <gtest/gtest.h>

#include "cli_harness.hpp"
#include "prism/registry.hpp"

namespace prism::cli_test {
namespace {

fs::path built_plugin(const std::string& type) {
  return default_plugin_folder() / ("libprism_primitive_" + type + ".so");
}

class PluginCheck : public CliTest {};

TEST_F(PluginCheck, PrintsTheDescriptorAndPassesOnEmbree) {
  RunResult r = run({"plugin", "check", built_plugin("torus").string(), "-b", "embree"});
  ASSERT_TRUE(ExitedWith(r, 0));
  for (const char* part : {"torus 1.0.0 (ABI 6)", "transformable", "refine: yes", "GLSL: yes (prefix torus",
                           "major_radius", "minor_radius", "required", "embree (double): ids agree on 100.000 %",
                           "PASS"})
    EXPECT_NE(r.out.find(part), std::string::npos) << part << "\n" << r.out;
  EXPECT_EQ(r.out.find("FAIL"), std::string::npos) << r.out;
}

// Every plugin built, so a new one is covered without an edit here: its
// packet entries and its occlusion test (ABI 6) answer each lane exactly as
// its scalar intersector does,
// on random lanes and bounds, rays from inside and grazing rays; and its
// surface asked for no uv (PRISM_HIT_SKIP_UV) gives the same t, point and
// normal, bit for bit, on those rays' hits.
class PacketEntries : public CliTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(PacketEntries, AgreeWithTheScalarIntersectorBitForBit) {
  RunResult r = run({"plugin", "check", built_plugin(GetParam()).string(), "-b", "reference", "--rays", "600"});
  ASSERT_TRUE(ExitedWith(r, 0)) << r.out;
  EXPECT_NE(r.out.find("packet entries: agree with intersect bit for bit"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("surface without uv: the same t, point and normal bit for bit"), std::string::npos) << r.out;
  // The same run measures the float entry: within the float caps, or the
  // double one standing in for a plugin without a float instantiation.
  EXPECT_TRUE(contains_any(r.out, "float entry: within the float caps|float entry: the double intersector stands in"))
      << r.out;
  // Its bounding sphere (ABI 5; the box's without one) holds every hit
  // point, or the primitive is unbounded.
  EXPECT_TRUE(contains_any(r.out, "): holds every hit point on|bounding sphere: none (unbounded)")) << r.out;
}

// Every plugin built carries the float entry (ABI 4), and one written in the
// shared dialect (its GLSL is its C++ source) has a float instantiation of
// its own there.
class FloatEntry : public ::testing::TestWithParam<std::string> {};

TEST_P(FloatEntry, IsPresentInTheDescriptor) {
  std::string error;
  auto plugin = load_primitive_plugin(built_plugin(GetParam()), error);
  ASSERT_TRUE(plugin) << error;
  const PrismPrimitiveDesc& d = plugin->desc();
  EXPECT_EQ(d.abi_version, 6u);
  ASSERT_NE(d.intersect_float, nullptr);
  const bool shared_dialect = d.glsl_source && std::string(d.glsl_source).find("OUT(PrismHit)") != std::string::npos;
  if (shared_dialect) {
    EXPECT_NE(d.intersect_float, d.intersect);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPlugin, FloatEntry, ::testing::ValuesIn(primitives_built()),
                         [](const auto& info) { return info.param; });

INSTANTIATE_TEST_SUITE_P(EveryPlugin, PacketEntries, ::testing::ValuesIn(primitives_built()),
                         [](const auto& info) { return info.param; });

TEST_F(PluginCheck, PassesOnEveryGpuBackendBuilt) {
  for (const std::string& backend : backends_built()) {
    if (backend != "opengl" && backend != "vulkan") continue;
    SCOPED_TRACE(backend);
    RunResult r = run({"plugin", "check", built_plugin("sphere").string(), "-b", backend, "--rays", "500"});
    if (r.out.find("skipped, cannot run here") != std::string::npos) continue;  // PRISM_REQUIRE_BACKENDS guards CI
    EXPECT_TRUE(ExitedWith(r, 0));
    EXPECT_NE(r.out.find(backend + " (double geometry, float32 shading): ids agree on 100.000 %"), std::string::npos)
        << r.out;
    // The GLSL float instantiation of the same source, held to the float caps.
    EXPECT_NE(r.out.find(backend + " (float): ids agree on 100.000 %"), std::string::npos) << r.out;
  }
}

TEST_F(PluginCheck, WrongBoundsFailOnEmbree) {
  // The fixture's bounds are half its size: Embree culls rays the plugin would hit.
  RunResult r = run({"plugin", "check", (bad_plugin_folder() / "libprism_primitive_badbounds.so").string(), "-b",
                     "embree"});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
}

TEST_F(PluginCheck, APacketEntryThatDropsALaneFails) {
  RunResult r = run({"plugin", "check", (bad_plugin_folder() / "libprism_primitive_badpacket.so").string(), "-b",
                     "reference", "--rays", "200"});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_NE(r.out.find("packet entries: FAIL: disagree with intersect"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("intersect_packet differs for the ray from"), std::string::npos) << r.out;
}

TEST_F(PluginCheck, BadInputExitsTwo) {
  RunResult wrong_abi = run({"plugin", "check", (bad_plugin_folder() / "libprism_primitive_wrongabi.so").string()});
  EXPECT_TRUE(ExitedWith(wrong_abi, 2));
  EXPECT_TRUE(StderrHas(wrong_abi, {"not a usable primitive plugin", "ABI version 999"}));

  RunResult missing = run({"plugin", "check", path("nothing.so").string()});
  EXPECT_TRUE(ExitedWith(missing, 2));
  EXPECT_TRUE(StderrHas(missing, {"nothing.so"}));

  RunResult invalid = run({"plugin", "check", built_plugin("ring").string(), "-b", "embree", "--object",
                           R"({"inner_radius": 3, "outer_radius": 1})"});
  EXPECT_TRUE(ExitedWith(invalid, 2));
  EXPECT_TRUE(StderrHas(invalid, {"objects[0].outer_radius", "--object"}));

  RunResult not_json = run({"plugin", "check", built_plugin("ring").string(), "--object", "{oops"});
  EXPECT_TRUE(ExitedWith(not_json, 2));
  EXPECT_TRUE(StderrHas(not_json, {"--object"}));
}

}  // namespace
}  // namespace prism::cli_test
