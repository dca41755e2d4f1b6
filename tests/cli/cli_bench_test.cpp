// `prism bench`: the frames it times, the rays it counts, the memory and
// check it reports, its JSON, and its bad input. Figures of speed are not
// tested here (speed is measured, never asserted in a unit test).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bench/bench_run.hpp"
#include "cli_harness.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli_test {
namespace {

using nlohmann::json;

class Bench : public CliTest {
 protected:
  fs::path scene() {
    SceneText text;
    text.image = R"({"width": 32, "height": 24, "spp": 2, "max_depth": 3})";
    return write("scene.json", text.text());
  }
};

TEST_F(Bench, TimesFramesCountsRaysAndWritesJson) {
  const fs::path out = path("bench.json");
  RunResult r = run({"bench", scene().string(), "-b", "reference,embree", "--frames", "3", "--warmup", "1", "--spp",
                     "1", "--json", out.string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(r.out.find("reference"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FPS"), std::string::npos) << r.out;
  const json report = json::parse(read_file(out));
  EXPECT_EQ(report["image"]["width"], 32);
  EXPECT_EQ(report["image"]["spp"], 1);  // the override
  ASSERT_EQ(report["backends"].size(), 2u);
  for (const json& b : report["backends"]) {
    SCOPED_TRACE(b["backend"].get<std::string>());
    EXPECT_FALSE(b.contains("skipped"));
    EXPECT_EQ(b["frames"], 3);
    EXPECT_EQ(b["frame_ms"]["all"].size(), 3u);
    EXPECT_GT(b["frame_ms"]["median"].get<double>(), 0.0);
    // One camera ray per pixel and sample, over the 3 measured frames only.
    EXPECT_EQ(b["rays_by_kind"]["camera"], 3 * 32 * 24);
    EXPECT_GE(b["rays"].get<uint64_t>(), 3u * 32 * 24);
    // The last frame equals a fresh render of its camera.
    EXPECT_EQ(b["check_max_difference"], 0.0);
    const json& m = b["memory_bytes"];
    EXPECT_GT(m["loaded"].get<int64_t>(), 0);
    EXPECT_GE(m["peak"].get<int64_t>(), 0);
    EXPECT_EQ(m["frame"], 32 * 24 * 3 * 4);  // rgb floats
    EXPECT_GT(m["scene"].get<int64_t>(), 0);
    EXPECT_EQ(m["bound"], 4 * (m["scene"].get<int64_t>() + m["frame"].get<int64_t>()));
  }
}

TEST_F(Bench, BadInputExitsTwoAndWritesNothing) {
  const std::string s = scene().string();
  const std::string out = path("bench.json").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"bench", s, "--frames", "0", "--json", out}, "--frames"},
      {{"bench", s, "--warmup", "0", "--json", out}, "--warmup"},
      {{"bench", s, "-b", "nosuchbackend", "--json", out}, "nosuchbackend"},
      {{"bench", s, "--json", path("bench.txt").string()}, ".json"},
      {{"bench", path("missing.json").string(), "--json", out}, "missing.json"},
      {{"bench", s, "--width", "0", "--json", out}, "width"},
  };
  for (const auto& [args, message] : cases) {
    RunResult r = run(args);
    EXPECT_TRUE(ExitedWith(r, 2));
    EXPECT_TRUE(StderrHas(r, {message}));
  }
  EXPECT_EQ(list_folder(dir()), std::vector<std::string>{"scene.json"});
}

TEST_F(Bench, FrameCamerasOrbitTheViewersTargetAtTheGivenRate) {
  Registry registry;
  const Scene s = load_scene(scene(), registry);
  const bench::FrameCameras cameras(s, 90.0);
  // Frame 0 is the scene's camera bit for bit.
  EXPECT_EQ(cameras(0).position, s.camera.position);
  EXPECT_EQ(cameras(0).forward, s.camera.forward);
  // The scene looks from (0, 0, -5) at the origin with up +y: a quarter turn
  // about +y (right-handed) moves the camera to (-5, 0, 0), still aimed at
  // the origin; the warm-up direction (-1) goes the other way.
  const Camera quarter = cameras(1);
  EXPECT_NEAR(quarter.position.x, -5.0, 1e-12);
  EXPECT_NEAR(quarter.position.z, 0.0, 1e-12);
  EXPECT_NEAR(quarter.forward.x, 1.0, 1e-12);
  EXPECT_NEAR(cameras(-1).position.x, 5.0, 1e-12);
}

}  // namespace
}  // namespace prism::cli_test
